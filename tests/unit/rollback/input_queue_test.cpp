// SPDX-License-Identifier: MIT
#include "rewind/net/input_queue.h"

#include "rewind/core/stick_input.h"

#include <gtest/gtest.h>

namespace rwd::net {
namespace {

rwd::PlayerInput in(int16_t x, uint32_t buttons = 0) {
  return rwd::stick_input(x, 0, buttons);
}

TEST(InputQueue, PredictsNeutralBeforeAnyInput) {
  InputQueue q(16);
  EXPECT_EQ(q.input_for(0), rwd::PlayerInput{});
  EXPECT_EQ(q.input_for(10), rwd::PlayerInput{});
  EXPECT_EQ(q.contiguous_through(), -1);
  EXPECT_EQ(q.newest(), kNoTick);
}

// A predictor that releases the buttons: what a game might say of a fire
// button, pressed for a tick and not held.
rwd::PlayerInput release_buttons(const rwd::PlayerInput& newest) {
  rwd::StickInput stick = newest.as<rwd::StickInput>();
  stick.buttons = 0;
  return rwd::PlayerInput::of(stick);
}

TEST(InputQueue, AGamesPredictorGuessesUnconfirmedTicks) {
  InputQueue q(16, 0, &release_buttons);
  EXPECT_EQ(q.add(0, in(5, 3)), InputQueue::AddOutcome::kNew);
  EXPECT_EQ(q.input_for(0), in(5, 3));  // confirmed: as sent
  EXPECT_EQ(q.input_for(1), in(5));     // predicted from tick 0, once
  EXPECT_EQ(q.input_for(7), in(5));
  // After the queue moves on, the carried input is the confirmed one.
  q.discard_before(4);
  EXPECT_EQ(q.input_for(4), in(5));
  q.rebase(2);
  EXPECT_EQ(q.input_for(2), in(5));
  EXPECT_EQ(q.add(6, in(-1, 8)), InputQueue::AddOutcome::kNew);
  EXPECT_EQ(q.input_for(6), in(-1, 8));
  EXPECT_EQ(q.input_for(9), in(-1));
}

TEST(InputQueue, RepeatsNewestEarlierInput) {
  InputQueue q(16);
  EXPECT_EQ(q.add(0, in(5)), InputQueue::AddOutcome::kNew);
  EXPECT_EQ(q.add(3, in(7)), InputQueue::AddOutcome::kNew);
  EXPECT_EQ(q.input_for(0), in(5));
  EXPECT_EQ(q.input_for(1), in(5));  // predicted from tick 0
  EXPECT_EQ(q.input_for(2), in(5));
  EXPECT_EQ(q.input_for(3), in(7));
  EXPECT_EQ(q.input_for(9), in(7));
  EXPECT_EQ(q.contiguous_through(), 0);
  EXPECT_TRUE(q.is_confirmed(3));
  EXPECT_FALSE(q.is_confirmed(2));
}

TEST(InputQueue, FirstWriterWinsAndAuthoritativeOverrides) {
  InputQueue q(16);
  EXPECT_EQ(q.add(2, in(1)), InputQueue::AddOutcome::kNew);
  EXPECT_EQ(q.add(2, in(1)), InputQueue::AddOutcome::kDuplicate);
  EXPECT_EQ(q.add(2, in(9)), InputQueue::AddOutcome::kConflict);
  EXPECT_EQ(q.input_for(2), in(1));
  EXPECT_EQ(q.set_authoritative(2, in(9)), InputQueue::AddOutcome::kNew);
  EXPECT_EQ(q.input_for(2), in(9));
  EXPECT_EQ(q.set_authoritative(2, in(9)), InputQueue::AddOutcome::kDuplicate);
}

TEST(InputQueue, RejectsTicksOutsideItsWindow) {
  InputQueue q(8, 10);
  EXPECT_EQ(q.add(9, in(1)), InputQueue::AddOutcome::kOutOfRange);
  EXPECT_EQ(q.add(18, in(1)), InputQueue::AddOutcome::kOutOfRange);
  EXPECT_EQ(q.add(17, in(1)), InputQueue::AddOutcome::kNew);
  EXPECT_EQ(q.contiguous_through(), 9);
}

TEST(InputQueue, ContiguousAdvancesOverOutOfOrderArrivals) {
  InputQueue q(16);
  (void)q.add(2, in(2));
  (void)q.add(1, in(1));
  EXPECT_EQ(q.contiguous_through(), -1);
  (void)q.add(0, in(0));
  EXPECT_EQ(q.contiguous_through(), 2);
}

TEST(InputQueue, DiscardKeepsPredictionSeedAndFreesSpace) {
  InputQueue q(8);
  for (Tick t = 0; t < 6; ++t) (void)q.add(t, in(static_cast<int16_t>(t + 1)));
  q.discard_before(6);
  EXPECT_EQ(q.base(), 6);
  EXPECT_EQ(q.input_for(7), in(6));                            // seed = input of tick 5
  EXPECT_EQ(q.add(13, in(40)), InputQueue::AddOutcome::kNew);  // space freed
  EXPECT_EQ(q.contiguous_through(), 5);
}

TEST(InputQueue, RebaseBackwardsKeepsLaterInputs) {
  InputQueue q(16, 10);
  (void)q.add(10, in(1));
  (void)q.add(12, in(3));
  q.rebase(8);
  EXPECT_EQ(q.base(), 8);
  EXPECT_TRUE(q.is_confirmed(10));
  EXPECT_TRUE(q.is_confirmed(12));
  EXPECT_FALSE(q.is_confirmed(11));
  q.rebase(11);
  EXPECT_FALSE(q.is_confirmed(10));
  EXPECT_EQ(q.input_for(11), in(1));
}

}  // namespace
}  // namespace rwd::net
