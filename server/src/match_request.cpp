// SPDX-License-Identifier: MIT
#include "rewind/server/match_request.h"

#include <charconv>
#include <string>

namespace rwd::server {
namespace {

constexpr size_t kMaxQueryBytes = 1024;

bool is_value_text(std::string_view text) {
  for (const char c : text) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == '-';
    if (!ok) return false;
  }
  return !text.empty();
}

bool read_int(std::string_view text, int64_t low, int64_t high, int64_t* out) {
  int64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return false;
  if (value < low || value > high) return false;
  *out = value;
  return true;
}

bool read_seconds(std::string_view text, double low, double high, double* out) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return false;
  if (!(value >= low && value <= high)) return false;
  *out = value;
  return true;
}

Status bad(const std::string& message) {
  return Status::Error(ErrorCode::kInvalidArgument, message);
}

}  // namespace

Result<MatchRequest> parse_match_request(std::string_view query, const MatchConfig& defaults) {
  if (query.size() > kMaxQueryBytes) {
    return bad("query longer than " + std::to_string(kMaxQueryBytes) + " bytes");
  }
  MatchRequest request;
  request.match = defaults;
  MatchConfig& m = request.match;
  std::string seen = "&";  // keys already read, each between '&'s
  while (!query.empty()) {
    const size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view() : query.substr(amp + 1);
    if (pair.empty()) continue;  // "a=1&&b=2" or a trailing '&'
    const size_t equals = pair.find('=');
    if (equals == std::string_view::npos) {
      return bad("'" + std::string(pair.substr(0, 64)) + "' has no value");
    }
    const std::string key(pair.substr(0, equals));
    const std::string_view value = pair.substr(equals + 1);
    if (!is_value_text(key) || key.size() > 32) return bad("bad key");
    if (seen.find("&" + key + "&") != std::string::npos) return bad("'" + key + "' given twice");
    seen += key + "&";
    if (!is_value_text(value) || value.size() > 64) {
      return bad("'" + key + "': values are 1 to 64 characters of A-Z a-z 0-9 . _ -");
    }
    int64_t number = 0;
    double seconds = 0;
    const std::string range = "'" + key + "' out of range or not a number";
    if (key == "id") {
      m.match_id = std::string(value);
    } else if (key == "game") {
      m.game = std::string(value);
    } else if (key == "players") {
      if (!read_int(value, 1, 32, &number)) return bad(range);
      m.players = static_cast<uint32_t>(number);
    } else if (key == "start_players") {
      if (!read_int(value, 0, 32, &number)) return bad(range);
      m.start_players = static_cast<uint32_t>(number);
    } else if (key == "spectators") {
      if (!read_int(value, 0, 63, &number)) return bad(range);
      m.max_spectators = static_cast<uint32_t>(number);
    } else if (key == "tick_rate") {
      if (!read_int(value, 1, 1000, &number)) return bad(range);
      m.tick_rate_hz = static_cast<uint32_t>(number);
    } else if (key == "window") {
      if (!read_int(value, 1, 120, &number)) return bad(range);
      m.window_ticks = static_cast<int32_t>(number);
    } else if (key == "ticks") {
      if (!read_int(value, 0, int64_t{1} << 31, &number)) return bad(range);
      m.max_ticks = number;
    } else if (key == "seed") {
      if (!read_int(value, 0, INT64_MAX, &number)) return bad(range);
      m.seed = static_cast<uint64_t>(number);
    } else if (key == "join_timeout") {
      if (!read_seconds(value, 0.1, 86400, &seconds)) return bad(range);
      m.join_timeout_s = seconds;
    } else if (key == "peer_timeout") {
      if (!read_seconds(value, 0.1, 3600, &seconds)) return bad(range);
      m.peer_timeout_s = seconds;
    } else if (key == "port") {
      if (!read_int(value, 0, 65535, &number)) return bad(range);
      request.port = static_cast<uint16_t>(number);
    } else {
      return bad("unknown key '" + key + "'");
    }
  }
  if (Status status = m.validate(); !status.ok()) return status;
  return request;
}

}  // namespace rwd::server
