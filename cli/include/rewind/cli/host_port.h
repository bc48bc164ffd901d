// SPDX-License-Identifier: MIT
#pragma once
// "HOST:PORT" flag values (--connect, --metrics-bind).
#include <cstdint>
#include <string>
#include <string_view>

namespace rwd::cli {

/// Splits "HOST:PORT", or "[IPV6]:PORT" (the brackets are dropped). False
/// unless HOST is non-empty and PORT is a decimal number in [0, 65535];
/// callers that cannot use port 0 refuse it themselves.
bool split_host_port(std::string_view text, std::string* host, uint16_t* port);

}  // namespace rwd::cli
