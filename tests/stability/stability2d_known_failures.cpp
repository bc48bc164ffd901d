// SPDX-License-Identifier: MIT
// 2D lane scenes that FAIL their criterion at default settings today. This
// file is deliberately not in any CMake target, so the suite stays green
// while the solver changes; add it to stability2d_tests to check a fix. The
// criteria are the built suite's (scene2d.h), unchanged. Measured at the
// time of writing, with the cause:
//
// - A 20-box stack: drifts 2.18 m sideways and the top box sinks 0.28 m in
//   10 s; the deepest overlap in the last second is 20 mm (limit 6 mm; 13 mm
//   at the bottom before it starts to lean). The soft contact is a spring
//   of stiffness normal_mass (2 pi contact_hertz)^2 per point, so a box-box
//   point (normal mass m / 5 with the rotational terms, half the load) rests
//   2.5 N g / (2 pi 30)^2 = 0.70 mm deep per box above it (13.4 mm under
//   19). Its resistance to tilting is as soft, and a column of such joints
//   buckles under its own weight (Greenhill: q L^3 / EI > 7.84, with
//   EI = 0.1 m (2 pi f)^2 per metre of column) beyond about 14 boxes at
//   30 Hz: 15 boxes drift 0.53 m in 10 s, 10 stand (but rest 6.4 mm deep).
//   The first sideways motion (5e-5 m at tick 1) comes from solving a
//   manifold's two points one after the other. At contact_hertz 60 the same
//   stack stands (built test StackOf20StandsAtContactHertz60); more substeps
//   or relax passes do not help (the hertz stays at 30).
// - A 1:100 box on box: the heavy box rests 35.5 mm into the light one
//   (limit 6 mm), exactly the spring's answer 50 m g / (0.396 m (2 pi
//   30)^2) = 35.5 mm: the softness is sized to the pair's effective mass,
//   dominated by the light box, while the load is the heavy one's weight.
//   It does not sink through (the overlap is steady: the built test
//   HundredTimesHeavierBoxDoesNotSinkThrough), and the 1:10 pair passes
//   (3.9 mm).
// - Two boxes overlapping by half a box in zero gravity separate, but keep
//   0.163 m/s each (0.33 m/s apart) for ever, against the config's "moves
//   bodies apart without leaving them velocity". One relax pass solves the
//   manifold's two points one after the other and the second undoes part
//   of the first through the rotation they share: the push-out speed
//   (1.62 m/s each with no relax pass) is left at 10% after one pass, 0.4%
//   after two, none after four. The same leftover compounds in a dense
//   pack: in the built over-full confined box (stability2d_circles.cpp)
//   circles reach 22.9 m/s, RMS 13.8 m/s, in the first 4 ticks, 4.6 times
//   the 3 m/s cap, before the pack settles; with 2, 4 and 8 relax
//   passes the RMS peak is 9.7, 6.4 and 4.1 m/s, with none 23 m/s (and one
//   circle 107 m/s, beyond that scene's 39 m/s bound).
#include "stacks2d.h"

namespace rwd::sim2d {
namespace {

using namespace scene;  // NOLINT: test brevity

// The built suite's stack criteria at default settings.
TEST(Stability2DKnownFailure, StackOf20Stands) {
  const StackResult r = run_stack(World2DConfig{}, 20);
  report("stack20 drift_m", r.drift_m, "m", "<=", kDriftLimitM);
  report("stack20 top_sink_m", r.top_sink_m, "m", "<=", 20 * kDepthLimitM);
  report("stack20 penetration_m", r.depth_m, "m", "<=", kDepthLimitM);
  EXPECT_LE(r.drift_m, kDriftLimitM);
  EXPECT_LE(r.top_sink_m, 20 * kDepthLimitM);
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

// Two 1 m boxes half inside each other, no gravity: once apart (no contact
// for a second) they must be at rest, relative speed under 0.05 m/s.
TEST(Stability2DKnownFailure, PushOutLeavesNoVelocity) {
  World2DConfig config;
  config.gravity = {};
  World2D world(config);
  const BodyId2D a = add(world, def(make_box(0.5_fx, 0.5_fx), {Fx(), Fx()}));
  const BodyId2D b = add(world, def(make_box(0.5_fx, 0.5_fx), {0.5_fx, Fx()}));
  for (int t = 1; t <= 120; ++t) world.step();
  EXPECT_TRUE(world.events().empty());
  const double apart = d(world.linear_velocity(b).x) - d(world.linear_velocity(a).x);
  report("push_out relative_speed_mps", apart, "m/s", "<=", kRestSpeedMps);
  EXPECT_LE(std::fabs(apart), kRestSpeedMps);
}

}  // namespace
}  // namespace rwd::sim2d
