// SPDX-License-Identifier: MIT
#pragma once
// A test's HTTP client over real loopback sockets: connect, send bytes,
// read until the server closes, never waiting past a deadline.
#include <asio/connect.hpp>
#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/read.hpp>
#include <asio/write.hpp>
#include <chrono>
#include <memory>
#include <string>
#include <string_view>

namespace rwd::server::testing_http {

using asio::ip::tcp;
using namespace std::chrono_literals;

class Client {
 public:
  explicit Client(uint16_t port) : port_(port) {}

  // Connects without the server's help: the kernel completes the handshake.
  std::unique_ptr<tcp::socket> connect() {
    auto socket = std::make_unique<tcp::socket>(io_);
    socket->connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port_));
    return socket;
  }

  // Everything until the server closes; `closed` says whether it did in time.
  std::string read_all(tcp::socket& socket, std::chrono::milliseconds limit = 5s,
                       bool* closed = nullptr) {
    std::string response;
    bool done = false;
    asio::async_read(socket, asio::dynamic_buffer(response),
                     [&done](const std::error_code&, size_t) { done = true; });
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!done && std::chrono::steady_clock::now() < deadline) {
      io_.restart();
      io_.run_for(5ms);
    }
    if (!done) {
      std::error_code ignored;
      socket.close(ignored);
      io_.restart();
      io_.run_for(5ms);
    }
    if (closed != nullptr) *closed = done;
    return response;
  }

  std::string exchange(std::string_view request, std::chrono::milliseconds limit = 5s) {
    auto socket = connect();
    asio::write(*socket, asio::buffer(request));
    return read_all(*socket, limit);
  }

  asio::io_context& io() { return io_; }

 private:
  asio::io_context io_;
  uint16_t port_;
};

/// "HTTP/1.1 200 OK" -> 200; 0 when `response` is not an HTTP answer.
inline int status_of(std::string_view response) {
  if (!response.starts_with("HTTP/1.1 ") || response.size() < 12) return 0;
  return std::stoi(std::string(response.substr(9, 3)));
}

/// The body after the blank line.
inline std::string body_of(std::string_view response) {
  const size_t blank = response.find("\r\n\r\n");
  return blank == std::string_view::npos ? std::string() : std::string(response.substr(blank + 4));
}

}  // namespace rwd::server::testing_http
