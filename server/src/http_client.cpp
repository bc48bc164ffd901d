// SPDX-License-Identifier: MIT
// The only file that includes Boost.Beast (and Boost.Asio): both are
// header-only and slow to compile, so the HTTP client and the reader its
// tests and fuzz target drive share this one translation unit.
#include "rewind/server/http_client.h"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/string.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/error.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/http/write.hpp>
#include <iterator>
#include <sstream>
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
  parser->eager(true);  // as http::read sets it: one put() takes all it can
}

// http::read's parsing step, shared by http_call (bytes as they arrive)
// and parse_http_response (all of them, then the end): `data` goes to the
// parser, which takes what it can, and `closed` says the peer has closed
// the connection. Returns the bytes used. The parse is over when the parser
// is done or `error` is set; otherwise it waits for more bytes.
size_t parse_arrived(net::const_buffer data, bool closed, ResponseParser* parser,
                     beast::error_code* error) {
  size_t used = 0;
  while (!parser->is_done()) {
    if (data.size() > 0) {
      const size_t n = parser->put(data, *error);
      data += n;
      used += n;
      if (*error != http::error::need_more) {
        if (*error) return used;
        continue;
      }
      *error = {};
    }
    if (!closed) return used;
    if (parser->got_some()) {
      parser->put_eof(*error);
    } else {
      *error = http::error::end_of_stream;
    }
    return used;
  }
  return used;
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
// io_context so that the stream's timer, set once for the whole call, ends
// whichever step is pending: Beast then closes the socket and the step
// fails with error::timeout. (Beast's synchronous operations ignore the
// timer.) Beast's composed http::async_read and http::async_write would do
// the same work, but made this file take about 40% longer to compile (GCC
// 12, -O3) than reading with async_read_some into parse_arrived and writing
// the serialized request.
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
    net::async_write(stream, net::buffer(wire), [this](const beast::error_code& error, size_t) {
      if (error) return fail("write", error);
      read();
    });
  }

  void read() {
    stream.async_read_some(
        buffer.prepare(16 << 10), [this](const beast::error_code& error, size_t n) {
          buffer.commit(n);
          const bool closed = error == net::error::eof;
          if (error && !closed) return fail("read", error);
          buffer.consume(parse_arrived(buffer.data(), closed, &parser, &parse_error));
          if (!parse_error && !parser.is_done()) return read();
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
  std::string wire;           ///< the request as sent
  beast::flat_buffer buffer;  ///< bytes received and not parsed yet
  ResponseParser parser;
  const char* failed_step = nullptr;  ///< set when connecting, writing or reading failed
  beast::error_code io_error;
  /// A malformed answer: the response's fault, not the connection's.
  beast::error_code parse_error;
};

}  // namespace

Result<HttpResponse> http_call(std::string_view host, uint16_t port, const HttpCallRequest& request,
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

  http::request<http::string_body> message;
  message.method_string(request.method);
  message.target(request.target);
  message.version(11);
  message.set(http::field::host, where);
  message.set(http::field::accept, "application/json");
  message.keep_alive(false);
  if (request.method != "GET") {
    message.set(http::field::content_type, "application/json");
    message.body() = request.body;
    message.content_length(request.body.size());
  }
  Call call(limits.response);
  std::ostringstream serialized;
  serialized << message;
  call.wire = std::move(serialized).str();

  // Synchronous: asio's resolver cannot interrupt getaddrinfo either, so an
  // asynchronous resolve under the deadline would wait for it just the same.
  beast::error_code error;
  tcp::resolver resolver(call.io);
  const auto addresses = resolver.resolve(std::string(host), std::to_string(port), error);
  if (error) return Status::Error(ErrorCode::kIo, context + "resolve: " + error.message());

  // What resolving left of the call's time; none left times out at once.
  call.stream.expires_after(deadline - std::chrono::steady_clock::now());
  call.connect(addresses);
  call.io.run();
  if (call.failed_step != nullptr) {
    const std::string why =
        call.io_error == beast::error::timeout
            ? "no answer within " + std::to_string(limits.deadline.count()) + " ms"
            : call.io_error.message();
    return Status::Error(ErrorCode::kIo, context + call.failed_step + ": " + why);
  }
  return take_response(&call.parser, call.parse_error, limits.response, context);
}

Result<HttpResponse> parse_http_response(std::string_view bytes, const HttpResponseLimits& limits) {
  ResponseParser parser;
  apply_limits(limits, &parser);
  beast::error_code error;
  parse_arrived(net::const_buffer(bytes.data(), bytes.size()), /*closed=*/true, &parser, &error);
  return take_response(&parser, error, limits, "HTTP response: ");
}

}  // namespace rwd::server
