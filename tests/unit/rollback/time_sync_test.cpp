// SPDX-License-Identifier: MIT
#include "rewind/net/time_sync.h"

#include <gtest/gtest.h>

namespace rwd::net {
namespace {

TEST(TimeSync, NeutralWithoutSamples) {
  TimeSync sync;
  EXPECT_DOUBLE_EQ(sync.period_scale(), 1.0);
  EXPECT_FALSE(sync.has_samples());
}

TEST(TimeSync, SlowsDownWhenTooFarAheadAndSpeedsUpWhenLate) {
  TimeSyncConfig config;
  config.target_lead_ticks = 2.0;
  TimeSync ahead(config);
  for (int i = 0; i < 50; ++i) ahead.on_lead_report(10);
  EXPECT_GT(ahead.period_scale(), 1.0);
  EXPECT_LE(ahead.period_scale(), 1.0 + config.max_adjust);

  TimeSync late(config);
  for (int i = 0; i < 50; ++i) late.on_lead_report(1);  // early, but short of the target
  EXPECT_LT(late.period_scale(), 1.0);
  EXPECT_GE(late.period_scale(), 1.0 - config.max_adjust);

  TimeSync on_target(config);
  for (int i = 0; i < 50; ++i) on_target.on_lead_report(2);
  EXPECT_NEAR(on_target.period_scale(), 1.0, 1e-9);
}

TEST(TimeSync, JumpsForwardOnceWhenInputsArriveLate) {
  TimeSyncConfig config;
  config.target_lead_ticks = 2.0;
  config.jump_cooldown_reports = 5;
  TimeSync sync(config);
  sync.on_lead_report(-3);
  EXPECT_EQ(sync.take_jump(), 5);  // from 3 late to 2 early
  EXPECT_EQ(sync.take_jump(), 0);
  // Reports already in flight still say "late": no second jump.
  for (int i = 0; i < 5; ++i) sync.on_lead_report(-3);
  EXPECT_EQ(sync.take_jump(), 0);
  sync.on_lead_report(-1);  // late again after the cooldown
  EXPECT_EQ(sync.take_jump(), 3);
  EXPECT_NEAR(sync.period_scale(), 1.0, 1e-9);  // the jump lands on target
}

TEST(TimeSync, SmoothsSingleOutliers) {
  TimeSync sync;
  for (int i = 0; i < 50; ++i) sync.on_lead_report(2);
  sync.on_lead_report(40);
  EXPECT_LT(sync.smoothed_lead(), 6.0);
}

}  // namespace
}  // namespace rwd::net
