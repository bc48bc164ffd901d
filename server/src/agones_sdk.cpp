// SPDX-License-Identifier: MIT
#include "rewind/server/agones_sdk.h"

#include <cmath>

#include "rewind/server/http_client.h"
#include "rewind/server/json_value.h"

namespace rwd::server {
namespace {

using Kind = JsonValue::Kind;

Status corrupt(const std::string& what) {
  return Status::Error(ErrorCode::kCorrupt, "GameServer: " + what);
}

// `parent[key]` if present; a present member of another kind is an error.
Result<const JsonValue*> member(const JsonValue& parent, std::string_view key, Kind kind,
                                std::string_view path) {
  const JsonValue* value = parent.find(key);
  if (value == nullptr || value->is(Kind::kNull)) return static_cast<const JsonValue*>(nullptr);
  if (!value->is(kind)) {
    return corrupt(std::string(path) + " is a " + std::string(json_kind_name(value->kind())) +
                   ", not a " + std::string(json_kind_name(kind)));
  }
  return value;
}

Status read_string(const JsonValue& parent, std::string_view key, std::string_view path,
                   std::string* out) {
  auto value = member(parent, key, Kind::kString, path);
  if (!value.ok()) return value.status();
  if (*value != nullptr) *out = (*value)->as_string();
  return Status::Ok();
}

Status read_string_map(const JsonValue& parent, std::string_view key, std::string_view path,
                       std::map<std::string, std::string>* out) {
  auto value = member(parent, key, Kind::kObject, path);
  if (!value.ok()) return value.status();
  if (*value == nullptr) return Status::Ok();
  const JsonValue& object = **value;
  for (size_t i = 0; i < object.keys().size(); ++i) {
    const JsonValue& item = object.items()[i];
    if (!item.is(Kind::kString)) {
      return corrupt(std::string(path) + "[\"" + object.keys()[i] + "\"] is not a string");
    }
    (*out)[object.keys()[i]] = item.as_string();
  }
  return Status::Ok();
}

// A port number: a JSON number, or a decimal string (how proto3 JSON may
// write integers).
Result<int64_t> read_port(const JsonValue& value) {
  if (value.is(Kind::kNumber)) {
    const double n = value.as_number();
    if (n >= 0 && n <= 65535 && std::floor(n) == n) return static_cast<int64_t>(n);
  } else if (value.is(Kind::kString)) {
    const std::string& text = value.as_string();
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

}  // namespace

Result<AgonesGameServer> parse_agones_game_server(std::string_view json) {
  auto document = parse_json(json);
  if (!document.ok()) return corrupt(document.status().message());
  if (!document->is(Kind::kObject)) return corrupt("the document is not an object");
  AgonesGameServer out;

  auto meta = member(*document, "object_meta", Kind::kObject, "object_meta");
  if (!meta.ok()) return meta.status();
  if (*meta != nullptr) {
    const JsonValue& m = **meta;
    if (Status s = read_string(m, "name", "object_meta.name", &out.name); !s.ok()) return s;
    if (Status s = read_string_map(m, "labels", "object_meta.labels", &out.labels); !s.ok()) {
      return s;
    }
    if (Status s = read_string_map(m, "annotations", "object_meta.annotations", &out.annotations);
        !s.ok()) {
      return s;
    }
  }

  auto status = member(*document, "status", Kind::kObject, "status");
  if (!status.ok()) return status.status();
  if (*status != nullptr) {
    const JsonValue& st = **status;
    if (Status s = read_string(st, "state", "status.state", &out.state); !s.ok()) return s;
    if (Status s = read_string(st, "address", "status.address", &out.address); !s.ok()) return s;
    auto ports = member(st, "ports", Kind::kArray, "status.ports");
    if (!ports.ok()) return ports.status();
    if (*ports != nullptr) {
      for (const JsonValue& entry : (*ports)->items()) {
        if (!entry.is(Kind::kObject)) return corrupt("status.ports[] is not an object");
        AgonesGameServer::Port port;
        if (Status s = read_string(entry, "name", "status.ports[].name", &port.name); !s.ok()) {
          return s;
        }
        if (const JsonValue* number = entry.find("port"); number != nullptr) {
          auto value = read_port(*number);
          if (!value.ok()) return value.status();
          port.port = *value;
        }
        out.ports.push_back(std::move(port));
      }
    }
  }
  return out;
}

Result<uint16_t> agones_port_from_env(const char* value) {
  if (value == nullptr) return kAgonesDefaultHttpPort;
  const std::string_view text(value);
  uint32_t port = 0;
  bool valid = !text.empty() && text.size() <= 5;
  for (const char c : text) {
    if (c < '0' || c > '9') valid = false;
    if (valid) port = port * 10 + static_cast<uint32_t>(c - '0');
  }
  if (!valid || port < 1 || port > 65535) {
    return Status::Error(ErrorCode::kInvalidArgument, "AGONES_SDK_HTTP_PORT='" + std::string(text) +
                                                          "' is not a port number in [1, 65535]");
  }
  return static_cast<uint16_t>(port);
}

Result<std::string> AgonesSdk::call(std::string_view method, std::string_view path) const {
  HttpRequest request;
  request.method = std::string(method);
  request.target = std::string(path);
  // The REST gateway's lifecycle calls take an empty message.
  if (method != "GET") request.body = "{}";
  HttpCallLimits limits;
  limits.deadline = options_.call_deadline;
  auto response = http_call(options_.host, options_.port, request, limits);
  if (!response.ok()) return response.status();
  if (response->status < 200 || response->status > 299) {
    std::string body = response->body.substr(0, 200);
    for (char& c : body) {
      if (static_cast<unsigned char>(c) < 0x20) c = ' ';
    }
    return Status::Error(ErrorCode::kIo, std::string(method) + " " + std::string(path) + ": HTTP " +
                                             std::to_string(response->status) + " " +
                                             response->reason + (body.empty() ? "" : ": " + body));
  }
  return std::move(response->body);
}

Status AgonesSdk::ready() const {
  return call("POST", "/ready").status();
}

Status AgonesSdk::health() const {
  return call("POST", "/health").status();
}

Status AgonesSdk::shutdown() const {
  return call("POST", "/shutdown").status();
}

Result<AgonesGameServer> AgonesSdk::game_server() const {
  auto body = call("GET", "/gameserver");
  if (!body.ok()) return body.status();
  return parse_agones_game_server(*body);
}

}  // namespace rwd::server
