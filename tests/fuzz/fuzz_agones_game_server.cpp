// SPDX-License-Identifier: MIT
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <string_view>

#include "fuzz_entries.h"
#include "rewind/server/agones_game_server.h"
#include "rewind/server/agones_match_settings.h"
#include "rewind/server/match_config.h"

namespace {

using rwd::server::AgonesGameServer;

[[noreturn]] void invariant_broken(const char* what) {
  std::fprintf(stderr, "fuzz_agones_game_server: invariant broken: %s\n", what);
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
      out += c;  // accepted strings are valid UTF-8
    }
  }
  out += '"';
}

void write_map(const std::map<std::string, std::string>& entries, std::string& out) {
  out += '{';
  for (const auto& [key, value] : entries) {
    if (out.back() != '{') out += ',';
    write_string(key, out);
    out += ':';
    write_string(value, out);
  }
  out += '}';
}

// The record as a GameServer document: what the reader must read back equal.
std::string write(const AgonesGameServer& gs) {
  std::string out = "{\"object_meta\":{\"name\":";
  write_string(gs.name, out);
  out += ",\"labels\":";
  write_map(gs.labels, out);
  out += ",\"annotations\":";
  write_map(gs.annotations, out);
  out += "},\"status\":{\"state\":";
  write_string(gs.state, out);
  out += ",\"address\":";
  write_string(gs.address, out);
  out += ",\"ports\":[";
  for (const AgonesGameServer::Port& port : gs.ports) {
    if (out.back() != '[') out += ',';
    out += "{\"name\":";
    write_string(port.name, out);
    out += ",\"port\":" + std::to_string(port.port) + "}";
  }
  out += "]}}";
  return out;
}

// The fields an allocation may set (MatchConfig has no operator==).
bool same_settings(const rwd::server::MatchConfig& a, const rwd::server::MatchConfig& b) {
  return a.game == b.game && a.players == b.players && a.start_players == b.start_players &&
         a.max_spectators == b.max_spectators && a.tick_rate_hz == b.tick_rate_hz &&
         a.window_ticks == b.window_ticks && a.max_ticks == b.max_ticks && a.seed == b.seed &&
         a.match_id == b.match_id && a.join_timeout_s == b.join_timeout_s &&
         a.peer_timeout_s == b.peer_timeout_s;
}

bool printable(const std::string& text) {
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) {
      return false;
    }
  }
  return true;
}

}  // namespace

int fuzz_agones_game_server_one(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto gs = rwd::server::parse_agones_game_server(text);
  if (!gs.ok()) {
    if (gs.status().code() != rwd::ErrorCode::kCorrupt) invariant_broken("error not kCorrupt");
    if (gs.status().message().empty()) invariant_broken("error without message");
    if (!printable(gs.status().message())) invariant_broken("error message not printable");
    return 0;
  }
  for (const AgonesGameServer::Port& port : gs->ports) {
    if (port.port < 0 || port.port > 65535) invariant_broken("port out of range");
  }
  // The allocation's match settings: applied whole and valid, or refused
  // leaving the configuration as it was.
  rwd::server::MatchConfig match;
  const rwd::server::MatchConfig before = match;
  auto applied = rwd::server::apply_agones_match_settings(*gs, &match);
  if (applied.ok()) {
    if (!match.validate().ok()) invariant_broken("applied settings do not validate");
  } else {
    if (applied.status().code() != rwd::ErrorCode::kInvalidArgument) {
      invariant_broken("settings error not kInvalidArgument");
    }
    if (applied.status().message().empty()) invariant_broken("settings error without message");
    if (!same_settings(match, before))
      invariant_broken("refused settings changed the configuration");
  }
  // Whatever the reader accepts, written back as a document, reads back equal.
  auto round = rwd::server::parse_agones_game_server(write(*gs));
  if (!round.ok()) invariant_broken("the record written back is refused");
  if (!(*round == *gs)) invariant_broken("round trip changed the record");
  return 0;
}
