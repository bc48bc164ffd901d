// SPDX-License-Identifier: MIT
// The tick grid on made-up times: lateness is the start minus the due
// time, a loop a period or more behind runs its due ticks back to back
// (each counted late), and one more than kMaxBehind periods behind drops
// the ticks it missed and restarts the grid.
#include "rewind/server/tick_schedule.h"

#include <gtest/gtest.h>

namespace rwd::server {
namespace {

using namespace std::chrono_literals;
using net::TimePoint;

constexpr std::chrono::nanoseconds kPeriod = 10ms;
const TimePoint kStart = TimePoint{} + 1000s;

// Runs one tick that starts at `start` and takes `work`; returns the drops.
int64_t tick(TickSchedule& schedule, TimePoint start, std::chrono::nanoseconds work = 1ms) {
  schedule.begin(start);
  return schedule.end(start + work);
}

TEST(TickSchedule, TicksOnTimeAreDueAPeriodApartAndNeverLate) {
  TickSchedule schedule(kPeriod);
  schedule.start(kStart);
  EXPECT_EQ(schedule.due(), kStart + kPeriod);
  for (int i = 1; i <= 5; ++i) {
    const TimePoint due = schedule.due();
    EXPECT_EQ(due, kStart + i * kPeriod);
    EXPECT_EQ(schedule.begin(due + 50us), 50us);  // a timer's wake-up
    EXPECT_EQ(schedule.end(due + 2ms), 0);
    EXPECT_EQ(schedule.behind(), 0);
  }
  EXPECT_EQ(schedule.late(), 0u);
  EXPECT_EQ(schedule.missed(), 0u);
  EXPECT_EQ(schedule.lateness().count(), 5u);
  EXPECT_EQ(schedule.lateness().max_ns(), 50'000);
  EXPECT_EQ(schedule.lateness().bucket_count(0), 5u);  // <= 50 µs
}

TEST(TickSchedule, AStartBeforeItsTimeIsOnTime) {
  TickSchedule schedule(kPeriod);
  schedule.start(kStart);
  EXPECT_EQ(schedule.begin(schedule.due() - 1us), 0ns);
  EXPECT_EQ(schedule.lateness().max_ns(), 0);
}

TEST(TickSchedule, ALateLoopCatchesUpBackToBackOnTheSameGrid) {
  TickSchedule schedule(kPeriod);
  schedule.start(kStart);
  // The first tick starts 35 ms late: three more ticks are due by then.
  const TimePoint stalled = kStart + kPeriod + 35ms;
  EXPECT_EQ(schedule.begin(stalled), 35ms);
  EXPECT_EQ(schedule.behind(), 3);
  EXPECT_EQ(schedule.end(stalled + 1ms), 0);
  EXPECT_EQ(schedule.late(), 1u);
  // The grid does not move: the next tick is due at its own time, long
  // past, so the loop runs it at once, and the ones after it.
  EXPECT_EQ(schedule.due(), kStart + 2 * kPeriod);
  TimePoint now = stalled + 1ms;
  while (schedule.due() <= now) {
    schedule.begin(now);
    schedule.end(now + 1ms);
    now += 1ms;
  }
  // 2nd (26 ms late), 3rd (17 ms), 4th (8 ms: less than a period, on time).
  EXPECT_EQ(schedule.late(), 3u);
  EXPECT_EQ(schedule.missed(), 0u);
  EXPECT_EQ(schedule.behind(), 0);
  EXPECT_EQ(schedule.due(), kStart + 5 * kPeriod);
  EXPECT_EQ(schedule.lateness().count(), 4u);
  EXPECT_EQ(schedule.lateness().max_ns(), 35'000'000);
}

TEST(TickSchedule, ALongStallDropsTheMissedTicksAndRestartsTheGrid) {
  TickSchedule schedule(kPeriod);
  schedule.start(kStart);
  const TimePoint first = schedule.due();
  // The process stops for a second right after the first tick began.
  const int64_t dropped = tick(schedule, first, 1000ms);
  // Due after it were the ticks at +10 ms ... +1000 ms: 100 of them.
  EXPECT_EQ(dropped, 100);
  EXPECT_EQ(schedule.missed(), 100u);
  EXPECT_EQ(schedule.late(), 0u);  // the tick that stalled had started on time
  EXPECT_EQ(schedule.due(), first + 1000ms + kPeriod);
  EXPECT_EQ(tick(schedule, schedule.due()), 0);
  EXPECT_EQ(schedule.behind(), 0);
}

TEST(TickSchedule, AStallOfUpToTheLimitIsCaughtUpNotDropped) {
  TickSchedule schedule(kPeriod);
  schedule.start(kStart);
  const TimePoint first = schedule.due();
  // Ends exactly kMaxBehind periods after the next tick was due.
  EXPECT_EQ(tick(schedule, first, kPeriod + TickSchedule::kMaxBehind * kPeriod), 0);
  EXPECT_EQ(schedule.missed(), 0u);
  EXPECT_EQ(schedule.due(), first + kPeriod);
  // One nanosecond more and the ticks due by then are dropped.
  TickSchedule other(kPeriod);
  other.start(kStart);
  EXPECT_EQ(tick(other, first, kPeriod + TickSchedule::kMaxBehind * kPeriod + 1ns),
            TickSchedule::kMaxBehind + 1);
}

}  // namespace
}  // namespace rwd::server
