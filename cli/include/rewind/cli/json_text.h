// SPDX-License-Identifier: MIT
#pragma once
// Text as a JSON string literal, for the programs' --json output.
#include <string>
#include <string_view>

namespace rwd::cli {

/// `text` quoted and escaped as a JSON string: quote, backslash, newline and
/// tab by name, other control characters as `\u00XX`; bytes >= 0x20 pass
/// through unchanged (the programs print UTF-8).
std::string json_string(std::string_view text);

}  // namespace rwd::cli
