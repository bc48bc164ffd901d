// SPDX-License-Identifier: MIT
#include "rewind/server/agones_match_settings.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <system_error>

namespace rwd::server {
namespace {

// A value as it goes into a log line: control characters shown as '?' and
// at most 64 characters, so an allocation cannot forge or flood log lines.
std::string printable(const std::string& value) {
  std::string out = value.substr(0, 64);
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return value.size() > 64 ? out + "..." : out;
}

Status refuse(const std::string& key, const std::string& value, const std::string& why) {
  return Status::Error(ErrorCode::kInvalidArgument, std::string(kAgonesSettingPrefix) + key +
                                                        ": '" + printable(value) + "' " + why);
}

// Decimal integer, no sign, spaces or other characters, within [min, max].
Result<int64_t> parse_integer(const std::string& key, const std::string& value, int64_t min,
                              int64_t max) {
  int64_t n = 0;
  const char* last = value.data() + value.size();
  const auto [end, error] = std::from_chars(value.data(), last, n);
  if (value.empty() || value.front() == '-' || error != std::errc() || end != last) {
    if (error == std::errc::result_out_of_range) {
      return refuse(key, value,
                    "is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    }
    return refuse(key, value, "is not an integer");
  }
  if (n < min || n > max) {
    return refuse(key, value,
                  "is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  }
  return n;
}

// "0.1", "3600": a bound as the flags' help shows it.
std::string decimal(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// Decimal number (fixed or exponent form), finite, within [min, max].
Result<double> parse_seconds(const std::string& key, const std::string& value, double min,
                             double max) {
  double n = 0;
  const char* last = value.data() + value.size();
  const auto [end, error] = std::from_chars(value.data(), last, n);
  if (value.empty() || error != std::errc() || end != last || !std::isfinite(n)) {
    return refuse(key, value, "is not a number of seconds");
  }
  if (!(n >= min && n <= max)) {
    return refuse(key, value, "is outside [" + decimal(min) + ", " + decimal(max) + "] s");
  }
  return n;
}

Status check_match_id(const std::string& key, const std::string& value) {
  if (!is_match_id(value)) {
    return refuse(key, value, "must be 1-64 characters of A-Z a-z 0-9 . _ -");
  }
  return Status::Ok();
}

using Setter =
    std::function<Status(const std::string& key, const std::string& value, MatchConfig* match)>;

Setter integer(int64_t min, int64_t max, std::function<void(MatchConfig*, int64_t)> assign) {
  return [=](const std::string& key, const std::string& value, MatchConfig* match) {
    auto n = parse_integer(key, value, min, max);
    if (!n.ok()) return n.status();
    assign(match, *n);
    return Status::Ok();
  };
}

Setter seconds(double min, double max, double MatchConfig::*field) {
  return [=](const std::string& key, const std::string& value, MatchConfig* match) {
    auto n = parse_seconds(key, value, min, max);
    if (!n.ok()) return n.status();
    match->*field = *n;
    return Status::Ok();
  };
}

// The ranges are rewind-server's flags' (server/src/server_main.cpp).
const std::map<std::string, Setter, std::less<>>& setters() {
  static const std::map<std::string, Setter, std::less<>> table = {
      {"game",
       [](const std::string&, const std::string& value, MatchConfig* match) {
         match->game = value;  // MatchConfig::validate() names the known games
         return Status::Ok();
       }},
      {"players",
       integer(1, 32, [](MatchConfig* m, int64_t n) { m->players = static_cast<uint32_t>(n); })},
      {"spectators",
       integer(0, 63,
               [](MatchConfig* m, int64_t n) { m->max_spectators = static_cast<uint32_t>(n); })},
      {"tick-rate",
       integer(1, 1000,
               [](MatchConfig* m, int64_t n) { m->tick_rate_hz = static_cast<uint32_t>(n); })},
      {"start-players",
       integer(0, 32,
               [](MatchConfig* m, int64_t n) { m->start_players = static_cast<uint32_t>(n); })},
      {"window",
       integer(1, 120,
               [](MatchConfig* m, int64_t n) { m->window_ticks = static_cast<int32_t>(n); })},
      {"ticks", integer(0, int64_t{1} << 31, [](MatchConfig* m, int64_t n) { m->max_ticks = n; })},
      {"seed", integer(0, INT64_MAX,
                       [](MatchConfig* m, int64_t n) { m->seed = static_cast<uint64_t>(n); })},
      {"match-id",
       [](const std::string& key, const std::string& value, MatchConfig* match) {
         if (Status s = check_match_id(key, value); !s.ok()) return s;
         match->match_id = value;
         return Status::Ok();
       }},
      {"join-timeout", seconds(0.1, 86400, &MatchConfig::join_timeout_s)},
      {"peer-timeout", seconds(0.1, 3600, &MatchConfig::peer_timeout_s)},
  };
  return table;
}

std::string known_settings() {
  std::string out;
  for (const auto& [name, setter] : setters()) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace

Result<std::string> apply_agones_match_settings(const AgonesGameServer& game_server,
                                                MatchConfig* match) {
  // Setting name -> (value, where it came from); annotations are read last
  // so they win over labels.
  std::map<std::string, std::pair<std::string, std::string>> chosen;
  auto collect = [&](const std::map<std::string, std::string>& entries,
                     const std::string& source) -> Status {
    for (const auto& [name, value] : entries) {
      if (name.compare(0, kAgonesSettingPrefix.size(), kAgonesSettingPrefix) != 0) continue;
      const std::string key = name.substr(kAgonesSettingPrefix.size());
      if (setters().find(key) == setters().end()) {
        return Status::Error(ErrorCode::kInvalidArgument, "unknown setting " + printable(name) +
                                                              " (" + source + "); known under " +
                                                              std::string(kAgonesSettingPrefix) +
                                                              ": " + known_settings());
      }
      chosen[key] = {value, source};
    }
    return Status::Ok();
  };
  if (Status s = collect(game_server.labels, "label"); !s.ok()) return s;
  if (Status s = collect(game_server.annotations, "annotation"); !s.ok()) return s;

  MatchConfig candidate = *match;
  std::string applied;
  for (const auto& [key, entry] : chosen) {
    const auto& [value, source] = entry;
    if (Status s = setters().find(key)->second(key, value, &candidate); !s.ok()) return s;
    applied += (applied.empty() ? "" : ", ") + key + "=" + printable(value) + " (" + source + ")";
  }
  if (Status s = candidate.validate(); !s.ok()) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "the allocation's match settings: " + s.message());
  }
  *match = candidate;
  return applied;
}

}  // namespace rwd::server
