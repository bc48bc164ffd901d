// SPDX-License-Identifier: MIT
// The HTTP endpoint over real loopback sockets: requests reach the handler
// whole, oversized and malformed ones are answered without it, a silent
// client is closed at the deadline, silent connections give way to a
// request (32 held sockets do not stop a single scrape), and after close()
// nothing answers.
#include "rewind/server/http_endpoint.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "http_test_client.h"

namespace rwd::server {
namespace {

using namespace std::chrono_literals;
using testing_http::body_of;
using testing_http::Client;
using testing_http::status_of;

class HttpEndpointTest : public ::testing::Test {
 protected:
  void open(HttpEndpoint::Limits limits = {}) {
    auto endpoint = HttpEndpoint::open(
        "test", "127.0.0.1", 0,
        [this](const HttpRequest& request) {
          ++handled_;
          HttpReply reply;
          reply.content_type = "text/plain";
          reply.body = request.method + " " + request.target + " [" + request.authorization + "] " +
                       request.body;
          return reply;
        },
        limits);
    ASSERT_TRUE(endpoint.ok()) << endpoint.status().message();
    endpoint_ = std::move(*endpoint);
    ASSERT_NE(endpoint_->port(), 0);
    client_ = std::make_unique<Client>(endpoint_->port());
  }

