// SPDX-License-Identifier: MIT
// The browser transport: a match's WebSocketPort (endpoints of their own,
// datagrams in order, sends routed, nothing after close) and the
// WebSocketEndpoint over real loopback connections (routing by match id,
// 404 and 426 answers, text and oversized messages refused, the
// subprotocol echoed, a closed match closing its browsers).
#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <thread>
#include <vector>

#include "http_test_client.h"
#include "rewind/client/websocket_link.h"
#include "rewind/server/websocket_endpoint.h"
#include "rewind/server/websocket_port.h"

namespace rwd::server {
namespace {

using namespace std::chrono_literals;
using client::WebSocketLink;

// Records what the match sent to it, and whether it was closed.
class RecordingPeer : public WebSocketPeer {
 public:
  void send(std::vector<uint8_t> message) override { sent.push_back(std::move(message)); }
  void close() override { closed = true; }
  std::vector<std::vector<uint8_t>> sent;
  bool closed = false;
};

std::vector<uint8_t> bytes(std::initializer_list<uint8_t> list) {
  return list;
}

TEST(WebSocketPort, ConnectionsGetEndpointsNoUdpPeerHas) {
  WebSocketPort port;
  auto a = port.attach(std::make_shared<RecordingPeer>(), 5000);
  auto b = port.attach(std::make_shared<RecordingPeer>(), 5000);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_NE(*a, *b);  // the same browser port twice is still two peers
  EXPECT_TRUE(WebSocketPort::is_websocket_endpoint(*a));
  EXPECT_EQ(a->port(), 5000);
  const asio::ip::udp::endpoint v4(asio::ip::make_address("127.0.0.1"), 5000);
  const asio::ip::udp::endpoint v6(asio::ip::make_address("::1"), 5000);
  const asio::ip::udp::endpoint near(asio::ip::make_address("100:0:0:1::1"), 5000);
  EXPECT_FALSE(WebSocketPort::is_websocket_endpoint(v4));
  EXPECT_FALSE(WebSocketPort::is_websocket_endpoint(v6));
  EXPECT_FALSE(WebSocketPort::is_websocket_endpoint(near));
}

TEST(WebSocketPort, DatagramsReachTheMatchInOrderAndAnswersTheirSender) {
  WebSocketPort port;
  auto first = std::make_shared<RecordingPeer>(), second = std::make_shared<RecordingPeer>();
  const auto a = *port.attach(first, 1), b = *port.attach(second, 2);
  port.deliver(a, bytes({1, 2}));
  port.deliver(b, bytes({3}));
  port.deliver(a, bytes({}));
  std::vector<std::pair<std::vector<uint8_t>, asio::ip::udp::endpoint>> got;
  EXPECT_EQ(port.drain([&](std::span<const uint8_t> d, const asio::ip::udp::endpoint& from) {
    got.emplace_back(std::vector<uint8_t>(d.begin(), d.end()), from);
  }),
            3u);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0].first, bytes({1, 2}));
  EXPECT_EQ(got[0].second, a);
  EXPECT_EQ(got[1].first, bytes({3}));
  EXPECT_EQ(got[1].second, b);
  EXPECT_TRUE(got[2].first.empty());
  EXPECT_EQ(port.drain([](auto, const auto&) { FAIL(); }), 0u);

  port.send(bytes({9}), b);
  EXPECT_TRUE(first->sent.empty());
  ASSERT_EQ(second->sent.size(), 1u);
  EXPECT_EQ(second->sent[0], bytes({9}));
  const WebSocketPort::Stats stats = port.stats();
  EXPECT_EQ(stats.datagrams_in, 3u);
  EXPECT_EQ(stats.bytes_in, 3u);
  EXPECT_EQ(stats.datagrams_out, 1u);
  EXPECT_EQ(stats.open, 2u);
}

TEST(WebSocketPort, AGoneConnectionAndAUdpEndpointGetNothing) {
  WebSocketPort port;
  auto peer = std::make_shared<RecordingPeer>();
  const auto a = *port.attach(peer, 1);
  port.detach(a);
  port.send(bytes({1}), a);
  port.send(bytes({1}), asio::ip::udp::endpoint(asio::ip::make_address("127.0.0.1"), 1));
  EXPECT_TRUE(peer->sent.empty());
  EXPECT_EQ(port.stats().dropped_out, 2u);
  EXPECT_EQ(port.stats().open, 0u);
}

TEST(WebSocketPort, AFloodWaitsNoFurtherThanItsLimit) {
  WebSocketPort port;
  const auto a = *port.attach(std::make_shared<RecordingPeer>(), 1);
  for (size_t i = 0; i < WebSocketPort::kMaxWaiting + 10; ++i) port.deliver(a, bytes({7}));
  EXPECT_EQ(port.drain([](auto, const auto&) {}), WebSocketPort::kMaxWaiting);
  EXPECT_EQ(port.stats().dropped_in, 10u);
}

