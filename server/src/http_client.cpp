// SPDX-License-Identifier: MIT
// The only file that includes Boost.Beast (and Boost.Asio): both are
// header-only and slow to compile, so the HTTP client and the reader its
// tests and fuzz target drive share this one translation unit.
#include "rewind/server/http_client.h"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/string.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/error.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/http/write.hpp>
#include <iterator>
#include <utility>

namespace rwd::server {
namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = net::ip::tcp;
using ResponseParser = http::response_parser<http::string_body>;

bool is_method(std::string_view text) {
  if (text.empty() || text.size() > 16) return false;
  for (const char c : text) {
    if (c < 'A' || c > 'Z') return false;
  }
  return true;
}

// Beast writes the target as given: without this check a caller's target
// could carry a space or CRLF into the request line.
bool is_target(std::string_view text) {
  if (text.empty() || text.front() != '/' || text.size() > 2048) return false;
  for (const char c : text) {
    if (c <= 0x20 || c >= 0x7f) return false;
  }
  return true;
}

// The one configuration of the parser, for http_call and
// parse_http_response alike.
void apply_limits(const HttpResponseLimits& limits, ResponseParser* parser) {
  parser->header_limit(limits.max_header_bytes);
  parser->body_limit(static_cast<std::uint64_t>(limits.max_body_bytes));
}

bool is_parse_error(const beast::error_code& error) {
  return error.category() == http::make_error_code(http::error::need_more).category();
}

// What a parse that ended with `error` (none: a complete response) comes to,
// with the checks Beast leaves to its caller. Messages start with `context`.
Result<HttpResponse> take_response(ResponseParser* parser, const beast::error_code& error,
                                   const HttpResponseLimits& limits, const std::string& context) {
  auto refuse = [&](ErrorCode code, const std::string& what) {
    return Status::Error(code, context + what);
  };
  if (error == http::error::body_limit) {
    return refuse(ErrorCode::kCapacity,
                  "body longer than " + std::to_string(limits.max_body_bytes) + " bytes");
  }
  if (error == http::error::header_limit) {
    return refuse(ErrorCode::kCapacity, "header section longer than " +
                                            std::to_string(limits.max_header_bytes) + " bytes");
  }
  if (error == http::error::end_of_stream) {
    return refuse(ErrorCode::kCorrupt, "the connection closed before a response");
  }
  if (error == http::error::partial_message) {
    return refuse(ErrorCode::kCorrupt, "the connection closed mid-response");
  }
  if (error) return refuse(ErrorCode::kCorrupt, "malformed response: " + error.message());

  auto& message = parser->get();
  const unsigned status = message.result_int();
  // Beast takes any three digits.
  if (status < 100 || status > 599) {
    return refuse(ErrorCode::kCorrupt, "status code " + std::to_string(status) + " out of range");
  }
  // Beast de-chunks a coding list that ends in chunked and reads any other
  // to the end of the connection; either way the body would still be in a
  // coding (gzip, ...) that nothing here decodes.
  const auto codings = message.equal_range(http::field::transfer_encoding);
  if (codings.first != codings.second && (std::next(codings.first) != codings.second ||
                                          !beast::iequals(codings.first->value(), "chunked"))) {
    return refuse(ErrorCode::kCorrupt, "unsupported Transfer-Encoding");
  }
  HttpResponse out;
  out.status = static_cast<int>(status);
  out.reason = std::string(message.reason());
  out.body = std::move(message.body());
  return out;
}

// One call's connection. The steps chain asynchronously on a private
// io_context so that the stream's timer, set once to the call's deadline,
// ends whichever step is pending: Beast then closes the socket and the step
// fails with error::timeout. (Beast's synchronous reads ignore the timer.)
struct Call {
  explicit Call(const HttpResponseLimits& limits) { apply_limits(limits, &parser); }