  std::atomic<int> handled_{0};
  std::unique_ptr<HttpEndpoint> endpoint_;
  std::unique_ptr<Client> client_;
};

TEST_F(HttpEndpointTest, ARequestReachesTheHandlerWhole) {
  open();
  const std::string answer = client_->exchange(
      "POST /matches?id=a HTTP/1.1\r\nHost: x\r\nAuthorization: Bearer k\r\n"
      "Content-Length: 4\r\n\r\nbody");
  EXPECT_EQ(status_of(answer), 200) << answer;
  EXPECT_EQ(body_of(answer), "POST /matches?id=a [Bearer k] body");
  EXPECT_NE(answer.find("Connection: close"), std::string::npos);
  const std::string head = client_->exchange("HEAD /metrics HTTP/1.0\r\n\r\n");
  EXPECT_EQ(status_of(head), 200);
  EXPECT_EQ(body_of(head), "");
  EXPECT_EQ(endpoint_->stats().answered, 2u);
}

TEST_F(HttpEndpointTest, OversizedAndMalformedRequestsNeverReachTheHandler) {
  HttpEndpoint::Limits limits;
  limits.max_header_bytes = 256;
  limits.max_body_bytes = 16;
  open(limits);
  EXPECT_EQ(status_of(client_->exchange("GET /" + std::string(400, 'a') + " HTTP/1.1\r\n\r\n")),
            431);
  EXPECT_EQ(status_of(client_->exchange("POST / HTTP/1.1\r\nContent-Length: 17\r\n\r\n" +
                                        std::string(17, 'b'))),
            413);
  EXPECT_EQ(status_of(client_->exchange("GET /metrics HTTP/9.9\r\n\r\n")), 400);
  EXPECT_EQ(status_of(client_->exchange("NOT HTTP AT ALL\r\n\r\n")), 400);
  EXPECT_EQ(status_of(client_->exchange("GET * HTTP/1.1\r\n\r\n")), 400);
  EXPECT_EQ(handled_.load(), 0);
  EXPECT_EQ(endpoint_->stats().bad_requests, 5u);
}

TEST_F(HttpEndpointTest, ASilentClientIsClosedAtTheDeadline) {
  HttpEndpoint::Limits limits;
  limits.deadline = 150ms;
  open(limits);
  auto socket = client_->connect();
  asio::write(*socket, asio::buffer(std::string_view("GET /metrics HTTP/1.1\r\nHost: x\r\n")));
  bool closed = false;
  EXPECT_EQ(client_->read_all(*socket, 5s, &closed), "");
  EXPECT_TRUE(closed);
  // The endpoint counts the timeout on its own thread, just after closing.
  for (int i = 0; i < 500 && endpoint_->stats().timed_out == 0; ++i) {
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_EQ(endpoint_->stats().timed_out, 1u);
  EXPECT_EQ(status_of(client_->exchange("GET /metrics HTTP/1.1\r\n\r\n")), 200);
}

TEST_F(HttpEndpointTest, HeldSocketsGiveWayToEveryScrape) {
  // The cap is 16; 32 sockets opened and left silent (with a deadline far
  // beyond the test) must not stop a single one of 40 scrapes.
  HttpEndpoint::Limits limits;
  limits.deadline = 60s;
  open(limits);
  std::vector<std::unique_ptr<asio::ip::tcp::socket>> held;
  for (int i = 0; i < 32; ++i) held.push_back(client_->connect());
  int answered = 0;
  for (int i = 0; i < 40; ++i) {
    answered += status_of(client_->exchange("GET /metrics HTTP/1.1\r\n\r\n")) == 200;
  }
  EXPECT_EQ(answered, 40);
  EXPECT_GE(endpoint_->stats().evicted, 16u);
  EXPECT_EQ(endpoint_->stats().busy, 0u);
}

TEST_F(HttpEndpointTest, AfterCloseNothingAnswersAndNoHandlerRuns) {
  open();
  auto pending = client_->connect();
  asio::write(*pending, asio::buffer(std::string_view("GET /metrics HTTP/1.1\r\n")));
  endpoint_->close();
  std::error_code error;
  asio::ip::tcp::socket late(client_->io());
  late.connect(asio::ip::tcp::endpoint(asio::ip::make_address("127.0.0.1"), endpoint_->port()),
               error);
  EXPECT_TRUE(error) << "the listener is still open";
  EXPECT_EQ(client_->read_all(*pending), "");
  EXPECT_EQ(handled_.load(), 0);
  endpoint_->close();  // idempotent
}

TEST(HttpRequestParse, ReadsWhatTheEndpointReads) {
  auto request =
      parse_http_request("DELETE /matches/duel-7 HTTP/1.1\r\nauthorization: Bearer abc\r\n\r\n");
  ASSERT_TRUE(request.ok()) << request.status().message();
  EXPECT_EQ(request->method, "DELETE");
  EXPECT_EQ(request->path(), "/matches/duel-7");
  EXPECT_EQ(request->query(), "");
  EXPECT_EQ(request->authorization, "Bearer abc");
  auto with_query = parse_http_request("GET /matches?id=a&x=1 HTTP/1.0\r\n\r\n");
  ASSERT_TRUE(with_query.ok());
  EXPECT_EQ(with_query->query(), "id=a&x=1");
  EXPECT_EQ(parse_http_request("GET /x HTTP/1.1\r\n").status().code(), ErrorCode::kCorrupt);
  HttpEndpointLimits small;
  small.max_body_bytes = 2;
  EXPECT_EQ(
      parse_http_request("POST /x HTTP/1.1\r\nContent-Length: 3\r\n\r\nabc", small).status().code(),
      ErrorCode::kCapacity);
}

TEST(LoopbackAddress, OnlyLoopbackLiterals) {
  EXPECT_TRUE(is_loopback_address("127.0.0.1"));
  EXPECT_TRUE(is_loopback_address("127.9.0.1"));
  EXPECT_TRUE(is_loopback_address("::1"));
  EXPECT_TRUE(is_loopback_address("::ffff:127.0.0.1"));
  EXPECT_FALSE(is_loopback_address("0.0.0.0"));
  EXPECT_FALSE(is_loopback_address("::"));
  EXPECT_FALSE(is_loopback_address("10.0.0.1"));
  EXPECT_FALSE(is_loopback_address("localhost"));
  EXPECT_FALSE(is_loopback_address(""));
}

}  // namespace
}  // namespace rwd::server
