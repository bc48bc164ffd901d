// SPDX-License-Identifier: MIT
// InputSender on its own: each tick's input taken once, resent until the
// server acknowledges it (then trimmed), at most the newest 64 a frame, and
// the acknowledgement of final ticks waiting a tick period for a frame.
#include "input_sender.h"

#include <gtest/gtest.h>

#include <chrono>
#include <map>

#include "rewind/core/stick_input.h"
#include "rewind/proto/input_wire.h"

namespace rwd::client {
namespace {

rwd::PlayerInput sender_input(Tick tick) {
  return rwd::stick_input(static_cast<int16_t>(tick * 10 - 500), static_cast<int16_t>(tick % 5));
}

InputSender sender_with_provider(std::map<Tick, int>& calls) {
  InputSender sender;
  sender.set_provider([&calls](Tick tick) {
    ++calls[tick];
    return sender_input(tick);
  });
  return sender;
}

TEST(InputSender, ResendsEveryInputUntilAcknowledged) {
  std::map<Tick, int> calls;
  InputSender sender = sender_with_provider(calls);
  for (Tick t = 0; t < 10; ++t) {
    ASSERT_TRUE(sender.due(t));
    EXPECT_EQ(sender.take(t, rwd::stick_input_spec()), sender_input(t));
    EXPECT_FALSE(sender.due(t));
  }
  EXPECT_EQ(sender.next_input_tick(), 10);
  EXPECT_EQ(calls.size(), 10u);

  v1::InputFrame frame;
  sender.write_frame(1, kNoTick, frame);
  EXPECT_EQ(frame.player(), 1u);
  EXPECT_EQ(frame.first_tick(), 0);
  ASSERT_EQ(frame.inputs_size(), 10);
  for (int k = 0; k < frame.inputs_size(); ++k) {
    auto input = proto::from_wire(frame.inputs(k));
    ASSERT_TRUE(input.ok());
    EXPECT_EQ(*input, sender_input(k));
  }

  // Acknowledged through tick 5: the next frame starts at 6, and the
  // acknowledged inputs are gone for good.
  sender.on_ack(5);
  sender.on_ack(3);  // an older acknowledgement arriving late changes nothing
  frame.Clear();
  sender.write_frame(1, kNoTick, frame);
  EXPECT_EQ(frame.first_tick(), 6);
  EXPECT_EQ(frame.inputs_size(), 4);
  EXPECT_EQ(sender.unacked(), 4u);

  // Everything acknowledged: an empty frame naming the next tick.
  sender.on_ack(9);
  frame.Clear();
  sender.write_frame(1, kNoTick, frame);
  EXPECT_EQ(frame.first_tick(), 10);
  EXPECT_EQ(frame.inputs_size(), 0);
  for (const auto& [tick, count] : calls) EXPECT_EQ(count, 1) << "tick " << tick;
}

TEST(InputSender, CarriesAtMostTheNewestInputsAFrame) {
  std::map<Tick, int> calls;
  InputSender sender = sender_with_provider(calls);
  for (Tick t = 0; t < 100; ++t) (void)sender.take(t, rwd::stick_input_spec());
  v1::InputFrame frame;
  sender.write_frame(0, kNoTick, frame);
  ASSERT_EQ(frame.inputs_size(), static_cast<int>(InputSender::kMaxInputsPerPacket));
  EXPECT_EQ(frame.first_tick(), 100 - static_cast<Tick>(InputSender::kMaxInputsPerPacket));
  auto newest = proto::from_wire(frame.inputs(frame.inputs_size() - 1));
  ASSERT_TRUE(newest.ok());
  EXPECT_EQ(*newest, sender_input(99));
}

TEST(InputSender, PlaysTheNeutralInputForOneTheSpecRefuses) {
  InputSender sender;
  sender.hold(rwd::stick_input(5000, 0));  // beyond the axis range
  EXPECT_EQ(sender.take(0, rwd::stick_input_spec()), rwd::PlayerInput{});
  sender.hold(rwd::stick_input(700, -300));
  EXPECT_EQ(sender.take(1, rwd::stick_input_spec()), rwd::stick_input(700, -300));
  v1::InputFrame frame;
  sender.write_frame(0, kNoTick, frame);
  ASSERT_EQ(frame.inputs_size(), 2);
  auto first = proto::from_wire(frame.inputs(0));
  ASSERT_TRUE(first.ok());
  EXPECT_EQ(*first, rwd::PlayerInput{});
}

TEST(InputSender, SkipsTheTicksBeforeAResync) {
  InputSender sender;
  (void)sender.take(0, rwd::stick_input_spec());
  sender.skip_to(40);
  EXPECT_EQ(sender.next_input_tick(), 40);
  EXPECT_FALSE(sender.due(39));
  sender.skip_to(20);  // never backwards
  EXPECT_EQ(sender.next_input_tick(), 40);
}

TEST(InputSender, AnAcknowledgementWaitsATickPeriodForAFrame) {
  constexpr double kPeriodS = 1.0 / 60;
  const net::TimePoint t0{};
  InputSender sender;
  EXPECT_EQ(sender.ack_wait(kNoTick, t0, kPeriodS), InputSender::AckWait::kNone);
  EXPECT_EQ(sender.ack_wait(3, t0, kPeriodS), InputSender::AckWait::kWaiting);
  // Newer final ticks while waiting do not restart the wait.
  EXPECT_EQ(sender.ack_wait(5, t0 + std::chrono::milliseconds(10), kPeriodS),
            InputSender::AckWait::kWaiting);
  EXPECT_EQ(sender.ack_wait(5, t0 + std::chrono::milliseconds(17), kPeriodS),
            InputSender::AckWait::kDue);

  // A frame carries it: nothing left to acknowledge, and the next wait
  // starts afresh.
  v1::InputFrame frame;
  sender.write_frame(0, 5, frame);
  EXPECT_EQ(frame.last_final_tick_seen(), 5);
  EXPECT_EQ(sender.last_final_acked(), 5);
  const net::TimePoint t1 = t0 + std::chrono::milliseconds(40);
  EXPECT_EQ(sender.ack_wait(5, t1, kPeriodS), InputSender::AckWait::kNone);
  EXPECT_EQ(sender.ack_wait(6, t1, kPeriodS), InputSender::AckWait::kWaiting);
  EXPECT_EQ(sender.ack_wait(6, t1 + std::chrono::milliseconds(5), kPeriodS),
            InputSender::AckWait::kWaiting);
}

}  // namespace
}  // namespace rwd::client
