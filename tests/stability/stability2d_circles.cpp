// SPDX-License-Identifier: MIT
// 2D lane stability: circles, at default settings. Many fast circles in a
// closed box must neither escape nor gain energy; circles stacked in a
// narrow tube, or balanced on each other, must rest without sinking into
// each other. Each scene also
// replays a stretch from a mid-scene save bit for bit.
#include "scene2d.h"

namespace rwd::sim2d {
namespace {

using namespace scene;  // NOLINT: test brevity

/// A closed box of four static walls 1 m thick around [-4, 4] x [0, 8].
void add_closed_box(World2D& world) {
  add(world, def(make_box(5_fx, 0.5_fx), {Fx(), -0.5_fx}, Fx(), BodyKind2D::kStatic));
  add(world, def(make_box(5_fx, 0.5_fx), {Fx(), 8.5_fx}, Fx(), BodyKind2D::kStatic));
  add(world, def(make_box(0.5_fx, 5_fx), {-4.5_fx, 4_fx}, Fx(), BodyKind2D::kStatic));
  add(world, def(make_box(0.5_fx, 5_fx), {4.5_fx, 4_fx}, Fx(), BodyKind2D::kStatic));
}

/// Kinetic plus potential energy (from y = 0) of circles of radius r, J.
double energy(const World2D& world, std::span<const BodyId2D> ids, double r) {
  double e = 0.0;
  for (BodyId2D id : ids) {
    const double m = d(world.mass(id).to_fx());
    const double v = speed(world, id);
    const double w = d(world.angular_velocity(id));
    // A disc's moment of inertia about its centre is m r^2 / 2.
    e += 0.5 * m * v * v + 0.25 * m * r * r * w * w + m * kG * d(world.center_of_mass(id).y);
  }
  return e;
}

// 100 circles (r = 0.3 m) in a 10 x 10 grid inside the closed box, each
// thrown at up to 3.5 m/s in its own direction, under gravity, for 8 s. No
// circle may ever be outside the box (tunnelled through a wall), and the
// total energy (kinetic + potential) may never exceed its start by more
// than 1%: with restitution 0 contacts only take energy away, and the
// push-out is not meant to leave speed. After 8 s the kinetic energy must
// be below 1% of the starting total (the pile has come to rest).
TEST(Stability2D, ConfinedCirclesStayInAndLoseEnergy) {
  World2D world;
  add_closed_box(world);
  const Fx radius = 0.3_fx;
  std::vector<BodyId2D> circles;
  for (int row = 0; row < 10; ++row) {
    for (int col = 0; col < 10; ++col) {
      const int i = row * 10 + col;
      BodyDef2D c = def(make_circle(radius), {-3.15_fx + 0.7_fx * col, 0.5_fx + 0.7_fx * row});
      // A spread of directions and speeds from the index, the same on every
      // machine: components in {-2.5, ..., 2.5} m/s.
      c.linear_velocity = {Fx::ratio((i * 7) % 11 - 5, 2), Fx::ratio((i * 5) % 11 - 5, 2)};
      circles.push_back(add(world, c));
    }
  }
  const double r = d(radius);
  const double e0 = energy(world, circles, r);
  double e_max = e0;
  bool inside = true;
  World2DState mid;
  for (int t = 1; t <= 480; ++t) {
    world.step();
    e_max = std::max(e_max, energy(world, circles, r));
    for (BodyId2D id : circles) {
      const Vec2 p = world.center_of_mass(id);
      if (d(p.x) <= -4.0 || d(p.x) >= 4.0 || d(p.y) <= 0.0 || d(p.y) >= 8.0) inside = false;
    }
    if (t == 60) world.save(mid);
  }
  double kinetic = 0.0;
  for (BodyId2D id : circles) {
    const double v = speed(world, id);
    kinetic += 0.5 * d(world.mass(id).to_fx()) * v * v;
  }
  report("confined100 energy_gain_pct", 100.0 * (e_max - e0) / e0, "%", "<=", 1.0);
  report("confined100 end_kinetic_pct", 100.0 * kinetic / e0, "%", "<=", 1.0);
  EXPECT_TRUE(inside);
  EXPECT_LE(e_max, 1.01 * e0);
  EXPECT_LE(kinetic, 0.01 * e0);
  world.restore(mid);
  expect_replays_bit_for_bit(world, 30);
}

// Box2D's "confined" stress scene: 625 circles (r = 0.5 m) in a 25 x 25
// grid 0.72 m apart, so every circle starts 0.28 m into its neighbours, in
// a closed 20 m x 20 m box, no gravity. They cannot all fit (625 discs
// cover 491 m^2 of a 400 m^2 box), so the overlaps never go away and the
// push-out works against the walls for good. Criteria: no circle ever
// leaves the box (tunnels through a wall); none ever moves faster than the
// push-out cap (3 m/s) times the 13 overlapping contacts between the
// middle circle and a wall (39 m/s), since push-outs can only compound
// along such a chain (pushes that feed on each other, an explosion, break
// that bound); and after 2 s every circle is slower than 0.05 m/s (the
// pack comes to rest instead of jittering).
TEST(Stability2D, OverfullBoxOfCirclesComesToRest) {
  World2DConfig config;
  config.gravity = {};
  World2D world(config);
  add(world, def(make_box(11_fx, 0.5_fx), {Fx(), Fx()}, Fx(), BodyKind2D::kStatic));
  add(world, def(make_box(11_fx, 0.5_fx), {Fx(), 21_fx}, Fx(), BodyKind2D::kStatic));
  add(world, def(make_box(0.5_fx, 11_fx), {-10.5_fx, 10.5_fx}, Fx(), BodyKind2D::kStatic));
  add(world, def(make_box(0.5_fx, 11_fx), {10.5_fx, 10.5_fx}, Fx(), BodyKind2D::kStatic));
  std::vector<BodyId2D> circles;
  for (int col = 0; col < 25; ++col) {
    for (int row = 0; row < 25; ++row) {
      circles.push_back(add(world, def(make_circle(0.5_fx), {-8.75_fx + Fx::ratio(18 * col, 25),
                                                             1.5_fx + Fx::ratio(18 * row, 25)})));
    }
  }
  const double bound = 13 * d(world.config().contact_push_max);
  double fastest = 0.0;
  double peak_mean = 0.0;
  double late_speed = 0.0;
  bool inside = true;
  World2DState mid;
  for (int t = 1; t <= 180; ++t) {
    world.step();
    double sum = 0.0;
    for (BodyId2D id : circles) {
      const double v = speed(world, id);
      sum += v;
      fastest = std::max(fastest, v);
      if (t > 120) late_speed = std::max(late_speed, point_speed(world, id, 0.5));
      const Vec2 p = world.center_of_mass(id);
      if (d(p.x) <= -10.0 || d(p.x) >= 10.0 || d(p.y) <= 0.5 || d(p.y) >= 20.5) inside = false;
    }
    peak_mean = std::max(peak_mean, sum / static_cast<double>(circles.size()));
    if (t == 60) world.save(mid);
  }
  report("confined625 max_speed_mps", fastest, "m/s", "<=", bound);
  report("confined625 peak_mean_speed_mps", peak_mean, "m/s");
  report("confined625 late_speed_mps", late_speed, "m/s", "<=", kRestSpeedMps);
  EXPECT_TRUE(inside);
  EXPECT_LE(fastest, bound);
  EXPECT_LE(late_speed, kRestSpeedMps);
  world.restore(mid);
  expect_replays_bit_for_bit(world, 30);
}

// 10 circles (r = 0.25 m) dropped into a tube 0.52 m wide (1 cm of play
// each side), every other one 5 mm off the axis so they lean on the walls,
// 1 cm apart. After 5 s they must be in order, within the tube, at rest
// (< 0.05 m/s), each resting overlap within the slop + 1 mm, and the top
// circle no lower than 10 such overlaps below 4.75 m (the height of ten
// touching circles).
TEST(Stability2D, CircleStackInATubeRests) {
  World2D world(awake());
  add_ground(world);
  add(world, def(make_box(0.5_fx, 4_fx), {-0.76_fx, 4_fx}, Fx(), BodyKind2D::kStatic));
  add(world, def(make_box(0.5_fx, 4_fx), {0.76_fx, 4_fx}, Fx(), BodyKind2D::kStatic));
  std::vector<BodyId2D> circles;
  for (int i = 0; i < 10; ++i) {
    const Fx x = (i % 2 == 0) ? 0.005_fx : -0.005_fx;
    circles.push_back(add(world, def(make_circle(0.25_fx), {x, 0.26_fx + 0.51_fx * i})));
  }
  World2DState mid;
  double depth = 0.0;
  for (int t = 1; t <= 300; ++t) {
    world.step();
    if (t > 240) depth = std::max(depth, deepest_overlap(world));
    if (t == 150) world.save(mid);
  }
  bool ordered = true;
  bool in_tube = true;
  double end_speed = 0.0;
  for (size_t i = 0; i < circles.size(); ++i) {
    const Vec2 p = world.center_of_mass(circles[i]);
    if (i > 0 && p.y <= world.center_of_mass(circles[i - 1]).y) ordered = false;
    if (std::fabs(d(p.x)) > 0.01 + kSlopM) in_tube = false;
    end_speed = std::max(end_speed, point_speed(world, circles[i], 0.25));
  }
  const double top_low = 4.75 - d(world.center_of_mass(circles.back()).y);
  report("circle_stack10 penetration_m", depth, "m", "<=", kDepthLimitM);
  report("circle_stack10 top_sink_m", top_low, "m", "<=", 10 * kDepthLimitM);
  report("circle_stack10 end_speed_mps", end_speed, "m/s", "<=", kRestSpeedMps);
  EXPECT_TRUE(ordered);
  EXPECT_TRUE(in_tube);
  EXPECT_LE(depth, kDepthLimitM);
  EXPECT_LE(top_low, 10 * kDepthLimitM);
  EXPECT_LE(end_speed, kRestSpeedMps);
  world.restore(mid);
  expect_replays_bit_for_bit(world, 30);
}

// 10 circles (r = 0.25 m) exactly on top of each other, free standing, for
// 10 s. A column of circles balances only while every contact normal is
// exactly vertical: an exact integer step of an exactly aligned column
// keeps it so, and any sideways impulse the solver invents (rounding that
// is not mirror-symmetric, say) topples it. Criterion: no circle moves more
// than 1 mm sideways; the deepest overlap in the last second within the
// slop + 1 mm.
TEST(Stability2D, CircleColumnOnEachOtherStaysAligned) {
  World2D world(awake());
  add_ground(world);
  Drift drift;
  for (int i = 0; i < 10; ++i) {
    drift.track(world, add(world, def(make_circle(0.25_fx), {Fx(), 0.25_fx + 0.5_fx * i})));
  }
  World2DState mid;
  double depth = 0.0;
  for (int t = 1; t <= 600; ++t) {
    world.step();
    drift.observe(world);
    if (t > 540) depth = std::max(depth, deepest_overlap(world));
    if (t == 300) world.save(mid);
  }
  report("circle_column10 drift_m", drift.max_sideways_m(), "m", "<=", 0.001);
  report("circle_column10 penetration_m", depth, "m", "<=", kDepthLimitM);
  EXPECT_LE(drift.max_sideways_m(), 0.001);
  EXPECT_LE(depth, kDepthLimitM);
  world.restore(mid);
  expect_replays_bit_for_bit(world, 30);
}

}  // namespace
}  // namespace rwd::sim2d
