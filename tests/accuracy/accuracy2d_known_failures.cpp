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
//   There is no continuous collision yet; a speculative margin that grows
//   with the approach speed (|v| / tick_hz) would catch the landing step.
// - Rolling resistance stop distance. A disc (r = 0.25 m) rolling at 2 m/s
//   on the flat ground with rolling resistance c should stop after
//   v^2 / (2 a), a = c g / (1 + I / (m r^2)) = c g / 1.5 (the resisting
//   torque c N r does c m g of work per metre against 3/4 m v^2): 3.0 m for
//   c = 0.1, 1.0 m for c = 0.3. It stops after 0.70 m and 0.25 m (-77%,
//   -75%) starting at x = 0, and after 0.25 m for both when it starts at
//   x = -20 m: the stop depends on where on the ground it rolls.
//   prepare_contacts() (contact_solver2d.cpp) scales the coefficient by
//   max(|ra|, |rb|), the longer of the two anchors, and for a disc on a
//   static ground box ra runs from the ground's centre (0, -1) to the
//   contact, at least 1 m and 20 m at x = -20, instead of the disc's 0.25 m.
//   With a 20 m lever the torque exceeds what friction (mu = 0.8) can carry,
//   the disc skids to a stop in v^2 / (2 mu g) = 0.25 m. A lever from the
//   rolling bodies only (inverse inertia > 0), or the shapes' radii as in
//   Box2D, would give the disc's 0.25 m.
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

// A disc rolling at 2 m/s (r = 0.25 m, mu = 0.8) with rolling resistance c
// (0.1, 0.3) stops within 5% of 0.75 v^2 / (c g), starting at x = 0 and at
// x = -20 m (the 3D catalogue's roll_stop scene and bound, for a disc).
TEST(Accuracy2DKnownFailure, RollingResistanceStopDistance) {
  for (int tenths : {1, 3}) {
    for (int start : {0, -20}) {
      World2D world;
      add_ground(world, 0.8_fx);
      BodyDef2D disc_def = def(make_circle(0.25_fx), {Fx(start), 0.25_fx});
      disc_def.material.friction = 0.8_fx;
      disc_def.material.rolling_resistance = Fx::ratio(tenths, 10);
      disc_def.linear_velocity = {2_fx, Fx()};
      disc_def.angular_velocity = -8_fx;  // rolling from the start: w = -v / r
      const BodyId2D disc = add(world, disc_def);
      for (int t = 0; t < 360; ++t) world.step();
      const double travelled = d(world.position(disc).x) - start;
      const double expected = 0.75 * 2.0 * 2.0 / (0.1 * tenths * kG);
      const double err = 100.0 * std::fabs(travelled - expected) / expected;
      report("roll_stop_c0." + std::to_string(tenths) + "_x" + std::to_string(start) +
                 " stop_error_pct",
             err, "%", "<=", 5.0);
      EXPECT_LE(speed(world, disc), kRestSpeedMps);
      EXPECT_LE(err, 5.0) << "c = 0." << tenths << ", from x = " << start << ": " << travelled
                          << " m, expected " << expected << " m";
    }
  }
}

}  // namespace
}  // namespace rwd::sim2d
