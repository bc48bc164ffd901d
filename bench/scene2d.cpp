// SPDX-License-Identifier: MIT
#include "scene2d.h"

#include <algorithm>
#include <utility>

namespace rwd::bench {

namespace {

constexpr int32_t kHalf = 500;  // mm: the pyramid boxes' half size

// Adds a pyramid of `base` boxes whose bottom row is centred on x0 (mm),
// resting on y = 0, and returns the index of its top box.
uint32_t add_pyramid(Scene2D& s, int base, int32_t x0) {
  for (int row = 0; row < base; ++row) {
    const int n = base - row;
    for (int i = 0; i < n; ++i) {
      BodyDesc2D b;
      // Boxes touch side by side; each row is centred on the row below.
      b.x = x0 + (2 * i - (n - 1)) * kHalf;
      b.y = (2 * row + 1) * kHalf;
      s.bodies.push_back(b);
    }
  }
  return static_cast<uint32_t>(s.bodies.size() - 1);
}

void add_ground(Scene2D& s, int32_t half_width) {
  BodyDesc2D g;
  g.kind = Kind2D::kStatic;
  g.hx = half_width;
  g.hy = 1000;
  g.y = -1000;  // top face at y = 0
  s.bodies.push_back(g);
}

}  // namespace

Scene2D make_pyramid2d(int base) {
  Scene2D s;
  s.name = "large_pyramid";
  s.size = base;
  s.warmup_ticks = 60;
  s.timed_ticks = 300;
  add_ground(s, std::max(40, base) * 1000);
  s.tops.push_back(add_pyramid(s, base, 0));
  s.report_displacement = true;
  return s;
}

Scene2D make_pyramids2d(int count, int base) {
  Scene2D s;
  s.name = "pyramids";
  s.size = count;
  s.report_displacement = true;
  s.warmup_ticks = 60;
  s.timed_ticks = 300;
  // Two metres between neighbouring bases.
  const int32_t pitch = (base + 2) * 2 * kHalf;
  add_ground(s, (count * pitch) / 2 + 10000);
  for (int p = 0; p < count; ++p) {
    s.tops.push_back(add_pyramid(s, base, (2 * p - (count - 1)) * pitch / 2));
  }
  return s;
}

Scene2D make_tumbler2d(int count) {
  Scene2D s;
  s.name = "tumbler";
  s.size = count;
  s.warmup_ticks = 60;
  s.timed_ticks = 600;
  const int32_t cy = 10000;  // the container's centre and pivot
  const int32_t w = 157;     // 0.05 pi rad/s, the classic tumbler's speed
  // Four walls 1 m thick around a 19 m square inside; the corners overlap.
  const int32_t walls[4][4] = {{500, 10000, 10000, 0},
                               {500, 10000, -10000, 0},
                               {10000, 500, 0, 10000},
                               {10000, 500, 0, -10000}};
  s.container_wall = static_cast<int32_t>(s.bodies.size());
  s.container_half = 9500;
  for (const auto& wall : walls) {
    BodyDesc2D b;
    b.kind = Kind2D::kKinematic;
    b.hx = wall[0];
    b.hy = wall[1];
    b.cx = wall[2];
    b.cy = wall[3];
    b.y = cy;
    b.angular_velocity = w;
    b.group = 0;
    s.bodies.push_back(b);
  }
  // A square grid, 0.5 m pitch, centred in the container: 0.25 m gaps
  // between the 0.25 m boxes, so nothing starts overlapping.
  int side = 1;
  while (side * side < count) ++side;
  for (int i = 0; i < count; ++i) {
    BodyDesc2D b;
    b.hx = 125;
    b.hy = 125;
    b.x = (2 * (i % side) - (side - 1)) * 250;
    b.y = cy + (2 * (i / side) - (side - 1)) * 250;
    s.bodies.push_back(b);
  }
  return s;
}

Scene2D make_joint_grid2d(int n) {
  Scene2D s;
  s.name = "joint_grid";
  s.size = n;
  s.warmup_ticks = 60;
  s.timed_ticks = 180;  // 10,000 bodies and 19,800 joints: the slowest scene
  const int32_t pitch = 1000;
  auto index = [n](int column, int row) { return static_cast<uint32_t>(column * n + row); };
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < n; ++i) {
      BodyDesc2D b;
      const bool anchor = i == 0 && k >= n / 2 - 3 && k <= n / 2 + 3;
      b.kind = anchor ? Kind2D::kStatic : Kind2D::kDynamic;
      b.radius = 400;
      b.x = k * pitch;
      b.y = -i * pitch;
      s.bodies.push_back(b);
      if (i > 0) {
        s.joints.push_back({index(k, i - 1), index(k, i), k * pitch, -i * pitch + pitch / 2});
      }
      // As Box2D's grid, the static anchors side by side are joined too
      // (the joint moves nothing; both engines take it).
      if (k > 0) {
        s.joints.push_back({index(k - 1, i), index(k, i), k * pitch - pitch / 2, -i * pitch});
      }
    }
  }
  return s;
}

