// SPDX-License-Identifier: MIT
#pragma once
// A blocking HTTP/1.1 client for short calls to a local service (the
// Agones SDK sidecar), on Boost.Beast. Each call opens its own connection
// and io_context, sends one request with `Connection: close` and reads one
// response; a deadline bounds the call. Blocking: call it from a thread that
// may wait (never from the tick loop). Calls on different threads are
// independent.
//
// Beast stays out of this header: its headers are heavy to compile and
// only server/src/http_client.cpp includes them.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "rewind/core/status.h"

namespace rwd::server {

/// What http_call sends (the server side's parsed request is HttpRequest,
/// in http_endpoint.h).
struct HttpCallRequest {
  std::string method = "GET";  ///< an upper-case token: GET, POST, ...
  std::string target = "/";    ///< origin form: starts with '/', visible ASCII
  /// Sent with `Content-Type: application/json` when the method is not GET.
  std::string body;
};

struct HttpResponse {
  int status = 0;  ///< [100, 599]
  /// The reason phrase; when the peer sent none, the standard one for the
  /// status ("Internal Server Error"), as Beast reports it.
  std::string reason;
  std::string body;  ///< de-chunked
};

struct HttpResponseLimits {
  /// The status line and the header fields together.
  uint32_t max_header_bytes = 16 << 10;
  /// The body once de-chunked.
  size_t max_body_bytes = 1 << 20;
};

struct HttpCallLimits {
  /// From the start of the call to the end of the response. Name resolution
  /// counts against it but cannot be interrupted (getaddrinfo blocks; asio's
  /// cancel waits for it too): address the service as an IP literal or a
  /// name resolved locally, such as "localhost".
  std::chrono::milliseconds deadline{2000};
  HttpResponseLimits response;
};

/// Sends `request` to `host`:`port` (a name, tried at each address it
/// resolves to, or an IP literal) and returns the response, whatever its
/// status code. Errors name the call and the host and port:
/// kInvalidArgument for a malformed method or target; kIo when resolving,
/// connecting, writing or reading fails or the deadline passes (the message
/// names the step); kCorrupt for a malformed or truncated response; kCapacity
/// for one over the limits.
Result<HttpResponse> http_call(std::string_view host, uint16_t port, const HttpCallRequest& request,
                               const HttpCallLimits& limits = {});

/// Reads `bytes` as everything a peer sent before closing the connection,
/// through the same parser, limits and checks as http_call: bodies framed
/// by Content-Length, by chunked transfer coding, or by the end of the
/// connection. Bytes after a complete response are ignored, as http_call
/// never reads them. Errors are kCorrupt, or kCapacity past `limits`, with
/// a message naming the problem. For tests and the fuzz target.
Result<HttpResponse> parse_http_response(std::string_view bytes,
                                         const HttpResponseLimits& limits = {});

}  // namespace rwd::server