TEST(WebSocketPort, ClosingClosesEveryConnectionAndRefusesNewOnes) {
  WebSocketPort port;
  auto peer = std::make_shared<RecordingPeer>();
  const auto a = *port.attach(peer, 1);
  port.deliver(a, bytes({1}));
  port.close();
  EXPECT_TRUE(peer->closed);
  EXPECT_EQ(port.drain([](auto, const auto&) { FAIL(); }), 0u);
  port.deliver(a, bytes({1}));
  auto late = port.attach(std::make_shared<RecordingPeer>(), 2);
  EXPECT_EQ(late.status().code(), ErrorCode::kNotFound);
  EXPECT_EQ(port.stats().refused, 1u);
  port.close();  // idempotent
}

class WebSocketEndpointTest : public ::testing::Test {
 protected:
  void SetUp() override {
    port_ = std::make_shared<WebSocketPort>();
    auto endpoint = WebSocketEndpoint::open(
        "127.0.0.1", 0, [this](std::string_view id) { return id == "duel" ? port_ : nullptr; },
        limits_);
    ASSERT_TRUE(endpoint.ok()) << endpoint.status().message();
    endpoint_ = std::move(*endpoint);
  }

  std::string url(std::string_view match) const {
    return "ws://127.0.0.1:" + std::to_string(endpoint_->port()) + "/matches/" + std::string(match);
  }

  // Polls `link` until `done` or five seconds pass; returns `done`.
  template <typename Done>
  bool pump(WebSocketLink& link, std::vector<std::vector<uint8_t>>& received, Done done) {
    const auto until = std::chrono::steady_clock::now() + 5s;
    while (!done() && std::chrono::steady_clock::now() < until) {
      link.poll([&](std::span<const uint8_t> d) { received.emplace_back(d.begin(), d.end()); });
      std::this_thread::sleep_for(1ms);
    }
    return done();
  }

  std::vector<std::pair<std::vector<uint8_t>, asio::ip::udp::endpoint>> drain() {
    std::vector<std::pair<std::vector<uint8_t>, asio::ip::udp::endpoint>> got;
    port_->drain([&](std::span<const uint8_t> d, const asio::ip::udp::endpoint& from) {
      got.emplace_back(std::vector<uint8_t>(d.begin(), d.end()), from);
    });
    return got;
  }

  WebSocketLimits limits_;
  std::shared_ptr<WebSocketPort> port_;
  std::unique_ptr<WebSocketEndpoint> endpoint_;
};

TEST_F(WebSocketEndpointTest, BinaryMessagesAreDatagramsBothWays) {
  auto link = WebSocketLink::open(url("duel"));
  ASSERT_TRUE(link.ok());
  std::vector<std::vector<uint8_t>> received;
  (*link)->send(bytes({1, 2, 3}));  // before the connection is open: it waits
  std::vector<std::pair<std::vector<uint8_t>, asio::ip::udp::endpoint>> got;
  ASSERT_TRUE(pump(**link, received, [&] {
    for (auto& d : drain()) got.push_back(std::move(d));
    return !got.empty();
  })) << (*link)->error();
  EXPECT_EQ(got[0].first, bytes({1, 2, 3}));
  EXPECT_TRUE(WebSocketPort::is_websocket_endpoint(got[0].second));

  port_->send(bytes({4, 5}), got[0].second);
  port_->send(bytes({6}), got[0].second);
  ASSERT_TRUE(pump(**link, received, [&] { return received.size() == 2; }));
  EXPECT_EQ(received[0], bytes({4, 5}));
  EXPECT_EQ(received[1], bytes({6}));
  EXPECT_EQ(endpoint_->stats().upgraded, 1u);
  EXPECT_EQ(endpoint_->stats().bytes_in, 3u);

  // The match ends: the browser's connection closes.
  port_->close();
  ASSERT_TRUE(
      pump(**link, received, [&] { return (*link)->state() == WebSocketLink::State::kClosed; }));
}

TEST_F(WebSocketEndpointTest, AnUnknownMatchIsNotFound) {
  auto link = WebSocketLink::open(url("nosuch"));
  ASSERT_TRUE(link.ok());
  std::vector<std::vector<uint8_t>> received;
  ASSERT_TRUE(
      pump(**link, received, [&] { return (*link)->state() == WebSocketLink::State::kClosed; }));
  EXPECT_NE((*link)->error().find("handshake"), std::string::npos) << (*link)->error();
  EXPECT_EQ(endpoint_->stats().not_found, 1u);

  testing_http::Client http(endpoint_->port());
  const std::string answer = http.exchange(
      "GET /matches/nosuch HTTP/1.1\r\nHost: x\r\nConnection: Upgrade\r\nUpgrade: websocket\r\n"
      "Sec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n");
  EXPECT_EQ(testing_http::status_of(answer), 404) << answer;
  EXPECT_NE(testing_http::body_of(answer).find("no match 'nosuch'"), std::string::npos);
}