Scene2D make_smash2d(int columns) {
  Scene2D s;
  s.name = "smash";
  s.size = columns;
  s.warmup_ticks = 0;
  s.timed_ticks = 300;  // the blow lands at 0.65 s; the wall breaks up by 5 s
  s.gravity = 0;
  s.report_displacement = true;
  BodyDesc2D ram;
  ram.hx = ram.hy = 4000;
  ram.x = -20000;
  ram.vx = 40000;
  ram.density = 8000;
  s.bodies.push_back(ram);
  constexpr int kRows = 80;
  constexpr int32_t kPitch = 400;
  for (int i = 0; i < columns; ++i) {
    for (int j = 0; j < kRows; ++j) {
      BodyDesc2D b;
      b.hx = b.hy = kPitch / 2;
      b.x = i * kPitch + 30000;
      b.y = (2 * j - kRows) * kPitch / 2;
      b.awake = false;
      s.bodies.push_back(b);
    }
  }
  return s;
}

namespace {

// One bone of Box2D v3's ragdoll (its shared/human.c at scale 1): a
// vertical capsule and, for all but the hip, the revolute joint to its
// parent. Lengths in mm, angles in mrad, torque scale in thousandths.
struct Bone2D {
  int parent;  // index into kBones; -1: the hip
  int32_t y;   // body origin above the ragdoll's feet
  int32_t capsule_y0, capsule_y1, radius;
  int32_t linear_damping;  // 1/s x 1000
  int32_t pivot_y;         // the joint's world point above the feet
  int32_t reference, lower, upper;
  int32_t friction_scale;  // x 1000 of the ragdoll's joint friction
};

constexpr Bone2D kBones[] = {
    {-1, 950, -20, 20, 95, 0, 0, 0, 0, 0, 0},                  // hip
    {0, 1200, -135, 135, 90, 0, 1000, 0, -785, 0, 500},        // torso
    {1, 1475, -38, 39, 75, 100, 1400, 0, -942, 314, 250},      // head
    {0, 775, -125, 125, 60, 0, 900, 0, -157, 1257, 1000},      // upper left leg
    {3, 475, -155, 125, 45, 0, 625, 0, -1571, -63, 500},       // lower left leg
    {0, 775, -125, 125, 60, 0, 900, 0, -157, 1257, 1000},      // upper right leg
    {5, 475, -155, 125, 45, 0, 625, 0, -1571, -63, 500},       // lower right leg
    {1, 1225, -125, 125, 35, 0, 1350, 0, -314, 2513, 500},     // upper left arm
    {7, 975, -125, 125, 30, 100, 1100, 785, -628, 942, 100},   // lower left arm
    {1, 1225, -125, 125, 35, 0, 1350, 0, -314, 2513, 500},     // upper right arm
    {9, 975, -125, 125, 30, 100, 1100, 785, -628, 942, 100}};  // lower right arm

constexpr int kRainRows = 5;
constexpr int kRainGroupSize = 5;
constexpr int32_t kRainCell = 500;        // mm: the floor boxes' size
constexpr int32_t kRainRowPitch = 45000;  // mm between floor rows

// Adds one ragdoll standing at (x, y) to `w`. `human` (0..4, its place in
// the group) picks its layer: Box2D's human gives every part of ragdoll
// number k the group index -k, so ragdolls of the same number never touch
// (nor do parts of one ragdoll) and all of them touch the floor (layer 1).
void add_ragdoll(Wave2D& w, int32_t x, int32_t y, int human) {
  const uint32_t first = static_cast<uint32_t>(w.bodies.size());
  const uint32_t layer = 2u << human;
  for (const Bone2D& bone : kBones) {
    BodyDesc2D b;
    b.radius = bone.radius;
    b.capsule_y0 = bone.capsule_y0;
    b.capsule_y1 = bone.capsule_y1;
    b.x = x;
    b.y = y + bone.y;
    b.friction = 200;
    b.linear_damping = bone.linear_damping;
    b.layer = layer;
    b.mask = 1u | (0x3Eu & ~layer);
    w.bodies.push_back(b);
    if (bone.parent < 0) continue;
    RevoluteDesc2D j;
    j.a = first + static_cast<uint32_t>(bone.parent);
    j.b = static_cast<uint32_t>(w.bodies.size() - 1);
    j.x = x;
    j.y = y + bone.pivot_y;
    j.reference = bone.reference;
    j.limit = true;
    j.lower = bone.lower;
    j.upper = bone.upper;
    j.friction_torque = 50 * bone.friction_scale / 1000;  // 0.05 N m at scale 1
    j.hertz = 5000;
    j.damping_ratio = 500;
    w.joints.push_back(j);
  }
}

}  // namespace

