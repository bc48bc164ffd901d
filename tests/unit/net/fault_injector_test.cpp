// SPDX-License-Identifier: MIT
#include "rewind/net/fault_injector.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include <asio/io_context.hpp>

namespace rwd::net {
namespace {

FaultInjector make(const FaultConfig& config) {
  Result<FaultInjector> r = FaultInjector::create(config);
  EXPECT_TRUE(r.ok()) << r.status().message();
  return std::move(r.value());
}

// 5 standard deviations of a binomial proportion over n trials.
double tolerance(double p, int n) {
  return 5.0 * std::sqrt(p * (1.0 - p) / n) + 1e-9;
}

TEST(FaultConfig, Validation) {
  EXPECT_TRUE(validate_fault_config({}).ok());
  EXPECT_TRUE(validate_fault_config({.latency_ms = 10'000,
                                     .jitter_ms = 10'000,
                                     .loss = 1.0,
                                     .duplicate = 1.0,
                                     .reorder = 1.0})
                  .ok());
  auto expect_bad = [](const FaultConfig& c, const char* field) {
    Status s = validate_fault_config(c);
    ASSERT_FALSE(s.ok()) << field;
    EXPECT_EQ(s.code(), ErrorCode::kInvalidArgument);
    EXPECT_NE(s.message().find(field), std::string::npos) << s.message();
    EXPECT_FALSE(FaultInjector::create(c).ok());
  };
  expect_bad({.loss = -0.1}, "loss");
  expect_bad({.loss = 1.5}, "loss");
  expect_bad({.loss = std::numeric_limits<double>::quiet_NaN()}, "loss");
  expect_bad({.duplicate = 2.0}, "duplicate");
  expect_bad({.reorder = -1e-9}, "reorder");
  expect_bad({.latency_ms = 10'001}, "latency_ms");
  expect_bad({.jitter_ms = 20'000}, "jitter_ms");
  expect_bad({.reorder_hold_ms = 0}, "reorder_hold_ms");
}

TEST(FaultInjector, RatesMatchConfigOver100kDecisions) {
  const FaultConfig config{.latency_ms = 50,
                           .jitter_ms = 20,
                           .loss = 0.1,
                           .duplicate = 0.05,
                           .reorder = 0.02,
                           .seed = 12345};
  FaultInjector injector = make(config);
  constexpr int kN = 100'000;
  int dropped = 0, duplicated = 0, reordered = 0, sent = 0;
  double delay_sum = 0;
  uint32_t min_delay = 1'000'000, max_delay = 0;
  for (int i = 0; i < kN; ++i) {
    const PacketFate f = injector.decide();
    if (f.dropped) {
      ++dropped;
      EXPECT_EQ(f.copies(), 0);
      continue;
    }
    ++sent;
    duplicated += f.duplicated;
    reordered += f.reordered;
    const uint32_t base = f.delay_ms - (f.reordered ? config.reorder_hold_ms : 0);
    min_delay = std::min(min_delay, base);
    max_delay = std::max(max_delay, base);
    delay_sum += base;
    if (f.duplicated) {
      EXPECT_GE(f.duplicate_delay_ms, 30u);
      EXPECT_LE(f.duplicate_delay_ms, 70u);
    }
  }
  EXPECT_NEAR(dropped / double(kN), 0.1, tolerance(0.1, kN));
  // Duplication and reordering apply to packets that were not dropped.
  EXPECT_NEAR(duplicated / double(sent), 0.05, tolerance(0.05, sent));
  EXPECT_NEAR(reordered / double(sent), 0.02, tolerance(0.02, sent));
  EXPECT_EQ(min_delay, 30u);
  EXPECT_EQ(max_delay, 70u);
  EXPECT_NEAR(delay_sum / sent, 50.0, 0.2);
}

TEST(FaultInjector, ExtremeProbabilities) {
  FaultInjector none = make({.latency_ms = 5, .seed = 3});
  FaultInjector all = make({.loss = 1.0, .seed = 3});
  FaultInjector twice = make({.duplicate = 1.0, .reorder = 1.0, .seed = 3});
  for (int i = 0; i < 10'000; ++i) {
    const PacketFate n = none.decide();
    EXPECT_EQ(n.copies(), 1);
    EXPECT_EQ(n.delay_ms, 5u);
    EXPECT_FALSE(n.reordered);
    EXPECT_TRUE(all.decide().dropped);
    const PacketFate t = twice.decide();
    EXPECT_EQ(t.copies(), 2);
    EXPECT_TRUE(t.reordered);
    EXPECT_EQ(t.delay_ms, 20u);  // latency 0 + default reorder hold
  }
}

TEST(FaultInjector, JitterNeverGoesNegative) {
  FaultInjector injector = make({.latency_ms = 2, .jitter_ms = 10, .seed = 9});
  int zero = 0;
  for (int i = 0; i < 10'000; ++i) {
    const PacketFate f = injector.decide();
    EXPECT_LE(f.delay_ms, 12u);
    zero += f.delay_ms == 0;
  }
  // Offsets -10..-2 all clamp to 0: about 9/21 of the packets.
  EXPECT_NEAR(zero / 10'000.0, 9.0 / 21.0, 0.03);
}

bool same_fate(const PacketFate& a, const PacketFate& b) {
  return a.dropped == b.dropped && a.duplicated == b.duplicated && a.reordered == b.reordered &&
         a.delay_ms == b.delay_ms && a.duplicate_delay_ms == b.duplicate_delay_ms;
}

TEST(FaultInjector, SameSeedSameFates) {
  const FaultConfig config{.latency_ms = 30,
                           .jitter_ms = 15,
                           .loss = 0.2,
                           .duplicate = 0.1,
                           .reorder = 0.1,
                           .seed = 777};
  FaultInjector a = make(config);
  FaultInjector b = make(config);
  FaultConfig other_seed = config;
  other_seed.seed = 778;
  FaultInjector c = make(other_seed);
  int differ = 0;
  for (int i = 0; i < 10'000; ++i) {
    const PacketFate fa = a.decide();
    ASSERT_TRUE(same_fate(fa, b.decide())) << "diverged at packet " << i;
    differ += !same_fate(fa, c.decide());
  }
  EXPECT_GT(differ, 5'000);
}

TEST(FaultInjector, DelaysDoNotDependOnLossRate) {
  // A fixed number of draws per packet: changing loss keeps the delays of
  // the surviving packets where they were.
  FaultInjector lossless = make({.latency_ms = 40, .jitter_ms = 30, .seed = 5});
  FaultInjector lossy = make({.latency_ms = 40, .jitter_ms = 30, .loss = 0.5, .seed = 5});
  for (int i = 0; i < 1000; ++i) {
    const PacketFate a = lossless.decide();
    const PacketFate b = lossy.decide();
    if (!b.dropped) {
      EXPECT_EQ(a.delay_ms, b.delay_ms);
    }
  }
}

using Endpoint = asio::ip::udp::endpoint;

struct Capture {
  std::vector<std::vector<uint8_t>> packets;
  FaultyLink::SendFunction fn() {
    return [this](std::span<const uint8_t> bytes, const Endpoint&) {
      packets.emplace_back(bytes.begin(), bytes.end());
    };
  }
};

TEST(FaultyLink, CreateValidates) {
  asio::io_context io;
  Capture capture;
  EXPECT_FALSE(FaultyLink::create(io, {.loss = 2.0}, capture.fn()).ok());
  EXPECT_FALSE(FaultyLink::create(io, {}, nullptr).ok());
  EXPECT_FALSE(FaultyLink::create(io, {}, capture.fn(), 0).ok());
}

TEST(FaultyLink, ZeroDelayPassesThroughInOrder) {
  asio::io_context io;
  Capture capture;
  Result<FaultyLink> link = FaultyLink::create(io, {}, capture.fn());
  ASSERT_TRUE(link.ok());
  for (uint8_t i = 0; i < 10; ++i) link->send(std::vector<uint8_t>{i}, Endpoint{});
  ASSERT_EQ(capture.packets.size(), 10u);
  for (uint8_t i = 0; i < 10; ++i) EXPECT_EQ(capture.packets[i][0], i);
  EXPECT_EQ(link->queued(), 0u);
  EXPECT_EQ(link->stats().delivered, 10u);
}

TEST(FaultyLink, ReorderLetsLaterPacketsOvertake) {
  asio::io_context io;
  Capture capture;
  Result<FaultyLink> link = FaultyLink::create(
      io, {.latency_ms = 1, .reorder = 0.3, .seed = 11, .reorder_hold_ms = 5}, capture.fn());
  ASSERT_TRUE(link.ok());
  for (uint8_t i = 0; i < 100; ++i) link->send(std::vector<uint8_t>{i}, Endpoint{});
  EXPECT_EQ(link->queued(), 100u);
  io.run_for(std::chrono::seconds(2));
  ASSERT_EQ(capture.packets.size(), 100u);
  int inversions = 0;
  for (size_t i = 1; i < capture.packets.size(); ++i) {
    inversions += capture.packets[i][0] < capture.packets[i - 1][0];
  }
  EXPECT_GT(link->stats().reordered, 10u);
  EXPECT_GT(inversions, 0);
}

TEST(FaultyLink, QueueIsBounded) {
  asio::io_context io;
  Capture capture;
  Result<FaultyLink> link = FaultyLink::create(io, {.latency_ms = 1000}, capture.fn(), 8);
  ASSERT_TRUE(link.ok());
  for (int i = 0; i < 20; ++i) link->send(std::vector<uint8_t>{1, 2, 3}, Endpoint{});
  EXPECT_EQ(link->queued(), 8u);
  EXPECT_EQ(link->stats().dropped_overflow, 12u);
  EXPECT_TRUE(capture.packets.empty());
}

TEST(FaultyLink, DestroyedWithPacketsQueuedIsSafe) {
  asio::io_context io;
  Capture capture;
  {
    Result<FaultyLink> link = FaultyLink::create(io, {.latency_ms = 5}, capture.fn());
    ASSERT_TRUE(link.ok());
    link->send(std::vector<uint8_t>{1}, Endpoint{});
  }
  // The cancelled timer completes after the link is gone.
  io.run_for(std::chrono::milliseconds(50));
  EXPECT_TRUE(capture.packets.empty());
}

}  // namespace
}  // namespace rwd::net
