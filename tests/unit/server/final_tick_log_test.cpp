// SPDX-License-Identifier: MIT
// The held final ticks: new ticks go first, packed against the tick before
// except the client's first; unacknowledged ticks come back only once a
// round trip has passed, round-robin; trimming drops what every client has.
#include <gtest/gtest.h>

#include "rewind/core/stick_input.h"
#include "rewind/proto/message_inputs.h"
#include "rewind/server/final_tick_log.h"

namespace rwd::server {
namespace {

std::vector<rwd::PlayerInput> inputs_at(Tick t) {
  return {rwd::stick_input(static_cast<int16_t>(t % 3 * 100), 0),
          rwd::stick_input(-500, static_cast<int16_t>(t % 5), 1)};
}

FinalTickLog log_of(Tick count, Tick made_every = 1) {
  FinalTickLog log;
  for (Tick t = 0; t < count; ++t) log.append(t, inputs_at(t), 0, 1000 + t, t * made_every);
  return log;
}

std::vector<Tick> ticks_in(const v1::FinalTicks& out) {
  std::vector<Tick> ticks;
  for (const v1::FinalTick& f : out.ticks()) ticks.push_back(f.tick());
  return ticks;
}

TEST(FinalTickLog, NewTicksFirstEachPackedAgainstTheOneBefore) {
  const FinalTickLog log = log_of(5);
  FinalTickLog::Cursor cursor;
  v1::FinalTicks out;
  log.add_to(out, 1000, cursor, 5, 0.0);
  EXPECT_EQ(ticks_in(out), (std::vector<Tick>{0, 1, 2, 3, 4}));
  EXPECT_EQ(cursor.sent, 4);
  // The client applies them in order: each reads against the one before.
  std::vector<rwd::PlayerInput> previous;
  for (const v1::FinalTick& f : out.ticks()) {
    EXPECT_EQ(f.delta(), f.tick() > 0);
    std::vector<rwd::PlayerInput> got;
    ASSERT_TRUE(proto::final_tick_inputs(f, previous, got).ok()) << f.tick();
    EXPECT_EQ(got, inputs_at(f.tick()));
    EXPECT_EQ(f.checksum(), 1000u + static_cast<uint64_t>(f.tick()));
    previous = got;
  }
  // Standalone from a snapshot's tick on.
  FinalTickLog::Cursor after_snapshot{2, 2, kNoTick, 3};
  v1::FinalTicks again;
  log.add_to(again, 1000, after_snapshot, 5, 0.0);
  ASSERT_EQ(ticks_in(again), (std::vector<Tick>{3, 4}));
  EXPECT_FALSE(again.ticks(0).delta());
  EXPECT_TRUE(again.ticks(1).delta());
}

TEST(FinalTickLog, UnacknowledgedTicksComeBackAfterARoundTrip) {
  const FinalTickLog log = log_of(10);
  // Everything was sent; the client acknowledged tick 3.
  FinalTickLog::Cursor cursor{3, 9, kNoTick, 0};
  v1::FinalTicks out;
  // At server tick 9 with a 4-tick round trip, ticks made at 3 or before
  // 9 - 4 - 2 = 3 are overdue: none past the acknowledgement.
  log.add_to(out, 1000, cursor, 9, 4.0);
  EXPECT_TRUE(ticks_in(out).empty());
  // Later, 4..6 are overdue and come back (round-robin from the cursor).
  out.Clear();
  log.add_to(out, 1000, cursor, 12, 4.0);
  EXPECT_EQ(ticks_in(out), (std::vector<Tick>{4, 5, 6}));
}

TEST(FinalTickLog, BudgetAndTrimming) {
  FinalTickLog log = log_of(40);
  FinalTickLog::Cursor cursor;
  v1::FinalTicks out;
  log.add_to(out, 60, cursor, 40, 0.0);
  EXPECT_LE(out.ByteSizeLong(), 60u);
  EXPECT_GT(out.ticks_size(), 0);
  EXPECT_EQ(cursor.sent, out.ticks(out.ticks_size() - 1).tick());
  log.trim(19, 1024);
  EXPECT_EQ(log.oldest(), 20);
  log.trim(kNoTick, 5);
  EXPECT_EQ(log.oldest(), 35);
  EXPECT_EQ(log.newest(), 39);
}

}  // namespace
}  // namespace rwd::server
