// SPDX-License-Identifier: MIT
// 2D lane scenes that FAIL their criterion at default settings today. This
// file is deliberately not in any CMake target, so the suite stays green
// while the solver changes; add it to stability2d_tests to check a fix. The
// criteria are the built suite's (scene2d.h), unchanged. Measured at the
// time of writing, with the cause:
//
// - A 20-box stack at default settings stands (drift 0, top sinks 0.108
//   m) but its bottom contact rests 10.7 mm deep (limit 6 mm): the soft
//   contact's spring, 0.70 mm per box above it (13.4 mm predicted under 19
//   boxes). At contact_hertz 60 it rests 2.7 mm deep (built test
//   StackOf20StandsAtContactHertz60); the built StackOf20Stands holds the
//   default settings to 15 mm.
// - A 1:100 box on box: the heavy box rests 35.5 mm into the light one
//   (limit 6 mm), exactly the spring's answer 50 m g / (0.396 m (2 pi
//   30)^2) = 35.5 mm: the softness is sized to the pair's effective mass,
//   dominated by the light box, while the load is the heavy one's weight.
//   It does not sink through (the overlap is steady: the built test
//   HundredTimesHeavierBoxDoesNotSinkThrough), and the 1:10 pair passes
//   (3.9 mm).
#include "stacks2d.h"

namespace rwd::sim2d {
namespace {

using namespace scene;  // NOLINT: test brevity

// The slop-sized resting overlap for a 20-box stack at default settings.
TEST(Stability2DKnownFailure, StackOf20RestsWithinTheSlop) {
  const StackResult r = run_stack(World2DConfig{}, 20);
  report("stack20 penetration_m", r.depth_m, "m", "<=", kDepthLimitM);
  EXPECT_LE(r.depth_m, kDepthLimitM);
}

// The built suite's mass-ratio criteria at 1:100.
TEST(Stability2DKnownFailure, HundredTimesHeavierBoxOnLightBoxStaysStacked) {
  const StackResult r = run_mass_ratio(100);
  report("mass_ratio100 drift_m", r.drift_m, "m", "<=", kDriftLimitM);
  report("mass_ratio100 penetration_m", r.depth_m, "m", "<=", kDepthLimitM);
  report("mass_ratio100 heavy_sink_m", r.top_sink_m, "m", "<=", 2 * kDepthLimitM);
  EXPECT_LE(r.drift_m, kDriftLimitM);
  EXPECT_LE(r.depth_m, kDepthLimitM);
  EXPECT_LE(r.top_sink_m, 2 * kDepthLimitM);
}

}  // namespace
}  // namespace rwd::sim2d
