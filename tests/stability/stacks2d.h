// SPDX-License-Identifier: MIT
#pragma once
// Box stacks of the 2D stability scenes, shared by the built suite and the
// scenes kept out of it (stability2d_known_failures.cpp).
#include "scene2d.h"

namespace rwd::sim2d::scene {

/// A pyramid `base` boxes wide of 1 m boxes with 5 cm gaps, centred at
/// x = origin.x, on a ground whose top is y = origin.y.
inline std::vector<BodyId2D> build_pyramid(World2D& world, int base, Vec2 origin) {
  std::vector<BodyId2D> boxes;
  const Fx pitch = 1.05_fx;
  for (int level = 0; level < base; ++level) {
    const int count = base - level;
    for (int i = 0; i < count; ++i) {
      // x = centre + (i - (count - 1) / 2) pitch, exact in halves of a pitch.
      const Fx x = origin.x + pitch * (2 * i - (count - 1)) / 2;
      boxes.push_back(
          add(world, def(make_box(0.5_fx, 0.5_fx), {x, origin.y + 0.5_fx + Fx(level)})));
    }
  }
  return boxes;
}

/// What a standing stack is judged by.
struct StackResult {
  double drift_m = 0.0;     ///< worst sideways drift of any box over the run
  double top_sink_m = 0.0;  ///< how far the top box ends below its start
  double depth_m = 0.0;     ///< deepest overlap in the last second
  /// How far the top box's height moved in the last 5 s: a stack that
  /// sinks through, or keeps sinking, moves; a settled one does not.
  double late_sink_m = 0.0;
};

/// A column of `count` 1 m boxes on the ground for 10 s; replays a stretch
/// from a save at 5 s bit for bit.
inline StackResult run_stack(const World2DConfig& config, int count) {
  World2D world(awake(config));
  add_ground(world);
  Drift drift;
  std::vector<BodyId2D> boxes;
  for (int i = 0; i < count; ++i) {
    boxes.push_back(add(world, def(make_box(0.5_fx, 0.5_fx), {Fx(), 0.5_fx + Fx(i)})));
    drift.track(world, boxes.back());
  }
  World2DState mid;
  StackResult r;
  double top_at_5s = 0.0;
  for (int t = 1; t <= 600; ++t) {
    world.step();
    drift.observe(world);
    const double top = d(world.center_of_mass(boxes.back()).y);
    if (t > 540) r.depth_m = std::max(r.depth_m, deepest_overlap(world));
    if (t == 300) {
      world.save(mid);
      top_at_5s = top;
    }
    if (t > 300) r.late_sink_m = std::max(r.late_sink_m, std::fabs(top - top_at_5s));
  }
  r.drift_m = drift.max_sideways_m();
  r.top_sink_m = (count - 0.5) - d(world.center_of_mass(boxes.back()).y);
  world.restore(mid);
  expect_replays_bit_for_bit(world, 30);
  return r;
}

/// A 1 m box of density `ratio` on a 1 m box of density 1 on the ground for
/// 10 s; replays a stretch from a save at 5 s bit for bit.
inline StackResult run_mass_ratio(int ratio) {
  World2D world(awake());
  add_ground(world);
  const BodyId2D light = add(world, def(make_box(0.5_fx, 0.5_fx), {Fx(), 0.5_fx}));
  BodyDef2D heavy_def = def(make_box(0.5_fx, 0.5_fx), {Fx(), 1.5_fx});
  heavy_def.density = Fx(ratio);
  const BodyId2D heavy = add(world, heavy_def);
  EXPECT_EQ(world.mass(heavy).to_fx(), world.mass(light).to_fx() * ratio);
  Drift drift;
  drift.track(world, light);
  drift.track(world, heavy);
  World2DState mid;
  StackResult r;
  double top_at_5s = 0.0;
  for (int t = 1; t <= 600; ++t) {
    world.step();
    drift.observe(world);
    const double top = d(world.center_of_mass(heavy).y);
    if (t > 540) r.depth_m = std::max(r.depth_m, deepest_overlap(world));
    if (t == 300) {
      world.save(mid);
      top_at_5s = top;
    }
    if (t > 300) r.late_sink_m = std::max(r.late_sink_m, std::fabs(top - top_at_5s));
  }
  r.drift_m = drift.max_sideways_m();
  r.top_sink_m = 1.5 - d(world.center_of_mass(heavy).y);
  world.restore(mid);
  expect_replays_bit_for_bit(world, 30);
  return r;
}

}  // namespace rwd::sim2d::scene
