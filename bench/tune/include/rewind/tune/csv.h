// SPDX-License-Identifier: MIT
#pragma once
// CSV fields shared by rewind-scene-sweep and rewind-tune.
#include <string>
#include <string_view>

namespace rwd::tune {

/// Free text in double quotes with inner quotes doubled (RFC 4180).
inline std::string csv_quoted(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace rwd::tune
