// SPDX-License-Identifier: MIT
#pragma once
// One description of a 2D benchmark scene, built the same way on Rewind's
// 2D lane and on Box2D 2.4. Every length, angle and velocity is an integer
// count of thousandths (mm, mrad, mrad/s), so Rewind gets exact Q16.16
// ratios and Box2D gets the nearest float: neither engine sees a value the
// other was not given.
#include <cstdint>
#include <string>
#include <vector>

namespace rwd::bench {

enum class Kind2D : uint8_t { kStatic, kKinematic, kDynamic };

/// A body with one box or circle. Rewind turns static and kinematic bodies
/// about their origin, so an offset box (cx, cy) is how a wall hangs off a
/// shared pivot.
struct BodyDesc2D {
  Kind2D kind = Kind2D::kDynamic;
  int32_t radius = 0;  ///< mm; > 0: a circle centred at (cx, cy) instead of the box
  /// mm; when they differ (and radius > 0), a capsule of `radius` about the
  /// segment from (cx, capsule_y0) to (cx, capsule_y1) instead of a circle.
  int32_t capsule_y0 = 0, capsule_y1 = 0;
  int32_t hx = 500, hy = 500;    ///< half extents, mm
  int32_t cx = 0, cy = 0;        ///< shape centre in the body frame, mm
  int32_t x = 0, y = 0;          ///< body origin, mm
  int32_t vx = 0, vy = 0;        ///< linear velocity, mm/s
  int32_t angular_velocity = 0;  ///< mrad/s
  int32_t density = 0;           ///< kg/m^2 x 1000; 0: the scene's
  bool awake = true;             ///< false: a dynamic body starts asleep
  int32_t friction = -1;         ///< x 1000; < 0: the scene's
  int32_t linear_damping = 0;    ///< 1/s x 1000
  /// Collision layers: a pair collides when each one's layer is in the
  /// other's mask (Box2D's category and mask bits).
  uint32_t layer = 1;
  uint32_t mask = 0xFFFFFFFFu;
  /// Bodies with the same group >= 0 (same origin and velocity) become one
  /// Box2D body with one fixture each; Rewind has one shape per body.
  int32_t group = -1;
};

/// A revolute joint between bodies a and b about a world point (mm).
struct RevoluteDesc2D {
  uint32_t a = 0;
  uint32_t b = 0;
  int32_t x = 0, y = 0;
  /// mrad: B's angle relative to A that counts as the joint's zero, from
  /// their angle at creation (Box2D's referenceAngle for bodies made at
  /// the same angle).
  int32_t reference = 0;
  bool limit = false;
  int32_t lower = 0, upper = 0;  ///< mrad, from the reference
  int32_t friction_torque = 0;   ///< N m x 1000: a motor held at speed 0
  int32_t hertz = 0;             ///< x 1000; > 0: a spring toward the reference
  int32_t damping_ratio = 0;     ///< x 1000
};

/// Bodies and joints added while the scene runs, after some earlier ones
/// are taken out (Box2D v3's rain drops ragdolls and removes the oldest).
struct Wave2D {
  int tick = 0;                   ///< added just before this tick's step (0: the first)
  std::vector<uint32_t> removes;  ///< earlier waves (indices into Scene2D::waves) removed first
  std::vector<BodyDesc2D> bodies;
  std::vector<RevoluteDesc2D> joints;  ///< a and b index this wave's bodies
};

struct Scene2D {
  std::string name;
  int size = 0;              ///< the scene's size knob (base, pyramids, boxes, grid side)
  int warmup_ticks = 0;      ///< stepped before the timing starts
  int timed_ticks = 0;       ///< stepped and timed
  int32_t density = 1000;    ///< kg/m^2 x 1000, every dynamic body
  int32_t friction = 600;    ///< x 1000, every body
  int32_t gravity = -10000;  ///< mm/s^2 along y
  std::vector<BodyDesc2D> bodies;
  std::vector<RevoluteDesc2D> joints;
  /// Pyramids: the index of each pyramid's top box (its drift is the
  /// accuracy figure). Empty for other scenes.
  std::vector<uint32_t> tops;
  /// The farthest any dynamic body ends from its start is reported
  /// (pyramids: whether they stood; smash: how far the wall was thrown).
  bool report_displacement = false;
  /// Tumbler: the inner half extent of the container (mm) and the index of
  /// one of its walls, whose angle turns body positions into its frame.
  int32_t container_half = 0;
  int32_t container_wall = -1;
  /// In tick order. Their bodies have no index for pose(); the figures
  /// cover the scene's own bodies and joints.
  std::vector<Wave2D> waves;
  /// The scene's joints have springs (Box2D 2.4's revolute joint has none).
  bool joint_springs = false;
};

/// Base `base` (base (base + 1) / 2 boxes of half size 0.5 m) on a static
/// ground box; each row shifted half a box, boxes touching side by side.
Scene2D make_pyramid2d(int base);
/// `count` pyramids of base `base` side by side on one ground box.
Scene2D make_pyramids2d(int count, int base);
/// A hollow 20 m box (four 1 m thick walls) turning at 0.05 pi rad/s about
/// its centre, filled at once with `count` boxes of half size 0.125 m.
Scene2D make_tumbler2d(int count);
/// An n x n grid of circles (radius 0.4 m, 1 m apart), each joined to its
/// upper and left neighbours by revolute joints at the midpoint, hanging
/// from the 7 middle circles of the top row (static).
Scene2D make_joint_grid2d(int n);
/// Box2D's smash: no gravity, a heavy box (half size 4 m, density 8,
/// 40 m/s) flying into a wall of `columns` x 80 boxes (half size 0.2 m,
/// touching) that start asleep and wake as the blow reaches them.
Scene2D make_smash2d(int columns);
/// Box2D v3's rain: 5 static floors of `columns` x 12.5 + 1 boxes
/// (0.5 m, 45 m between rows); every 8 ticks, a column of 5 groups of 5
/// ragdolls (11 capsules, 10 revolute joints with limits, springs and
/// friction) drops onto the floors; once `columns` columns fell, the
/// oldest column is removed before a new one drops. The ragdolls' feet (a second
/// shape on the lower legs) are left out: a Rewind 2D body has one shape.
Scene2D make_rain2d(int columns);
/// The scenes by name ("large_pyramid", "pyramids", "tumbler",
/// "joint_grid", "smash", "rain") at their benchmark sizes; size 0 picks
/// the default size.
bool make_scene2d(const std::string& name, int size, Scene2D& out);
/// The scene names make_scene2d() knows, in report order.
const std::vector<std::string>& scene2d_names();

}  // namespace rwd::bench
