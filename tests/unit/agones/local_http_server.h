// SPDX-License-Identifier: MIT
#pragma once
// A loopback HTTP server for the SDK client's tests, on its own thread:
// each connection's request (head and Content-Length body) is recorded and
// answered with whatever `answer` returns for it, raw bytes, then closed.
// An empty answer holds the connection open without a word until the server
// stops, as a hung sidecar would.
#include <asio/buffer.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/read.hpp>
#include <asio/read_until.hpp>
#include <asio/write.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace rwd::server::testing {

class LocalHttpServer {
 public:
  using AnswerFn = std::function<std::string(const std::string& request)>;

  explicit LocalHttpServer(AnswerFn answer)
      : answer_(std::move(answer)),
        acceptor_(io_, asio::ip::tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)) {
    accept();
    thread_ = std::thread([this] { io_.run(); });
  }
  ~LocalHttpServer() {
    io_.stop();
    thread_.join();
  }

  uint16_t port() const { return acceptor_.local_endpoint().port(); }
  std::vector<std::string> requests() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return requests_;
  }

  /// "HTTP/1.1 <status>" with a JSON body and its Content-Length.
  static std::string json_answer(const std::string& status, const std::string& body) {
    return "HTTP/1.1 " + status +
           "\r\nContent-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
           "\r\n\r\n" + body;
  }

 private:
  struct Connection {
    explicit Connection(asio::io_context& io) : socket(io) {}
    asio::ip::tcp::socket socket;
    std::string buffer;
    std::string reply;
  };

  void accept() {
    auto connection = std::make_shared<Connection>(io_);
    acceptor_.async_accept(connection->socket, [this, connection](const std::error_code& error) {
      if (error) return;
      read_head(connection);
      accept();
    });
  }

  void read_head(const std::shared_ptr<Connection>& c) {
    asio::async_read_until(
        c->socket, asio::dynamic_buffer(c->buffer), "\r\n\r\n",
        [this, c](const std::error_code& error, size_t head_size) {
          if (error) return;
          size_t length = 0;
          const std::string head = c->buffer.substr(0, head_size);
          if (const size_t at = head.find("Content-Length: "); at != std::string::npos) {
            length = std::stoul(head.substr(at + 16));
          }
          const size_t missing =
              head_size + length > c->buffer.size() ? head_size + length - c->buffer.size() : 0;
          asio::async_read(
              c->socket, asio::dynamic_buffer(c->buffer), asio::transfer_exactly(missing),
              [this, c](const std::error_code& read_error, size_t) {
                if (read_error) return;
                {
                  std::lock_guard<std::mutex> lock(mutex_);
                  requests_.push_back(c->buffer);
                }
                c->reply = answer_(c->buffer);
                if (c->reply.empty()) {
                  held_.push_back(c);
                  return;
                }
                asio::async_write(
                    c->socket, asio::buffer(c->reply), [c](const std::error_code&, size_t) {
                      std::error_code ignored;
                      c->socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
                      c->socket.close(ignored);
                    });
              });
        });
  }

  AnswerFn answer_;
  asio::io_context io_;
  asio::ip::tcp::acceptor acceptor_;
  std::vector<std::shared_ptr<Connection>> held_;  // io thread only
  mutable std::mutex mutex_;
  std::vector<std::string> requests_;
  std::thread thread_;
};

}  // namespace rwd::server::testing
