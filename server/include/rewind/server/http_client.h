// SPDX-License-Identifier: MIT
#pragma once
// A blocking HTTP/1.1 client for short calls to a local service (the
// Agones SDK sidecar). Each call opens its own connection and io_context,
// sends one request with `Connection: close`, reads until the peer closes
// and parses the answer; a deadline bounds the whole call. Blocking: call it
// from a thread that may wait (never from the tick loop). Calls on
// different threads are independent.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "rewind/server/http_response.h"
#include "rewind/sim/status.h"

namespace rwd::server {

struct HttpRequest {
  std::string method = "GET";  ///< an upper-case token: GET, POST, ...
  std::string target = "/";    ///< origin form: starts with '/', visible ASCII
  /// Sent with `Content-Type: application/json` when the method is not GET.
  std::string body;
};

struct HttpCallLimits {
  /// From resolving the host to the peer closing the connection.
  std::chrono::milliseconds deadline{2000};
  /// Responses longer than this (status line, headers, body) are refused.
  size_t max_response_bytes = 1 << 20;
};

/// Sends `request` to `host`:`port` (a name such as "localhost", tried at
/// each address it resolves to, or an IP literal) and returns the parsed
/// response, whatever its status code. Errors: kInvalidArgument for a
/// malformed method or target, kIo when resolving, connecting, writing or
/// reading fails or the deadline passes (the message names which, and the
/// host and port), kCorrupt or kCapacity from parse_http_response.
Result<HttpResponse> http_call(std::string_view host, uint16_t port, const HttpRequest& request,
                               const HttpCallLimits& limits = {});

}  // namespace rwd::server
