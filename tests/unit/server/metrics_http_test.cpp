// SPDX-License-Identifier: MIT
// The metrics endpoint over real loopback sockets, on one io_context as in
// the server: GET /metrics answers the rendered text, other targets 404,
// malformed and oversized heads 400; a silent client is closed at the
// deadline; connections beyond the cap get 503; after close() nothing
// answers and no handler runs.
#include "rewind/server/metrics_http.h"

#include <gtest/gtest.h>

#include <asio/connect.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/read.hpp>
#include <asio/write.hpp>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace rwd::server {
namespace {

using asio::ip::tcp;
using namespace std::chrono_literals;

class MetricsHttpTest : public ::testing::Test {
 protected:
  void open(MetricsHttp::Limits limits = {}) {
    auto http = MetricsHttp::open(
        io_, "127.0.0.1", 0, [this] { return body_; }, limits);
    ASSERT_TRUE(http.ok()) << http.status().message();
    http_ = std::move(*http);
    ASSERT_NE(http_->port(), 0);
  }

  // Connects without the server's help: the kernel completes the handshake.
  std::unique_ptr<tcp::socket> connect() {
    auto socket = std::make_unique<tcp::socket>(io_);
    socket->connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), http_->port()));
    return socket;
  }

  // Reads everything until the server closes, running the server meanwhile.
  std::string read_all(tcp::socket& socket, std::chrono::milliseconds limit = 5s) {
    std::string response;
    bool done = false;
    asio::async_read(socket, asio::dynamic_buffer(response),
                     [&done](const std::error_code&, size_t) { done = true; });
    run_until([&done] { return done; }, limit);
    EXPECT_TRUE(done) << "the server did not close the connection";
    return response;
  }

  std::string exchange(std::string_view request) {
    auto socket = connect();
    asio::write(*socket, asio::buffer(request));
    return read_all(*socket);
  }

  template <typename Done>
  void run_until(Done done, std::chrono::milliseconds limit) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!done() && std::chrono::steady_clock::now() < deadline) {
      io_.restart();
      io_.run_for(5ms);
    }
  }

  asio::io_context io_;
  std::string body_ = "# HELP rewind_matches m\n# TYPE rewind_matches gauge\nrewind_matches 1\n";
  std::unique_ptr<MetricsHttp> http_;
};

TEST_F(MetricsHttpTest, GetMetricsAnswersTheRenderedText) {
  open();
  const std::string response =
      exchange("GET /metrics HTTP/1.1\r\nHost: 127.0.0.1\r\nAccept: text/plain\r\n\r\n");
  EXPECT_TRUE(response.starts_with("HTTP/1.1 200 OK\r\n")) << response;
  EXPECT_NE(response.find("\r\nContent-Type: text/plain; version=0.0.4\r\n"), std::string::npos);
  EXPECT_NE(response.find("\r\nContent-Length: " + std::to_string(body_.size()) + "\r\n"),
            std::string::npos);
  EXPECT_NE(response.find("\r\nConnection: close\r\n"), std::string::npos);
  EXPECT_TRUE(response.ends_with("\r\n\r\n" + body_)) << response;
  EXPECT_EQ(http_->stats().answered, 1u);
}

TEST_F(MetricsHttpTest, OtherTargetsAndMethodsAre404) {
  open();
  EXPECT_TRUE(exchange("GET / HTTP/1.1\r\n\r\n").starts_with("HTTP/1.1 404 "));
  EXPECT_TRUE(exchange("GET /metricsx HTTP/1.0\r\n\r\n").starts_with("HTTP/1.1 404 "));
  EXPECT_TRUE(
      exchange("POST /metrics HTTP/1.1\r\nContent-Length: 0\r\n\r\n").starts_with("HTTP/1.1 404 "));
  EXPECT_EQ(http_->stats().not_found, 3u);
  EXPECT_EQ(http_->stats().answered, 0u);
}

TEST_F(MetricsHttpTest, MalformedAndOversizedHeadsAre400) {
  open();
  EXPECT_TRUE(exchange("hello\r\n\r\n").starts_with("HTTP/1.1 400 "));
  // A client that gives up midway sent a malformed request too.
  {
    auto socket = connect();
    asio::write(*socket, asio::buffer(std::string_view("GET /metrics HTTP/1.1\r\n")));
    socket->shutdown(tcp::socket::shutdown_send);
    EXPECT_TRUE(read_all(*socket).starts_with("HTTP/1.1 400 "));
  }
  const std::string huge = "GET /metrics HTTP/1.1\r\nX-Filler: " + std::string(9000, 'a');
  EXPECT_TRUE(exchange(huge).starts_with("HTTP/1.1 400 "));
  EXPECT_EQ(http_->stats().bad_requests, 3u);
}

