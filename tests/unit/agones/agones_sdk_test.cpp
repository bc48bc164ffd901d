// SPDX-License-Identifier: MIT
// The Agones SDK client: the sidecar's port from the environment, and the
// calls' requests, answers and failures against a loopback HTTP server.
#include "rewind/server/agones_sdk.h"

#include <gtest/gtest.h>

#include <asio/ip/tcp.hpp>
#include <chrono>
#include <string>

#include "local_http_server.h"

namespace rwd::server {
namespace {

using testing::LocalHttpServer;

TEST(AgonesSdk, PortFromTheEnvironment) {
  EXPECT_EQ(*agones_port_from_env(nullptr), kAgonesDefaultHttpPort);
  EXPECT_EQ(*agones_port_from_env("9358"), 9358);
  EXPECT_EQ(*agones_port_from_env("65535"), 65535);
  for (const char* bad : {"", "0", "65536", "-1", "+80", " 80", "80 ", "abc", "123456"}) {
    auto port = agones_port_from_env(bad);
    ASSERT_FALSE(port.ok()) << bad;
    EXPECT_EQ(port.status().code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(port.status().message(),
              "AGONES_SDK_HTTP_PORT='" + std::string(bad) + "' is not a port number in [1, 65535]");
  }
}

AgonesSdk sdk_for(uint16_t port, std::chrono::milliseconds deadline = std::chrono::seconds(2)) {
  AgonesSdk::Options options;
  options.host = "127.0.0.1";
  options.port = port;
  options.call_deadline = deadline;
  return AgonesSdk(options);
}

TEST(AgonesSdk, LifecycleCallsPostAnEmptyMessage) {
  LocalHttpServer sidecar(
      [](const std::string&) { return LocalHttpServer::json_answer("200 OK", "{}"); });
  const AgonesSdk sdk = sdk_for(sidecar.port());
  ASSERT_TRUE(sdk.ready().ok());
  ASSERT_TRUE(sdk.health().ok());
  ASSERT_TRUE(sdk.shutdown().ok());
  const std::vector<std::string> requests = sidecar.requests();
  ASSERT_EQ(requests.size(), 3u);
  const char* paths[] = {"/ready", "/health", "/shutdown"};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(requests[i].rfind(std::string("POST ") + paths[i] + " HTTP/1.1\r\n", 0), 0u)
        << requests[i];
    EXPECT_NE(requests[i].find("Content-Type: application/json\r\n"), std::string::npos);
    EXPECT_NE(requests[i].find("Content-Length: 2\r\n"), std::string::npos);
    EXPECT_NE(requests[i].find("Connection: close\r\n"), std::string::npos);
    EXPECT_EQ(requests[i].substr(requests[i].size() - 6), "\r\n\r\n{}");
  }
}

TEST(AgonesSdk, GameServerIsReadFromTheAnswer) {
  LocalHttpServer sidecar([](const std::string& request) {
    if (request.rfind("GET /gameserver ", 0) != 0)
      return LocalHttpServer::json_answer("404 No", "");
    return LocalHttpServer::json_answer("200 OK", R"({"status":{"state":"Ready"}})");
  });
  auto gs = sdk_for(sidecar.port()).game_server();
  ASSERT_TRUE(gs.ok()) << gs.status().message();
  EXPECT_EQ(gs->state, "Ready");
  EXPECT_EQ(sidecar.requests().at(0).find("Content-Length"), std::string::npos);
}

TEST(AgonesSdk, ErrorsNameTheCallAndTheCause) {
  LocalHttpServer failing([](const std::string&) {
    return LocalHttpServer::json_answer("500 Internal Server Error", "{\"error\":\"no\nway\"}");
  });
  const Status failed = sdk_for(failing.port()).ready();
  EXPECT_EQ(failed.code(), ErrorCode::kIo);
  EXPECT_EQ(failed.message(),
            "POST /ready: HTTP 500 Internal Server Error: {\"error\":\"no way\"}");

  LocalHttpServer garbled([](const std::string&) { return std::string("SSH-2.0-x\r\n\r\n"); });
  const Status bad = sdk_for(garbled.port()).health();
  EXPECT_EQ(bad.code(), ErrorCode::kCorrupt);
  EXPECT_EQ(bad.message(), "HTTP POST /health to 127.0.0.1:" + std::to_string(garbled.port()) +
                               ": malformed response: bad version");

  LocalHttpServer not_json(
      [](const std::string&) { return LocalHttpServer::json_answer("200 OK", "<html>"); });
  auto gs = sdk_for(not_json.port()).game_server();
  ASSERT_FALSE(gs.ok());
  EXPECT_EQ(gs.status().code(), ErrorCode::kCorrupt);
  EXPECT_EQ(gs.status().message().rfind("GameServer: JSON: parse error at line 1, column 1: ", 0),
            0u)
      << gs.status().message();
}

TEST(AgonesSdk, NoListenerIsAnIoError) {
  uint16_t port = 0;
  {
    asio::io_context io;
    asio::ip::tcp::acceptor probe(io,
                                  asio::ip::tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    port = probe.local_endpoint().port();
  }  // closed again: nothing listens there now
  const Status status = sdk_for(port).ready();
  EXPECT_EQ(status.code(), ErrorCode::kIo);
  EXPECT_EQ(status.message().rfind(
                "HTTP POST /ready to 127.0.0.1:" + std::to_string(port) + ": connect: ", 0),
            0u)
      << status.message();
}

TEST(AgonesSdk, ASilentSidecarTimesOut) {
  LocalHttpServer silent([](const std::string&) { return std::string(); });
  const auto start = std::chrono::steady_clock::now();
  const Status status = sdk_for(silent.port(), std::chrono::milliseconds(200)).health();
  const auto took = std::chrono::steady_clock::now() - start;
  EXPECT_EQ(status.code(), ErrorCode::kIo);
  EXPECT_EQ(status.message(), "HTTP POST /health to 127.0.0.1:" + std::to_string(silent.port()) +
                                  ": read: no answer within 200 ms");
  EXPECT_GE(took, std::chrono::milliseconds(190));
  EXPECT_LT(took, std::chrono::seconds(2));
}

TEST(AgonesSdk, AnOversizedAnswerIsRefused) {
  LocalHttpServer flood([](const std::string&) {
    return LocalHttpServer::json_answer("200 OK", "\"" + std::string(2 << 20, 'x') + "\"");
  });
  auto gs = sdk_for(flood.port()).game_server();
  ASSERT_FALSE(gs.ok());
  EXPECT_EQ(gs.status().code(), ErrorCode::kCapacity);
}

}  // namespace
}  // namespace rwd::server
