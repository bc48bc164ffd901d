// SPDX-License-Identifier: MIT
// The process's tick load on made-up times: the busy share of the match
// threads over the last whole seconds, new matches refused over the budget
// or while ticks slip, unhealthy only when they slip for many seconds in a
// row or the loop stops ticking.
#include "rewind/server/load_monitor.h"

#include <gtest/gtest.h>

namespace rwd::server {
namespace {

using namespace std::chrono_literals;
using net::TimePoint;

// The start of a whole second of the steady clock, far from zero.
const TimePoint kT0 = TimePoint{} + 5000s;

// One match ticking at 60 Hz through second [from, from + 1 s): each tick
// works `work`; `late_every` > 0: every so many ticks starts late.
void tick_second(LoadMonitor& monitor, TimePoint from, std::chrono::nanoseconds work,
                 int late_every = 0, uint64_t missed = 0) {
  for (int i = 0; i < 60; ++i) {
    const bool late = late_every > 0 && i % late_every == 0;
    monitor.record_tick(from + i * 16ms, work, late, i == 59 ? missed : 0);
  }
}

TEST(LoadMonitor, BusyIsTheShareOfTheThreadsTimeSpentTicking) {
  LoadMonitor monitor(0.75, kT0);
  monitor.set_threads(2);
  monitor.match_started(kT0);
  for (int s = 0; s < 5; ++s) tick_second(monitor, kT0 + s * 1s, 10ms);  // 600 ms a second
  const LoadMonitor::Load load = monitor.load(kT0 + 5s + 300ms);
  EXPECT_EQ(load.window_s, 5.0);
  EXPECT_EQ(load.ticks, 300u);
  EXPECT_NEAR(load.busy, 0.3, 1e-9);  // 0.6 s of each second over 2 threads
  EXPECT_FALSE(load.slipping);
  EXPECT_FALSE(load.stalled);
  EXPECT_EQ(load.live, 1u);
  EXPECT_EQ(monitor.overload_reason(kT0 + 5s + 300ms), "");
  EXPECT_TRUE(monitor.healthy(kT0 + 5s + 300ms));
}

TEST(LoadMonitor, TheCurrentSecondAndOldOnesAreOutsideTheWindow) {
  LoadMonitor monitor(0.75, kT0);
  monitor.match_started(kT0);
  tick_second(monitor, kT0, 10ms);
  // During the first second nothing whole has passed yet.
  EXPECT_EQ(monitor.load(kT0 + 900ms).window_s, 0.0);
  EXPECT_EQ(monitor.load(kT0 + 900ms).busy, 0.0);
  // A second later it is the whole window, which has not reached 5 s.
  EXPECT_EQ(monitor.load(kT0 + 1s).window_s, 1.0);
  EXPECT_NEAR(monitor.load(kT0 + 1s).busy, 0.6, 1e-9);
  // Six seconds on, that second has left the window.
  tick_second(monitor, kT0 + 6s, 1ms);
  const LoadMonitor::Load later = monitor.load(kT0 + 6s + 1s);
  EXPECT_EQ(later.window_s, 5.0);
  EXPECT_EQ(later.ticks, 60u);
  EXPECT_NEAR(later.busy, 0.06 / 5.0, 1e-9);
}

TEST(LoadMonitor, OverTheBudgetNewMatchesAreRefusedButTheProcessIsHealthy) {
  LoadMonitor monitor(0.5, kT0);
  monitor.match_started(kT0);
  for (int s = 0; s < 5; ++s) tick_second(monitor, kT0 + s * 1s, 10ms);  // busy 0.6
  const TimePoint now = kT0 + 5s;
  const std::string reason = monitor.overload_reason(now);
  EXPECT_EQ(reason.rfind("overloaded: ", 0), 0u) << reason;
  EXPECT_NE(reason.find("60%"), std::string::npos) << reason;
  EXPECT_NE(reason.find("budget 50%"), std::string::npos) << reason;
  EXPECT_TRUE(monitor.healthy(now));  // busy, yet every tick on time
}

TEST(LoadMonitor, SlippingTicksRefuseNewMatchesUnderTheBudget) {
  LoadMonitor monitor(0.75, kT0);
  monitor.match_started(kT0);
  // One tick in five late: 20% of the ticks, over the 10% that slips.
  for (int s = 0; s < 5; ++s) tick_second(monitor, kT0 + s * 1s, 1ms, 5);
  const LoadMonitor::Load load = monitor.load(kT0 + 5s);
  EXPECT_EQ(load.late, 60u);
  EXPECT_TRUE(load.slipping);
  EXPECT_EQ(load.slipping_s, 5);
  const std::string reason = monitor.overload_reason(kT0 + 5s);
  EXPECT_NE(reason.find("60 of the 300 ticks"), std::string::npos) << reason;
  // Five seconds of slipping is not yet persistent.
  EXPECT_TRUE(monitor.healthy(kT0 + 5s));
}

TEST(LoadMonitor, AFewLateTicksAreNotSlipping) {
  LoadMonitor monitor(0.75, kT0);
  monitor.match_started(kT0);
  for (int s = 0; s < 20; ++s) tick_second(monitor, kT0 + s * 1s, 1ms, 30);  // 2 of 60
  EXPECT_FALSE(monitor.load(kT0 + 20s).slipping);
  EXPECT_EQ(monitor.load(kT0 + 20s).slipping_s, 0);
  EXPECT_EQ(monitor.overload_reason(kT0 + 20s), "");
  EXPECT_TRUE(monitor.healthy(kT0 + 20s));
}

TEST(LoadMonitor, TicksSlippingForTenSecondsInARowAreUnhealthyUntilTheyRecover) {
  LoadMonitor monitor(0.75, kT0);
  monitor.match_started(kT0);
  for (int s = 0; s < 12; ++s) {
    tick_second(monitor, kT0 + s * 1s, 1ms, 0, /*missed=*/s % 2 == 0 ? 20 : 0);
    tick_second(monitor, kT0 + s * 1s + 500us, 1ms, 4);  // a second match, late a quarter
  }
  EXPECT_EQ(monitor.load(kT0 + 9s).slipping_s, 9);
  EXPECT_TRUE(monitor.healthy(kT0 + 9s));
  EXPECT_EQ(monitor.load(kT0 + 10s).slipping_s, 10);
  EXPECT_FALSE(monitor.healthy(kT0 + 10s));
  EXPECT_NE(monitor.unhealthy_reason(kT0 + 10s).find("10 s in a row"), std::string::npos)
      << monitor.unhealthy_reason(kT0 + 10s);
  // One punctual second ends the run.
  tick_second(monitor, kT0 + 12s, 1ms);
  EXPECT_TRUE(monitor.healthy(kT0 + 13s));
  EXPECT_EQ(monitor.load(kT0 + 13s).slipping_s, 0);
}

TEST(LoadMonitor, ALoopThatStopsTickingIsUnhealthyAndRefusesMatches) {
  LoadMonitor monitor(0.75, kT0);
  monitor.match_started(kT0);
  tick_second(monitor, kT0, 1ms);
  const TimePoint last = kT0 + 59 * 16ms;
  EXPECT_TRUE(monitor.healthy(last + LoadMonitor::kStalledAfter));
  const TimePoint later = last + LoadMonitor::kStalledAfter + 1ms;
  EXPECT_TRUE(monitor.load(later).stalled);
  EXPECT_FALSE(monitor.healthy(later));
  EXPECT_NE(monitor.overload_reason(later).find("none has ticked"), std::string::npos);
  // Quiet seconds while a match is live count as slipping.
  EXPECT_EQ(monitor.load(kT0 + 3s + 1ms).slipping_s, 2);
  // Without live matches silence is normal.
  monitor.match_ended();
  EXPECT_TRUE(monitor.healthy(kT0 + 60s));
  EXPECT_EQ(monitor.overload_reason(kT0 + 60s), "");
}

TEST(LoadMonitor, AnIdleProcessIsHealthyAndTakesMatches) {
  LoadMonitor monitor(0.75, kT0);
  EXPECT_TRUE(monitor.healthy(kT0 + 1h));
  EXPECT_EQ(monitor.overload_reason(kT0 + 1h), "");
  EXPECT_EQ(monitor.load(kT0 + 1h).busy, 0.0);
}

}  // namespace
}  // namespace rwd::server
