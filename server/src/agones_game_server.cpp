// SPDX-License-Identifier: MIT
#include "rewind/server/agones_game_server.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

namespace rwd::server {
namespace {

using Json = nlohmann::json;

Status corrupt(const std::string& what) {
  return Status::Error(ErrorCode::kCorrupt, "GameServer: " + what);
}

// nlohmann's messages quote the bytes where parsing stopped; anything but
// printable ASCII there is shown as '?', so a document cannot forge or
// garble the log line its error ends up in.
std::string printable(std::string_view text) {
  std::string out(text.substr(0, 300));
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  }
  return text.size() > 300 ? out + "..." : out;
}

// "[json.exception.parse_error.101] parse error at line 1, column 2: ...":
// the text after the exception's id.
std::string describe(const Json::exception& error) {
  std::string_view text = error.what();
  if (const size_t id_end = text.find("] "); text.front() == '[' && id_end != text.npos) {
    text.remove_prefix(id_end + 2);
  }
  return printable(text);
}

// Thrown from the parser's callback to stop at the first refusal.
struct Refused {
  std::string what;
};

// nlohmann's parser keeps the last of duplicate keys and has no depth bound
// of its own (it is iterative, but the tree it builds is not bounded): its
// callback sees every event in document order, so both are checked there,
// with the keys seen so far in each object still open.
class StrictnessCheck {
 public:
  bool operator()(int depth, Json::parse_event_t event, const Json& parsed) {
    switch (event) {
      case Json::parse_event_t::object_start:
      case Json::parse_event_t::array_start:
        // `depth` counts the containers around this one.
        if (depth + 1 > kAgonesGameServerMaxDepth) {
          throw Refused{"nesting deeper than " + std::to_string(kAgonesGameServerMaxDepth)};
        }
        if (event == Json::parse_event_t::object_start) open_keys_.emplace_back();
        break;
      case Json::parse_event_t::object_end:
        open_keys_.pop_back();
        break;
      case Json::parse_event_t::key:
        if (!open_keys_.back().insert(parsed.get_ref<const std::string&>()).second) {
          throw Refused{"duplicate key \"" + printable(parsed.get_ref<const std::string&>()) +
                        "\" in an object"};
        }
        break;
      case Json::parse_event_t::array_end:
      case Json::parse_event_t::value:
        break;
    }
    return true;  // keep everything: the reader below picks what it uses
  }