TEST_F(WebSocketEndpointTest, APlainRequestIsToldToUpgrade) {
  testing_http::Client http(endpoint_->port());
  const std::string answer = http.exchange("GET /matches/duel HTTP/1.1\r\nHost: x\r\n\r\n");
  EXPECT_EQ(testing_http::status_of(answer), 426) << answer;
  EXPECT_EQ(endpoint_->stats().not_upgrade, 1u);
  EXPECT_EQ(port_->stats().connections, 0u);
}

namespace beast = boost::beast;
namespace websocket = beast::websocket;
namespace basio = boost::asio;

// A blocking client that can misbehave: text messages, oversized ones.
struct RawClient {
  explicit RawClient(uint16_t port, const std::string& protocol = "") : ws(io) {
    basio::ip::tcp::resolver resolver(io);
    basio::connect(ws.next_layer(), resolver.resolve("127.0.0.1", std::to_string(port)));
    ws.set_option(websocket::stream_base::decorator([protocol](websocket::request_type& r) {
      if (!protocol.empty()) r.set(beast::http::field::sec_websocket_protocol, protocol);
    }));
    ws.handshake(response, "127.0.0.1", "/matches/duel");
  }
  // Reads until the server closes; the error it ended with.
  boost::system::error_code read_until_closed() {
    beast::flat_buffer buffer;
    boost::system::error_code error;
    while (!error) ws.read(buffer, error);
    return error;
  }
  basio::io_context io;
  websocket::stream<basio::ip::tcp::socket> ws;
  websocket::response_type response;
};

TEST_F(WebSocketEndpointTest, TheRewindSubprotocolIsEchoed) {
  RawClient offered(endpoint_->port(), "chat, rewind");
  EXPECT_EQ(offered.response[beast::http::field::sec_websocket_protocol], "rewind");
  RawClient plain(endpoint_->port());
  EXPECT_TRUE(plain.response[beast::http::field::sec_websocket_protocol].empty());
}

TEST_F(WebSocketEndpointTest, TextAndOversizedMessagesCloseTheConnection) {
  RawClient text(endpoint_->port());
  text.ws.text(true);
  text.ws.write(basio::buffer(std::string("hello")));
  EXPECT_TRUE(text.read_until_closed());

  RawClient big(endpoint_->port());
  big.ws.binary(true);
  const std::vector<uint8_t> oversized(4096, 1);
  boost::system::error_code error;
  big.ws.write(basio::buffer(oversized), error);
  EXPECT_TRUE(big.read_until_closed());

  // The endpoint counts and detaches on its own thread, maybe after the
  // client has seen the close.
  for (int i = 0; i < 2500 && (port_->stats().open != 0 || endpoint_->stats().refused != 2); ++i) {
    std::this_thread::sleep_for(2ms);
  }
  EXPECT_EQ(endpoint_->stats().refused, 2u);
  EXPECT_EQ(port_->stats().open, 0u);
  EXPECT_TRUE(drain().empty());  // neither reached the match
}

TEST_F(WebSocketEndpointTest, AfterCloseNothingConnects) {
  endpoint_->close();
  auto link = WebSocketLink::open(url("duel"));
  ASSERT_TRUE(link.ok());
  std::vector<std::vector<uint8_t>> received;
  ASSERT_TRUE(
      pump(**link, received, [&] { return (*link)->state() == WebSocketLink::State::kClosed; }));
  endpoint_->close();  // idempotent
}

TEST(WebSocketEndpoint, BadSettingsAreRefused) {
  const auto none = [](std::string_view) { return std::shared_ptr<WebSocketPort>(); };
  EXPECT_EQ(WebSocketEndpoint::open("not-an-address", 0, none).status().code(),
            ErrorCode::kInvalidArgument);
  WebSocketLimits limits;
  limits.max_queued_bytes = 10;
  EXPECT_EQ(WebSocketEndpoint::open("127.0.0.1", 0, none, limits).status().code(),
            ErrorCode::kInvalidArgument);
  HttpTls tls{"/nonexistent/cert.pem", "/nonexistent/key.pem", ""};
  auto with_tls = WebSocketEndpoint::open("127.0.0.1", 0, none, {}, tls);
  EXPECT_EQ(with_tls.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(with_tls.status().message().find("cert.pem"), std::string::npos);
}

TEST(WebSocketLinkUrl, OnlyPlainWebSocketUrlsAreTaken) {
  for (const char* bad : {"http://a:1/", "wss://a:1/", "ws://:1/", "ws://a/", "ws://a:0/",
                          "ws://a:70000/", "ws://[::1/", "ws://a:x/"}) {
    EXPECT_EQ(WebSocketLink::open(bad).status().code(), ErrorCode::kInvalidArgument) << bad;
  }
  EXPECT_TRUE(WebSocketLink::open("ws://[::1]:7/matches/m").ok());
  EXPECT_TRUE(WebSocketLink::open("ws://localhost:7").ok());
}

}  // namespace
}  // namespace rwd::server