TEST_F(MetricsHttpTest, RespondChecksTheRequestLineAndHeaders) {
  const MetricsHttp::RenderFn render = [] { return std::string("x 1\n"); };
  auto status = [&render](std::string_view head) {
    return MetricsHttp::respond(head, render).substr(0, 12);
  };
  EXPECT_EQ(status("GET /metrics HTTP/1.1\r\n\r\n"), "HTTP/1.1 200");
  EXPECT_EQ(status("GET /metrics?name[]=x HTTP/1.1\r\nHost: a:1\r\n\r\n"), "HTTP/1.1 200");
  EXPECT_EQ(status("GET /metrics/ HTTP/1.1\r\n\r\n"), "HTTP/1.1 404");
  EXPECT_EQ(status("get /metrics HTTP/1.1\r\n\r\n"), "HTTP/1.1 400");
  EXPECT_EQ(status("GET metrics HTTP/1.1\r\n\r\n"), "HTTP/1.1 400");
  EXPECT_EQ(status("GET /metrics HTTP/2.0\r\n\r\n"), "HTTP/1.1 400");
  EXPECT_EQ(status("GET  /metrics HTTP/1.1\r\n\r\n"), "HTTP/1.1 400");
  EXPECT_EQ(status("GET /metrics HTTP/1.1 x\r\n\r\n"), "HTTP/1.1 400");
  EXPECT_EQ(status("GET /metrics HTTP/1.1\r\nno colon here\r\n\r\n"), "HTTP/1.1 400");
  EXPECT_EQ(status("GET /metrics HTTP/1.1\r\n: empty name\r\n\r\n"), "HTTP/1.1 400");
  EXPECT_EQ(status("GET /metrics HTTP/1.1\r\nBad\x01: x\r\n\r\n"), "HTTP/1.1 400");
  EXPECT_EQ(status("GET /metrics HTTP/1.1\r\n"), "HTTP/1.1 400");
  EXPECT_EQ(status("\r\n\r\n"), "HTTP/1.1 400");
  // HEAD answers the headers without the body.
  const std::string head = MetricsHttp::respond("HEAD /metrics HTTP/1.1\r\n\r\n", render);
  EXPECT_TRUE(head.starts_with("HTTP/1.1 200"));
  EXPECT_TRUE(head.ends_with("Content-Length: 4\r\nConnection: close\r\n\r\n")) << head;
}

TEST_F(MetricsHttpTest, ASilentClientIsClosedAtTheDeadline) {
  MetricsHttp::Limits limits;
  limits.deadline = 150ms;
  open(limits);
  auto socket = connect();
  asio::write(*socket, asio::buffer(std::string_view("GET /metrics HTTP/1.1\r\nHost: x\r\n")));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(read_all(*socket), "");
  EXPECT_GE(std::chrono::steady_clock::now() - start, 100ms);
  EXPECT_EQ(http_->stats().timed_out, 1u);
  // The endpoint still answers.
  EXPECT_TRUE(exchange("GET /metrics HTTP/1.1\r\n\r\n").starts_with("HTTP/1.1 200 "));
}

TEST_F(MetricsHttpTest, ConnectionsBeyondTheCapGet503) {
  MetricsHttp::Limits limits;
  limits.max_connections = 2;
  limits.deadline = 300ms;
  open(limits);
  std::vector<std::unique_ptr<tcp::socket>> silent;
  silent.push_back(connect());
  silent.push_back(connect());
  run_until([this] { return false; }, 50ms);  // both accepted
  auto third = connect();
  EXPECT_TRUE(read_all(*third, 1s).starts_with("HTTP/1.1 503 "));
  EXPECT_EQ(http_->stats().busy, 1u);
  // Once the silent ones time out there is room again.
  for (auto& socket : silent) EXPECT_EQ(read_all(*socket), "");
  EXPECT_TRUE(exchange("GET /metrics HTTP/1.1\r\n\r\n").starts_with("HTTP/1.1 200 "));
}

TEST_F(MetricsHttpTest, AfterCloseNothingAnswersAndNoHandlerRuns) {
  open();
  auto pending = connect();
  run_until([this] { return false; }, 20ms);  // accepted, waiting for a request
  http_->close();
  std::error_code error;
  tcp::socket late(io_);
  late.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), http_->port()), error);
  EXPECT_TRUE(error) << "the listener is still open";
  EXPECT_EQ(read_all(*pending), "");
  http_.reset();
  // Whatever completes now must not touch the destroyed responder.
  run_until([] { return false; }, 20ms);
}

}  // namespace
}  // namespace rwd::server