 private:
  std::vector<std::set<std::string, std::less<>>> open_keys_;
};

Result<Json> parse_document(std::string_view text) {
  if (text.size() > kAgonesGameServerMaxBytes) {
    return corrupt("JSON: " + std::to_string(text.size()) + " bytes, more than the limit of " +
                   std::to_string(kAgonesGameServerMaxBytes));
  }
  StrictnessCheck check;
  try {
    return Json::parse(
        text.begin(), text.end(),
        [&check](int depth, Json::parse_event_t event, Json& parsed) {
          return check(depth, event, parsed);
        },
        /*allow_exceptions=*/true, /*ignore_comments=*/false);
  } catch (const Refused& refused) {
    return corrupt("JSON: " + refused.what);
  } catch (const Json::exception& error) {
    return corrupt("JSON: " + describe(error));
  }
}

// "an object", "a string".
std::string with_article(std::string_view type_name) {
  const bool vowel = type_name.front() == 'a' || type_name.front() == 'o';
  return (vowel ? "an " : "a ") + std::string(type_name);
}

// `parent[key]` if present and not null; a member of another type is an
// error. `parent` is an object.
Result<const Json*> member(const Json& parent, std::string_view key, Json::value_t type,
                           std::string_view path) {
  const auto found = parent.find(key);
  if (found == parent.end() || found->is_null()) return static_cast<const Json*>(nullptr);
  if (found->type() != type) {
    return corrupt(std::string(path) + " is " + with_article(found->type_name()) + ", not " +
                   with_article(Json(type).type_name()));
  }
  return &*found;
}

Status read_string(const Json& parent, std::string_view key, std::string_view path,
                   std::string* out) {
  auto value = member(parent, key, Json::value_t::string, path);
  if (!value.ok()) return value.status();
  if (*value != nullptr) *out = (*value)->get_ref<const std::string&>();
  return Status::Ok();
}

Status read_string_map(const Json& parent, std::string_view key, std::string_view path,
                       std::map<std::string, std::string>* out) {
  auto value = member(parent, key, Json::value_t::object, path);
  if (!value.ok()) return value.status();
  if (*value == nullptr) return Status::Ok();
  for (const auto& [name, item] : (*value)->items()) {
    if (!item.is_string()) {
      return corrupt(std::string(path) + "[\"" + printable(name) + "\"] is not a string");
    }
    (*out)[name] = item.get_ref<const std::string&>();
  }
  return Status::Ok();
}

// A port number: a JSON number with an integral value, or a decimal string
// (how proto3 JSON may write integers).
Result<int64_t> read_port(const Json& value) {
  if (value.is_number_unsigned()) {
    const auto n = value.get<uint64_t>();
    if (n <= 65535) return static_cast<int64_t>(n);
  } else if (value.is_number_float()) {
    const double n = value.get<double>();
    if (n >= 0 && n <= 65535 && std::floor(n) == n) return static_cast<int64_t>(n);
  } else if (value.is_string()) {
    const std::string& text = value.get_ref<const std::string&>();
    int64_t port = 0;
    bool digits = !text.empty() && text.size() <= 5;
    for (const char c : text) {
      digits = digits && c >= '0' && c <= '9';
      if (digits) port = port * 10 + (c - '0');
    }
    if (digits && port <= 65535) return port;
  }
  return corrupt("status.ports[].port is not a port number in [0, 65535]");
}

Status read_ports(const Json& ports, std::vector<AgonesGameServer::Port>* out) {
  for (const Json& entry : ports) {
    if (!entry.is_object()) return corrupt("status.ports[] is not an object");
    AgonesGameServer::Port port;
    if (Status s = read_string(entry, "name", "status.ports[].name", &port.name); !s.ok()) {
      return s;
    }
    if (const auto number = entry.find("port"); number != entry.end() && !number->is_null()) {
      auto value = read_port(*number);
      if (!value.ok()) return value.status();
      port.port = *value;
    }
    out->push_back(std::move(port));
  }
  return Status::Ok();
}

}  // namespace

Result<AgonesGameServer> parse_agones_game_server(std::string_view json) {
  auto document = parse_document(json);
  if (!document.ok()) return document.status();
  if (!document->is_object()) return corrupt("the document is not an object");
  AgonesGameServer out;

  auto meta = member(*document, "object_meta", Json::value_t::object, "object_meta");
  if (!meta.ok()) return meta.status();
  if (*meta != nullptr) {
    const Json& m = **meta;
    if (Status s = read_string(m, "name", "object_meta.name", &out.name); !s.ok()) return s;
    if (Status s = read_string_map(m, "labels", "object_meta.labels", &out.labels); !s.ok()) {
      return s;
    }
    if (Status s = read_string_map(m, "annotations", "object_meta.annotations", &out.annotations);
        !s.ok()) {
      return s;
    }
  }

  auto status = member(*document, "status", Json::value_t::object, "status");
  if (!status.ok()) return status.status();
  if (*status != nullptr) {
    const Json& st = **status;
    if (Status s = read_string(st, "state", "status.state", &out.state); !s.ok()) return s;
    if (Status s = read_string(st, "address", "status.address", &out.address); !s.ok()) return s;
    auto ports = member(st, "ports", Json::value_t::array, "status.ports");
    if (!ports.ok()) return ports.status();
    if (*ports != nullptr) {
      if (Status s = read_ports(**ports, &out.ports); !s.ok()) return s;
    }
  }
  return out;
}

}  // namespace rwd::server
