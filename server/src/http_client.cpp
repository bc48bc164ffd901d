// SPDX-License-Identifier: MIT
#include "rewind/server/http_client.h"

#include <asio/buffer.hpp>
#include <asio/connect.hpp>
#include <asio/error.hpp>
#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/read.hpp>
#include <asio/steady_timer.hpp>
#include <asio/write.hpp>
#include <utility>

namespace rwd::server {
namespace {

bool is_method(std::string_view text) {
  if (text.empty() || text.size() > 16) return false;
  for (const char c : text) {
    if (c < 'A' || c > 'Z') return false;
  }
  return true;
}

bool is_target(std::string_view text) {
  if (text.empty() || text.front() != '/' || text.size() > 2048) return false;
  for (const char c : text) {
    if (c <= 0x20 || c >= 0x7f) return false;
  }
  return true;
}

std::string format_request(std::string_view host, uint16_t port, const HttpRequest& request) {
  std::string out = request.method + " " + request.target + " HTTP/1.1\r\n";
  out += "Host: " + std::string(host) + ":" + std::to_string(port) + "\r\n";
  out += "Accept: application/json\r\nConnection: close\r\n";
  if (request.method != "GET") {
    out += "Content-Type: application/json\r\n";
    out += "Content-Length: " + std::to_string(request.body.size()) + "\r\n";
  }
  out += "\r\n";
  if (request.method != "GET") out += request.body;
  return out;
}

// One call's state. The steps chain asynchronously on a private
// io_context, so a single timer can cancel whichever step is pending when
// the deadline passes.
struct Call {
  explicit Call(size_t max_bytes) : resolver(io), socket(io), timer(io), limit(max_bytes) {}

  void fail(const std::string& step, const std::error_code& error) {
    fail_with(step + ": " + error.message());
  }

  void fail_with(std::string text) {
    if (!error_text.empty()) return;
    error_text = std::move(text);
    timer.cancel();
    resolver.cancel();
    std::error_code ignored;
    socket.close(ignored);
  }

  void start(const std::string& host, uint16_t port) {
    resolver.async_resolve(
        host, std::to_string(port),
        [this](const std::error_code& error, const asio::ip::tcp::resolver::results_type& found) {
          if (error) return fail("resolve", error);
          connect(found);
        });
  }

  // Every address the name resolved to, in order ("localhost" may be ::1
  // first while the service listens on 127.0.0.1 only).
  void connect(const asio::ip::tcp::resolver::results_type& found) {
    asio::async_connect(socket, found,
                        [this](const std::error_code& error, const asio::ip::tcp::endpoint&) {
                          if (error) return fail("connect", error);
                          write();
                        });
  }

  void write() {
    asio::async_write(socket, asio::buffer(wire), [this](const std::error_code& error, size_t) {
      if (error) return fail("write", error);
      read_more();
    });
  }

  void read_more() {
    // Bounded: one byte past the limit is enough to know it is too long.
    const size_t room = limit + 1 - received.size();
    const size_t old = received.size();
    received.resize(old + std::min<size_t>(room, 4096));
    socket.async_read_some(
        asio::buffer(received.data() + old, received.size() - old),
        [this, old](const std::error_code& error, size_t n) {
          received.resize(old + n);
          if (error == asio::error::eof) {
            done = true;
            timer.cancel();
            return;
          }
          if (error) return fail("read", error);
          if (received.size() > limit) {
            too_long = true;
            return fail_with("response longer than " + std::to_string(limit) + " bytes");
          }
          read_more();
        });
  }

  asio::io_context io{1};
  asio::ip::tcp::resolver resolver;
  asio::ip::tcp::socket socket;
  asio::steady_timer timer;
  size_t limit;
  std::string wire;
  std::string received;
  std::string error_text;
  bool done = false;
  bool too_long = false;
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
  const std::string where = std::string(host) + ":" + std::to_string(port);
  Call call(limits.max_response_bytes);
  call.wire = format_request(host, port, request);
  call.timer.expires_after(limits.deadline);
  call.timer.async_wait([&call, &limits](const std::error_code& error) {
    if (error || call.done) return;
    call.fail_with("no answer within " + std::to_string(limits.deadline.count()) + " ms");
  });
  call.start(std::string(host), port);
  call.io.run();
  if (call.too_long) {
    return Status::Error(ErrorCode::kCapacity, "HTTP " + request.method + " " + request.target +
                                                   " to " + where + ": " + call.error_text);
  }
  if (!call.done) {
    return Status::Error(ErrorCode::kIo, "HTTP " + request.method + " " + request.target + " to " +
                                             where + ": " + call.error_text);
  }
  return parse_http_response(call.received, limits.max_response_bytes);
}

}  // namespace rwd::server
