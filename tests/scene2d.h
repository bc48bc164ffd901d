// SPDX-License-Identifier: MIT
#pragma once
// Builders and measures shared by the 2D lane's stability and accuracy
// scenes. Scenes are built only through the public World2D API. Setup is
// integer (Fx) so a scene is the same world on every machine; measures are
// taken in double, since they only judge the result and never feed back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <span>
#include <string>
#include <vector>

#include "rewind/fixed/trig.h"
#include "rewind/sim2d/world2d.h"

namespace rwd::sim2d::scene {

using namespace rwd::fixed::literals;  // NOLINT: test brevity

/// Metres (or any Fx quantity) as a double, for judging only.
inline double d(Fx v) {
  return static_cast<double>(v.raw()) / 65536.0;
}

/// The default world's numbers the criteria are stated against.
inline constexpr double kG = 10.0;             // m/s^2, World2DConfig::gravity
inline constexpr double kTickS = 1.0 / 60.0;   // s, World2DConfig::tick_hz
inline constexpr double kSlopM = 0.005;        // m, World2DConfig::linear_slop
inline constexpr double kDepthLimitM = 0.006;  // resting overlap: the slop + 1 mm of solver error
inline constexpr double kDriftLimitM = 0.1;    // sideways drift of a standing box: a tenth of a box
inline constexpr double kRestSpeedMps = 0.05;  // "at rest": the 3D catalogue's kick scene bound
inline constexpr int kTicksPerSecond = 60;

inline double deg(int degrees) {
  return static_cast<double>(degrees) * 3.14159265358979323846 / 180.0;
}
/// An angle of `degrees` in Fx radians, rounded once from the exact ratio.
inline Fx fx_deg(int degrees) {
  // pi to 1e-9, far below the Fx's own rounding.
  return Fx::ratio(static_cast<int64_t>(degrees) * 3141592654LL, 180LL * 1000000000LL);
}

/// A body definition: dynamic unless said otherwise, default material.
inline BodyDef2D def(const Result<Shape2D>& shape, Vec2 position, Fx angle = Fx(),
                     BodyKind2D kind = BodyKind2D::kDynamic) {
  EXPECT_TRUE(shape.ok()) << shape.status().message();
  BodyDef2D b;
  b.kind = kind;
  if (shape.ok()) b.shape = *shape;
  b.position = position;
  b.angle = angle;
  return b;
}

inline BodyId2D add(World2D& world, const BodyDef2D& b) {
  auto id = world.create_body(b);
  EXPECT_TRUE(id.ok()) << id.status().message();
  return id.ok() ? *id : BodyId2D{};
}

/// A flat static ground whose top is y = top, 200 m wide about x = centre.
inline BodyId2D add_ground(World2D& world, Fx friction = 0.6_fx, Fx centre = Fx(), Fx top = Fx()) {
  BodyDef2D g = def(make_box(100_fx, 1_fx), {centre, top - 1_fx}, Fx(), BodyKind2D::kStatic);
  g.material.friction = friction;
  return add(world, g);
}

inline double speed(const World2D& world, BodyId2D id) {
  const Vec2 v = world.linear_velocity(id);
  return std::hypot(d(v.x), d(v.y));
}

/// The fastest point of a body whose farthest point is `reach` m from its
/// centre of mass: |v| + |w| reach.
inline double point_speed(const World2D& world, BodyId2D id, double reach) {
  return speed(world, id) + std::fabs(d(world.angular_velocity(id))) * reach;
}

/// `config` with sleeping off. Scenes that measure resting overlap use it:
/// the overlap is read from the contact events, and a sleeping pair reports
/// none, so a scene that fell asleep would measure nothing.
inline World2DConfig awake(World2DConfig config = {}) {
  config.enable_sleep = false;
  return config;
}

/// The deepest overlap of two solid bodies in the last step's contact
/// events (the engine's own manifold depth), m. Awake pairs only: see
/// awake().
inline double deepest_overlap(const World2D& world) {
  double deepest = 0.0;
  for (const ContactEvent2D& e : world.events()) {
    if (e.sensor || e.type == ContactEventType2D::kExit) continue;
    deepest = std::max(deepest, d(e.depth));
  }
  return deepest;
}

/// Tracks how far bodies move from where they started: the largest
/// sideways (x) and total centre-of-mass displacement over the scene.
class Drift {
 public:
  void track(const World2D& world, BodyId2D id) {
    ids_.push_back(id);
    start_.push_back(world.center_of_mass(id));
  }
  void observe(const World2D& world) {
    for (size_t i = 0; i < ids_.size(); ++i) {
      const Vec2 p = world.center_of_mass(ids_[i]);
      const double dx = d(p.x) - d(start_[i].x);
      const double dy = d(p.y) - d(start_[i].y);
      max_sideways_m_ = std::max(max_sideways_m_, std::fabs(dx));
      max_move_m_ = std::max(max_move_m_, std::hypot(dx, dy));
    }
  }
  double max_sideways_m() const { return max_sideways_m_; }
  double max_move_m() const { return max_move_m_; }
  std::span<const BodyId2D> ids() const { return ids_; }

 private:
  std::vector<BodyId2D> ids_;
  std::vector<Vec2> start_;
  double max_sideways_m_ = 0.0;
  double max_move_m_ = 0.0;
};

/// Prints a measured value with its limit (none when `bound` is empty), so a
/// passing run still shows how close it came.
inline void report(const std::string& what, double value, const char* unit, const char* bound = "",
                   double limit = 0.0) {
  std::cout << "[ measured ] " << what << " = " << value << " " << unit;
  if (*bound != '\0') std::cout << " (" << bound << " " << limit << ")";
  std::cout << "\n";
  // Property names become XML attribute names in --gtest_output=xml.
  std::string key = what;
  for (char& c : key) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  ::testing::Test::RecordProperty(key, std::to_string(value));
}

/// Restore-and-re-step: saves the world, steps `ticks` recording every
/// checksum, restores and re-steps, and expects the same checksums; then
/// does the same from serialize()d bytes in a fresh world. The world is left
/// `ticks` further on.
inline void expect_replays_bit_for_bit(World2D& world, int ticks) {
  World2DState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<uint64_t> sums;
  for (int i = 0; i < ticks; ++i) {
    world.step();
    sums.push_back(world.checksum());
  }
  const uint64_t end_sum = world.checksum();
  world.restore(saved);
  for (int i = 0; i < ticks; ++i) {
    world.step();
    ASSERT_EQ(world.checksum(), sums[static_cast<size_t>(i)]) << "restored world, tick " << i;
  }
  World2D fresh(world.config());
  ASSERT_TRUE(fresh.deserialize(bytes).ok());
  for (int i = 0; i < ticks; ++i) {
    fresh.step();
    ASSERT_EQ(fresh.checksum(), sums[static_cast<size_t>(i)]) << "deserialized world, tick " << i;
  }
  EXPECT_EQ(world.checksum(), end_sum);
}

}  // namespace rwd::sim2d::scene