  void connect(const tcp::resolver::results_type& addresses) {
    // Every address the name resolved to, in order ("localhost" may be ::1
    // first while the service listens on 127.0.0.1 only).
    stream.async_connect(addresses, [this](const beast::error_code& error, const tcp::endpoint&) {
      if (error) return fail("connect", error);
      write();
    });
  }

  void write() {
    http::async_write(stream, request, [this](const beast::error_code& error, size_t) {
      if (error) return fail("write", error);
      read();
    });
  }

  void read() {
    http::async_read(stream, buffer, parser, [this](const beast::error_code& error, size_t) {
      // A malformed answer is the response's fault, not the connection's.
      if (error && !is_parse_error(error)) return fail("read", error);
      read_error = error;
      beast::error_code ignored;
      stream.socket().shutdown(tcp::socket::shutdown_both, ignored);
    });
  }

  void fail(const char* step, const beast::error_code& error) {
    failed_step = step;
    io_error = error;
  }

  net::io_context io{1};
  beast::tcp_stream stream{io};
  http::request<http::string_body> request;
  beast::flat_buffer buffer;
  ResponseParser parser;
  const char* failed_step = nullptr;  ///< set when connecting, writing or reading failed
  beast::error_code io_error;
  beast::error_code read_error;  ///< the parser's, once reading ended
};

}  // namespace

Result<HttpResponse> http_call(std::string_view host, uint16_t port, const HttpRequest& request,
                               const HttpCallLimits& limits) {
  if (!is_method(request.method)) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "HTTP: malformed method '" + request.method + "'");
  }
  if (!is_target(request.target)) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "HTTP: malformed target '" + request.target + "'");
  }
  const auto deadline = std::chrono::steady_clock::now() + limits.deadline;
  const std::string where = std::string(host) + ":" + std::to_string(port);
  const std::string context =
      "HTTP " + request.method + " " + request.target + " to " + where + ": ";

  Call call(limits.response);
  http::request<http::string_body>& wire = call.request;
  wire.method_string(request.method);
  wire.target(request.target);
  wire.version(11);
  wire.set(http::field::host, where);
  wire.set(http::field::accept, "application/json");
  wire.keep_alive(false);
  if (request.method != "GET") {
    wire.set(http::field::content_type, "application/json");
    wire.body() = request.body;
    wire.content_length(request.body.size());
  }

  // Synchronous: asio's resolver cannot interrupt getaddrinfo either, so an
  // asynchronous resolve under the deadline would wait for it just the same.
  beast::error_code error;
  tcp::resolver resolver(call.io);
  const auto addresses = resolver.resolve(std::string(host), std::to_string(port), error);
  if (error) return Status::Error(ErrorCode::kIo, context + "resolve: " + error.message());

  call.stream.expires_at(deadline);
  call.connect(addresses);
  call.io.run();
  if (call.failed_step != nullptr) {
    const std::string why =
        call.io_error == beast::error::timeout
            ? "no answer within " + std::to_string(limits.deadline.count()) + " ms"
            : call.io_error.message();
    return Status::Error(ErrorCode::kIo, context + call.failed_step + ": " + why);
  }
  return take_response(&call.parser, call.read_error, limits.response, context);
}

Result<HttpResponse> parse_http_response(std::string_view bytes, const HttpResponseLimits& limits) {
  ResponseParser parser;
  apply_limits(limits, &parser);
  parser.eager(true);  // as http::read sets it
  // http::read's loop, with `bytes` as all the connection ever delivers:
  // put() while it makes progress; once it needs more, the peer has closed.
  beast::error_code error;
  net::const_buffer rest(bytes.data(), bytes.size());
  while (!parser.is_done()) {
    if (rest.size() > 0) {
      rest += parser.put(rest, error);
      if (error != http::error::need_more) {
        if (error) break;
        continue;
      }
      error = {};
    }
    if (parser.got_some()) {
      parser.put_eof(error);
    } else {
      error = http::error::end_of_stream;
    }
    break;
  }
  return take_response(&parser, error, limits, "HTTP response: ");
}

}  // namespace rwd::server
