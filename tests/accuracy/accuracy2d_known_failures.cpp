// SPDX-License-Identifier: MIT
// 2D lane accuracy scenes that FAIL their criterion at default settings
// today. Deliberately in no CMake target, so the suite stays green while
// the solver changes; add it to accuracy2d_tests to check a fix. Measured
// at the time of writing, with the cause:
//
// - Bounce apex against drop height. The built test drops from 2 m (the 3D
//   catalogue's height) and passes (e = 0.5: -4.0%), but from 1.0 to 3.0 m
//   in 0.1 m steps the e = 0.5 apex misses e^2 h by -2.1% to -12.8% (over
//   5% for 11 of the 21 heights; e = 0.9 stays within -1.0% to -2.0%). The
//   ball lands up to 8 cm inside the ground: a contact is made only if the
//   gap at the start of a step is within speculative_distance (0.02 m),
//   while at 4.5 to 7.8 m/s the ball moves 0.075 to 0.13 m per tick, so in
//   the step it arrives it meets no contact and sinks (h = 1.2 m: 6.0 cm,
//   h = 2.5 m: 8.3 cm). The next step bounces it at e times the approach
//   speed (restitution itself is exact: the rebound speed is e x the
//   pre-step speed) but from below the surface, and the push-out lifts it
//   without adding speed, so the apex comes short by about the depth (h = 1 m:
//   2.2 cm deep, 1.85 cm short; h = 2 m: 1.9 cm deep, 2.0 cm short).
//   A ball with continuous collision on lands on the surface and passes
//   from every height (built test SweptBallBouncesToRestitutionSquared-
//   FromAnyHeight); a speculative margin that grows with the approach
//   speed would fix the unswept ball, but it also stopped tipping dominoes
//   early (speculative points far from where the bodies will touch).
#include <string>

#include "scene2d.h"

namespace rwd::sim2d {
namespace {

using namespace scene;  // NOLINT: test brevity

// The built bounce criterion (first apex within 5% of e^2 h) for drop
// heights 1.0 to 3.0 m.
TEST(Accuracy2DKnownFailure, BounceApexFromAnyHeight) {
  for (int percent : {50, 90}) {
    for (int cm = 100; cm <= 300; cm += 10) {
      World2D world;
      add_ground(world);
      BodyDef2D ball_def = def(make_circle(0.5_fx), {Fx(), Fx::ratio(cm, 100) + 0.5_fx});
      ball_def.material.restitution = Fx::ratio(percent, 100);
      const BodyId2D ball = add(world, ball_def);
      int phase = 0;
      double apex = 0.0;
      for (int t = 0; t < 240 && phase < 2; ++t) {
        world.step();
        const double vy = d(world.linear_velocity(ball).y);
        const double y = d(world.position(ball).y) - 0.5;
        if (phase == 0 && vy > 0.0) phase = 1;
        if (phase == 1) {
          apex = std::max(apex, y);
          if (vy < 0.0) phase = 2;
        }
      }
      const double expected = (percent / 100.0) * (percent / 100.0) * (cm / 100.0);
      const double err = 100.0 * std::fabs(apex - expected) / expected;
      report("bounce" + std::to_string(percent) + "_h" + std::to_string(cm) + "cm apex_error_pct",
             err, "%", "<=", 5.0);
      EXPECT_LE(err, 5.0) << "e = " << percent << "%, h = " << cm << " cm: apex " << apex;
    }
  }
}

}  // namespace
}  // namespace rwd::sim2d
