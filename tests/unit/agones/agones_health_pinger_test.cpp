// SPDX-License-Identifier: MIT
// Health pings on their own thread: one at once and then every period,
// failures counted without stopping, withheld while the process is not
// healthy, and stop() prompt even mid-period.
#include "rewind/server/agones_health_pinger.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <thread>

#include "local_http_server.h"
#include "rewind/server/load_monitor.h"

namespace rwd::server {
namespace {

using namespace std::chrono_literals;
using testing::LocalHttpServer;

AgonesSdk sdk_for(uint16_t port) {
  AgonesSdk::Options options;
  options.host = "127.0.0.1";
  options.port = port;
  // Generous: a loaded machine must not turn a slow answer into a failure.
  options.call_deadline = 5s;
  return AgonesSdk(options);
}

// Waits (without a bound on speed, up to a generous deadline) for `done`.
bool eventually(const std::function<bool()>& done) {
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(5ms);
  }
  return true;
}

TEST(AgonesHealthPinger, PingsEveryPeriod) {
  LocalHttpServer sidecar(
      [](const std::string&) { return LocalHttpServer::json_answer("200 OK", "{}"); });
  const AgonesSdk sdk = sdk_for(sidecar.port());
  const auto start = std::chrono::steady_clock::now();
  AgonesHealthPinger pinger(sdk, 50ms);
  ASSERT_TRUE(eventually([&] { return pinger.sent() >= 4; }));
  pinger.stop();
  // One at once, then one a period: a loaded machine may fall behind the
  // grid, never ahead of it.
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_LE(pinger.sent(), 2u + static_cast<uint64_t>(elapsed / 50ms));
  EXPECT_EQ(pinger.failed(), 0u);
  const std::vector<std::string> requests = sidecar.requests();
  EXPECT_EQ(requests.size(), pinger.sent());
  for (const std::string& request : requests) {
    EXPECT_EQ(request.rfind("POST /health HTTP/1.1\r\n", 0), 0u);
  }
}

TEST(AgonesHealthPinger, FailuresAreCountedAndPingingGoesOn) {
  LocalHttpServer sidecar([](const std::string&) {
    return LocalHttpServer::json_answer("503 Service Unavailable", "{}");
  });
  const AgonesSdk sdk = sdk_for(sidecar.port());
  AgonesHealthPinger pinger(sdk, 20ms);
  ASSERT_TRUE(eventually([&] { return pinger.sent() >= 3; }));
  pinger.stop();
  EXPECT_GE(pinger.sent(), 3u);
  EXPECT_EQ(pinger.failed(), pinger.sent());
}

TEST(AgonesHealthPinger, PingsAreWithheldWhileTheProcessIsUnhealthy) {
  LocalHttpServer sidecar(
      [](const std::string&) { return LocalHttpServer::json_answer("200 OK", "{}"); });
  const AgonesSdk sdk = sdk_for(sidecar.port());
  std::atomic<bool> slipping{true};
  AgonesHealthPinger pinger(sdk, 10ms, [&slipping]() -> std::string {
    return slipping.load() ? "ticks have slipped for 10 s in a row" : "";
  });
  ASSERT_TRUE(eventually([&] { return pinger.withheld() >= 3; }));
  EXPECT_EQ(pinger.sent(), 0u);
  EXPECT_TRUE(sidecar.requests().empty());
  // Healthy again: pings resume.
  slipping.store(false);
  ASSERT_TRUE(eventually([&] { return pinger.sent() >= 2; }));
  pinger.stop();
  EXPECT_EQ(pinger.failed(), 0u);
  EXPECT_EQ(sidecar.requests().size(), pinger.sent());
}

TEST(AgonesHealthPinger, ALoadMonitorWhoseMatchStoppedTickingWithholdsPings) {
  // As run_agones_match wires it: the pinger asks the load monitor. A match
  // that started ten (made-up) seconds ago and never ticked is a stalled
  // loop, whatever the machine's speed.
  LocalHttpServer sidecar(
      [](const std::string&) { return LocalHttpServer::json_answer("200 OK", "{}"); });
  const AgonesSdk sdk = sdk_for(sidecar.port());
  const auto now = std::chrono::steady_clock::now();
  auto load = std::make_shared<LoadMonitor>(0.75, now - 10s);
  load->match_started(now - 10s);
  AgonesHealthPinger pinger(
      sdk, 10ms, [load] { return load->unhealthy_reason(std::chrono::steady_clock::now()); });
  ASSERT_TRUE(eventually([&] { return pinger.withheld() >= 2; }));
  EXPECT_EQ(pinger.sent(), 0u);
  // The match ends: nothing is live, so nothing is stalled.
  load->match_ended();
  ASSERT_TRUE(eventually([&] { return pinger.sent() >= 1; }));
  pinger.stop();
}

TEST(AgonesHealthPinger, StopDoesNotWaitForTheNextPeriod) {
  LocalHttpServer sidecar(
      [](const std::string&) { return LocalHttpServer::json_answer("200 OK", "{}"); });
  const AgonesSdk sdk = sdk_for(sidecar.port());
  AgonesHealthPinger pinger(sdk, 60s);
  ASSERT_TRUE(eventually([&] { return pinger.sent() == 1; }));  // the first goes out at once
  const auto start = std::chrono::steady_clock::now();
  pinger.stop();
  // Far below the 60 s period, however loaded the machine.
  EXPECT_LT(std::chrono::steady_clock::now() - start, 20s);
  EXPECT_EQ(pinger.sent(), 1u);
  pinger.stop();  // idempotent
}

}  // namespace
}  // namespace rwd::server
