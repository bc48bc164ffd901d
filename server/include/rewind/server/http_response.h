// SPDX-License-Identifier: MIT
#pragma once
// Reading one whole HTTP/1.1 response, as received on a connection the
// server asked to close (`Connection: close`): the status line, the headers
// and a body framed by Content-Length, by chunked transfer coding, or by the
// end of the connection. Strict: a malformed status line or header, both
// framings at once, a truncated body or bytes after it are errors.
#include <cstddef>
#include <string>
#include <string_view>

#include "rewind/sim/status.h"

namespace rwd::server {

struct HttpResponse {
  int status = 0;      ///< [100, 599]
  std::string reason;  ///< the reason phrase, possibly empty
  std::string body;    ///< de-chunked
};

/// Parses `bytes`, everything the peer sent before closing. Errors are
/// kCorrupt naming the problem; a body longer than `max_body_bytes` is
/// kCapacity.
Result<HttpResponse> parse_http_response(std::string_view bytes, size_t max_body_bytes = 1 << 20);

}  // namespace rwd::server
