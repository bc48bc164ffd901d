// SPDX-License-Identifier: MIT
// The two real targets: a catalogue scene, and a game measured against its
// reference in windows.
#include <gtest/gtest.h>

#include <cmath>

#include "rewind/tune/game_target.h"
#include "rewind/tune/scene_target.h"

namespace rwd::tune {
namespace {

const scenes::Metric* find(const Measurement& m, const std::string& name) {
  for (const scenes::Metric& metric : m.metrics) {
    if (metric.name == name) return &metric;
  }
  return nullptr;
}

TEST(SceneTarget, RunsTheCatalogueSceneWithItsOwnCriteria) {
  auto target = SceneTarget::create("free_fall", 0);
  ASSERT_TRUE(target.ok()) << target.status().message();
  EXPECT_EQ((*target)->size(), 1) << "free_fall's chart size";
  EXPECT_EQ((*target)->default_setting(), SolverSetting::of(sim::WorldConfig{}));
  const Measurement m = (*target)->measure({4, 0, 30.0f});
  EXPECT_TRUE(m.error.empty()) << m.error;
  ASSERT_FALSE(m.metrics.empty());
  EXPECT_GT(m.ms_per_step, 0.0);
  // Two substeps of a 60 Hz tick are longer than the world accepts:
  // reported, never run under a repaired config.
  const Measurement refused = (*target)->measure({2, 0, 30.0f});
  EXPECT_EQ(refused.error.rfind("refused: ", 0), 0u) << refused.error;
  EXPECT_TRUE(refused.metrics.empty());

  auto unknown = SceneTarget::create("nope", 0);
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.status().message().find("stack"), std::string::npos)
      << "lists the catalogue: " << unknown.status().message();
  EXPECT_FALSE(SceneTarget::create("stack", -3).ok());
}

GamePlay short_match() {
  GamePlay play;
  play.players = 2;
  play.ticks = 120;
  play.window_ticks = 15;
  play.reference_substeps = 8;
  play.reference_relax_iterations = 2;
  return play;
}

TEST(GameTarget, TheReferenceSettingHasNoError) {
  auto target = GameTarget::create(short_match(), nullptr);
  ASSERT_TRUE(target.ok()) << target.status().message();
  // Replaying the reference's own setting from its own states must land on
  // its positions bit for bit: windows, transplant and comparison agree.
  const Measurement same = (*target)->measure((*target)->reference_setting());
  ASSERT_TRUE(same.error.empty()) << same.error;
  ASSERT_NE(find(same, "position_error_m"), nullptr);
  EXPECT_EQ(find(same, "position_error_m")->value, 0.0);
  EXPECT_EQ(find(same, "velocity_error_mps")->value, 0.0);
  EXPECT_NEAR(find(same, "diverged_s")->value, 2.0, 1e-6) << "120 ticks at 60 Hz, never left";

  const Measurement coarse = (*target)->measure({4, 0, 30.0f});
  ASSERT_TRUE(coarse.error.empty()) << coarse.error;
  EXPECT_GT(find(coarse, "position_error_m")->value, 0.0);
  EXPECT_GT(coarse.ms_per_step, 0.0);
  EXPECT_TRUE(find(coarse, "position_error_m")->limit > 0.0) << "the game budget";
  EXPECT_FALSE(std::isfinite(find(coarse, "position_error_mean_m")->limit)) << "reported only";
}

TEST(GameTarget, RefusesWhatCannotBePlayed) {
  GamePlay play = short_match();
  play.game = "chess";
  auto unknown = GameTarget::create(play, nullptr);
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.status().message().find("crates"), std::string::npos);
  play = short_match();
  play.window_ticks = 500;
  EXPECT_FALSE(GameTarget::create(play, nullptr).ok());
  play = short_match();
  play.players = 0;
  EXPECT_FALSE(GameTarget::create(play, nullptr).ok());
}

}  // namespace
}  // namespace rwd::tune