Scene2D make_rain2d(int columns) {
  Scene2D s;
  s.name = "rain";
  s.size = columns;
  s.warmup_ticks = 0;
  s.timed_ticks = 1000;  // as Box2D v3's benchmark: 40 columns land by tick 320
  s.joint_springs = true;
  const int cells = columns * 25 / 2;  // 500 at 40 columns, as Box2D's
  const int32_t span = cells * kRainCell;
  for (int row = 0; row < kRainRows; ++row) {
    for (int j = 0; j <= cells; ++j) {
      BodyDesc2D b;
      b.kind = Kind2D::kStatic;
      b.hx = b.hy = kRainCell / 2;
      b.cx = -span / 2 + j * kRainCell;
      b.cy = row * kRainRowPitch;
      b.group = 0;  // one Box2D body of many boxes, as Box2D's floor
      s.bodies.push_back(b);
    }
  }
  const int32_t pitch = span / columns;
  for (int k = 0; 8 * k < s.timed_ticks; ++k) {
    Wave2D w;
    w.tick = 8 * k;
    if (k >= columns) w.removes.push_back(static_cast<uint32_t>(k - columns));
    const int column = k % columns;
    for (int row = 0; row < kRainRows; ++row) {
      int32_t x = -span / 2 + pitch * column + pitch / 2;
      const int32_t y = 40000 + row * kRainRowPitch;
      for (int human = 0; human < kRainGroupSize; ++human, x += 500) add_ragdoll(w, x, y, human);
    }
    s.waves.push_back(std::move(w));
  }
  return s;
}

const std::vector<std::string>& scene2d_names() {
  static const std::vector<std::string> names = {"large_pyramid", "pyramids", "tumbler",
                                                 "joint_grid",    "smash",    "rain"};
  return names;
}

bool make_scene2d(const std::string& name, int size, Scene2D& out) {
  if (name == "large_pyramid") {
    out = make_pyramid2d(size > 0 ? size : 100);
  } else if (name == "pyramids") {
    out = make_pyramids2d(size > 0 ? size : 20, 10);
  } else if (name == "tumbler") {
    out = make_tumbler2d(size > 0 ? size : 800);
  } else if (name == "joint_grid") {
    out = make_joint_grid2d(size > 0 ? size : 100);
  } else if (name == "smash") {
    out = make_smash2d(size > 0 ? size : 120);
  } else if (name == "rain") {
    out = make_rain2d(size > 0 ? size : 40);
  } else {
    return false;
  }
  return true;
}

}  // namespace rwd::bench
