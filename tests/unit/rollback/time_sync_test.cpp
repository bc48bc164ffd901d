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
  for (int i = 0; i < 50; ++i) late.on_lead_report(-5);
  EXPECT_LT(late.period_scale(), 1.0);
  EXPECT_GE(late.period_scale(), 1.0 - config.max_adjust);

  TimeSync on_target(config);
  for (int i = 0; i < 50; ++i) on_target.on_lead_report(2);
  EXPECT_NEAR(on_target.period_scale(), 1.0, 1e-9);
}

TEST(TimeSync, SmoothsSingleOutliers) {
  TimeSync sync;
  for (int i = 0; i < 50; ++i) sync.on_lead_report(2);
  sync.on_lead_report(40);
  EXPECT_LT(sync.smoothed_lead(), 6.0);
}

}  // namespace
}  // namespace rwd::net
