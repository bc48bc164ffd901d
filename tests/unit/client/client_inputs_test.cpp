// SPDX-License-Identifier: MIT
// ClientProtocol's input packets: each input taken once and resent until
// acknowledged, and the acknowledgement of final ticks riding on the next
// input packet (one datagram a player a tick), alone only when none follows.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "client_protocol_harness.h"
#include "rewind/proto/input_wire.h"

namespace rwd::test {
namespace {

TEST(ClientProtocol, TakesEachInputOnceAndResendsItUntilAcknowledged) {
  Harness h;
  h.join_and_start();
  std::map<Tick, rwd::PlayerInput> seen;  // every input the frames carried
  Tick newest_sent = kNoTick;
  for (int i = 0; i < 20; ++i) {
    h.advance(kTick);
    for (const v1::Envelope& e : h.sent()) {
      if (!e.has_input_frame()) continue;
      const v1::InputFrame& frame = e.input_frame();
      EXPECT_EQ(frame.player(), 0u);
      // Redundancy: with nothing acknowledged, every frame starts at tick 0.
      EXPECT_EQ(frame.first_tick(), 0);
      for (int k = 0; k < frame.inputs_size(); ++k) {
        const Tick tick = frame.first_tick() + k;
        auto input = proto::from_wire(frame.inputs(k));
        ASSERT_TRUE(input.ok());
        EXPECT_EQ(*input, own_input(tick));
        seen[tick] = *input;
        newest_sent = std::max(newest_sent, tick);
      }
    }
  }
  ASSERT_GE(h.client_tick(), 18);
  EXPECT_EQ(newest_sent, h.client_tick() - 1);
  EXPECT_EQ(seen.size(), static_cast<size_t>(h.client_tick()));
  // The provider was asked exactly once per simulated tick.
  ASSERT_EQ(h.provided.size(), static_cast<size_t>(h.client_tick()));
  for (const auto& [tick, calls] : h.provided) EXPECT_EQ(calls, 1) << "tick " << tick;

  // Once the server acknowledges through tick 9, frames start at 10.
  h.catch_up_server();
  h.deliver(h.server.final_ticks(0, 0, 9, h.now));
  h.advance(kTick);
  bool checked = false;
  for (const v1::Envelope& e : h.sent()) {
    if (!e.has_input_frame()) continue;
    EXPECT_EQ(e.input_frame().first_tick(), 10);
    EXPECT_EQ(e.input_frame().last_final_tick_seen(), 0);
    checked = true;
  }
  EXPECT_TRUE(checked);
}

std::vector<v1::InputFrame> input_frames(const std::vector<v1::Envelope>& sent) {
  std::vector<v1::InputFrame> out;
  for (const v1::Envelope& e : sent) {
    if (e.has_input_frame()) out.push_back(e.input_frame());
  }
  return out;
}

TEST(ClientProtocol, AcknowledgementsRideOnTheNextInputPacket) {
  Harness h;
  h.join_and_start();
  h.run(4);
  (void)h.sent();
  Tick delivered = kNoTick;
  for (int i = 0; i < 30; ++i) {
    // The server's broadcast lands between two of the client's ticks: the
    // client reads it at once, but sends nothing until its next tick.
    h.catch_up_server();
    const Tick newest = h.server.next_tick() - 1;
    h.deliver(h.server.final_ticks(delivered + 1, newest, newest, h.now));
    delivered = newest;
    const Tick before = h.client_tick();
    h.advance(std::chrono::microseconds(0));
    if (h.client_tick() == before) {
      EXPECT_TRUE(input_frames(h.sent()).empty())
          << "period " << i << ": the acknowledgement went alone, a tick before an input packet";
    }
    h.advance(kTick);
    // At most one input packet a tick; it carries the acknowledgement.
    const auto sent = input_frames(h.sent());
    ASSERT_EQ(sent.size(), 1u) << "period " << i;
    EXPECT_EQ(sent.back().last_final_tick_seen(), delivered) << "period " << i;
  }
  EXPECT_EQ(h.protocol.stats().final_ticks_verified, static_cast<uint64_t>(delivered + 1));
}

TEST(ClientProtocol, AcknowledgementGoesAloneWhenNoInputPacketTakesItWithinATick) {
  Harness h;
  h.start_ending();
  ASSERT_EQ(h.protocol.phase(), ClientPhase::kEnding);
  (void)h.sent();
  // Every input is sent; final ticks 6..8 still need acknowledging.
  h.deliver(h.server.final_ticks(6, 8, 11, h.now));
  h.advance(std::chrono::microseconds(0));
  EXPECT_TRUE(input_frames(h.sent()).empty());
  h.advance(kTick / 2);
  EXPECT_TRUE(input_frames(h.sent()).empty());
  h.advance(kTick / 2 + std::chrono::microseconds(1));
  const auto frames = input_frames(h.sent());
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].last_final_tick_seen(), 8);
}

}  // namespace
}  // namespace rwd::test
