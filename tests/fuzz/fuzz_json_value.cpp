// SPDX-License-Identifier: MIT
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_entries.h"
#include "rewind/server/agones_sdk.h"
#include "rewind/server/json_value.h"

namespace {

using rwd::server::JsonValue;

[[noreturn]] void invariant_broken(const char* what) {
  std::fprintf(stderr, "fuzz_json_value: invariant broken: %s\n", what);
  std::abort();
}

void write_string(const std::string& text, std::string& out) {
  out += '"';
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", byte);
      out += escape;
    } else {
      out += c;
    }
  }
  out += '"';
}

// Canonical text of a parsed value: what the reader must read back equal.
void write(const JsonValue& value, std::string& out) {
  switch (value.kind()) {
    case JsonValue::Kind::kNull:
      out += "null";
      return;
    case JsonValue::Kind::kBool:
      out += value.as_bool() ? "true" : "false";
      return;
    case JsonValue::Kind::kNumber: {
      char text[40];
      std::snprintf(text, sizeof text, "%.17g", value.as_number());
      out += text;
      return;
    }
    case JsonValue::Kind::kString:
      write_string(value.as_string(), out);
      return;
    case JsonValue::Kind::kArray:
    case JsonValue::Kind::kObject: {
      const bool object = value.is(JsonValue::Kind::kObject);
      out += object ? '{' : '[';
      for (size_t i = 0; i < value.items().size(); ++i) {
        if (i > 0) out += ',';
        if (object) {
          write_string(value.keys()[i], out);
          out += ':';
        }
        write(value.items()[i], out);
      }
      out += object ? '}' : ']';
      return;
    }
  }
}

bool finite_everywhere(const JsonValue& value) {
  if (value.is(JsonValue::Kind::kNumber) && !std::isfinite(value.as_number())) return false;
  for (const JsonValue& item : value.items()) {
    if (!finite_everywhere(item)) return false;
  }
  return true;
}

}  // namespace

int fuzz_json_value_one(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  rwd::server::JsonLimits limits;
  limits.max_depth = 8;  // small, so the fuzzer reaches the bound
  auto parsed = rwd::server::parse_json(text, limits);
  // The GameServer reader sees the same bytes: it may refuse them, never crash.
  auto game_server = rwd::server::parse_agones_game_server(text);
  if (!game_server.ok() && game_server.status().message().empty()) {
    invariant_broken("GameServer error without message");
  }
  if (!parsed.ok()) {
    if (parsed.status().code() != rwd::ErrorCode::kCorrupt) invariant_broken("error not kCorrupt");
    if (parsed.status().message().empty()) invariant_broken("error without message");
    return 0;
  }
  if (!finite_everywhere(*parsed)) invariant_broken("accepted a non-finite number");
  // Whatever the reader accepts, its canonical text must read back equal.
  std::string again;
  write(*parsed, again);
  auto round = rwd::server::parse_json(again, limits);
  if (!round.ok()) invariant_broken("canonical text of an accepted value refused");
  if (!(*round == *parsed)) invariant_broken("round trip changed the value");
  return 0;
}
