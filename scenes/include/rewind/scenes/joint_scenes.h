// SPDX-License-Identifier: MIT
#pragma once
// Jointed scenes, described once: bodies (spheres, boxes and capsules),
// ball and hinge joints between them with their anchors in each body's
// frame (and, where a scene wants them, cone-twist and hinge limits), and
// the figures measured on them (joint_scene_meter.h: how far a joint's
// two anchors are apart, how much a chain stretched, a pendulum's period,
// the energy of the whole). Shared by the stability and accuracy suites (on Rewind) and the
// side-by-side benchmark (Rewind and Bullet build the same description).
// Header only but for ragdoll_pile() (src/joint_ragdoll_pile.cpp, which
// reads its ragdolls off Rewind's ragdoll builder); depends on the
// engine's public API.
//
// The scenes:
// - hanging_chain: 20 box links on ball joints hanging from a fixed point,
//   holding a sphere of 100 times a link's mass (a mass ratio solvers
//   stretch under);
// - rope_bridge: planks hinged end to end, hung with slack between two
//   static posts, with boxes dropped on them;
// - joint_grid: an N x N sheet of spheres, each held to its neighbours by
//   ball joints at their midpoints, held along one edge (a static row) and
//   falling from horizontal;
// - hinge_pendulum: a box rod on a hinge at its end, let go at a small
//   angle (the physical pendulum);
// - ragdoll_pile: Rewind's 11-capsule ragdolls (rewind/sim/ragdoll3d.h)
//   in ten crossed layers of five, dropped on a floor (the pile of the
//   stability suite, tests/stability/ragdoll_pile3d.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "rewind/sim/world3d.h"

namespace rwd::scenes {

/// A capsule stands along its body's local y axis, as Rewind's
/// Shape::make_capsule and Bullet's btCapsuleShape both do.
enum class JointSceneShape : uint8_t { kSphere, kBox, kCapsule };

struct JointSceneBody {
  bool fixed = false;  ///< static: never moves
  JointSceneShape shape = JointSceneShape::kBox;
  /// Box half extents; a sphere's and a capsule's radius is half.x.
  sim::Vec3 half{0.5f, 0.5f, 0.5f};
  /// Capsule: half the distance between its cap centres, along local y.
  float half_height = 0.0f;
  sim::Vec3 position;
  sim::Quat rotation;
  float density = 1000.0f;  ///< kg/m^3
  float angular_damping = 0.0f;
  float friction = 0.6f;
  /// Bodies of one group (>= 0) never collide with each other (a
  /// ragdoll's parts), while they collide with everything else; -1: in no
  /// group. Joined bodies never collide either way.
  int collision_group = -1;

  float volume() const {
    if (shape == JointSceneShape::kSphere) {
      return 4.0f / 3.0f * 3.14159265f * half.x * half.x * half.x;
    }
    if (shape == JointSceneShape::kCapsule) {
      const float r = half.x;
      return 3.14159265f * r * r * (2.0f * half_height + 4.0f / 3.0f * r);
    }
    return 8.0f * half.x * half.y * half.z;
  }
  float mass_kg() const { return fixed ? 0.0f : density * volume(); }
  /// Principal moments about the centre, body frame, kg m^2.
  sim::Vec3 inertia() const {
    const float m = mass_kg();
    if (shape == JointSceneShape::kSphere) {
      const float i = 0.4f * m * half.x * half.x;
      return {i, i, i};
    }
    if (shape == JointSceneShape::kCapsule) {
      // Rewind's capsule (sim/src/d3/shape_capsule.cpp): the cylinder and
      // the two hemispheres share the mass by volume, each cap's inertia
      // moved out to the centre from its own centre of mass, 3r/8 off its
      // flat face.
      const float r = half.x, h = half_height;
      const float v_c = 3.14159265f * r * r * 2.0f * h;
      const float v_s = 4.0f / 3.0f * 3.14159265f * r * r * r;
      const float m_c = m * v_c / (v_c + v_s), m_s = m - m_c;
      const float axial = m_c * r * r * 0.5f + m_s * r * r * 0.4f;
      const float across =
          m_c * (r * r * 0.25f + h * h / 3.0f) + m_s * (r * r * 0.4f + h * h + 0.75f * h * r);
      return {across, axial, across};
    }
    const sim::Vec3 s{half.x * half.x, half.y * half.y, half.z * half.z};
    return {m * (s.y + s.z) / 3.0f, m * (s.x + s.z) / 3.0f, m * (s.x + s.y) / 3.0f};
  }
};

enum class JointSceneType : uint8_t { kBall, kHinge };

struct JointSceneJoint {
  JointSceneType type = JointSceneType::kBall;
  int a = -1;  ///< body index, -1: the world
  int b = 0;
  /// The joint's point in each body's frame (world coordinates when a is -1).
  sim::Vec3 local_a;
  sim::Vec3 local_b;
  /// Hinge axis in each body's frame (world when a is -1).
  sim::Vec3 axis_a{0.0f, 0.0f, 1.0f};
  sim::Vec3 axis_b{0.0f, 0.0f, 1.0f};
  /// A friction torque, N m (0: none): the joint resists turning with up
  /// to this much, as a motor held at zero relative speed. Bullet's hinges
  /// take it as a motor too; its cone-twist joints have no velocity motor
  /// and go without (which costs Rewind, not Bullet, the extra rows).
  float friction_torque_nm = 0.0f;
  /// Limits, rad, counted from the starting pose (false: none, and the
  /// fields below are not read). A ball joint becomes a cone-twist joint:
  /// axis_b (the twist axis, in b's frame) swings at most cone_angle away
  /// from axis_a (the cone's centre, in a's frame), and b twists about it
  /// within [twist_lower, twist_upper]. A hinge's angle, b turning about
  /// the axis by the right hand, stays within [lower, upper].
  bool limited = false;
  float cone_angle = 0.0f;
  float twist_lower = 0.0f;
  float twist_upper = 0.0f;
  float lower = 0.0f;
  float upper = 0.0f;
};

struct JointScene {
  std::string name;
  int size = 0;
  std::vector<JointSceneBody> bodies;
  std::vector<JointSceneJoint> joints;
  sim::Vec3 gravity{0.0f, -9.81f, 0.0f};
  int ticks = 600;  ///< 60 Hz ticks the scene runs
  /// hanging_chain: the heavy body, the chain's first joint (to the world)
  /// and its last (to the heavy body), and the pivot-to-anchor length.
  int heavy = -1;
  int first_joint = -1;
  int last_joint = -1;
  float chain_length_m = 0.0f;
  /// rope_bridge: the planks and the dropped boxes.
  std::vector<int> planks;
  std::vector<int> loads;
  /// hinge_pendulum: the rod, its starting angle (rad) and the analytic
  /// period (s) at that amplitude.
  int rod = -1;
  float amplitude_rad = 0.0f;
  double analytic_period_s = 0.0;
  /// joint_grid: the energy its fall can release (the dynamic mass
  /// lowered by half the sheet's side), J: the scale of energy errors.
  double energy_scale_j = 0.0;

  int dynamic_count() const {
    int n = 0;
    for (const JointSceneBody& b : bodies) n += b.fixed ? 0 : 1;
    return n;
  }

  /// Adds a joint through the world point `at` (and world axis), its
  /// anchors and axes taken in each body's frame at the starting poses.
  void join(JointSceneType type, int a, int b, sim::Vec3 at, sim::Vec3 axis = {0, 0, 1}) {
    JointSceneJoint j;
    j.type = type;
    j.a = a;
    j.b = b;
    j.local_a = a < 0 ? at : to_local(a, at);
    j.axis_a = a < 0 ? axis : sim::inv_rotate(bodies[static_cast<size_t>(a)].rotation, axis);
    j.local_b = to_local(b, at);
    j.axis_b = sim::inv_rotate(bodies[static_cast<size_t>(b)].rotation, axis);
    joints.push_back(j);
  }
  sim::Vec3 to_local(int i, sim::Vec3 world) const {
    const JointSceneBody& body = bodies[static_cast<size_t>(i)];
    return sim::inv_rotate(body.rotation, world - body.position);
  }
};

/// A body's state as an engine reports it (centre = authored frame: the
/// scenes only use spheres, boxes and capsules).
struct JointBodyState {
  sim::Vec3 position;
  sim::Quat rotation;
  sim::Vec3 linear_velocity;
  sim::Vec3 angular_velocity;
};

// --- the scenes ----------------------------------------------------------

/// `links` box links (0.1 x 0.5 x 0.1 m, 5 kg) on ball joints hanging
/// straight down from a fixed point 15 m up, holding a sphere (radius
/// 0.3 m) of `mass_ratio` times a link's mass on the last link.
inline JointScene hanging_chain(int links = 20, float mass_ratio = 100.0f) {
  JointScene s;
  s.name = "chain";
  s.size = links;
  s.ticks = 600;
  const float top = 15.0f;
  const sim::Vec3 half{0.05f, 0.25f, 0.05f};
  for (int i = 0; i < links; ++i) {
    JointSceneBody link;
    link.half = half;
    link.position = {0.0f, top - half.y - 2.0f * half.y * static_cast<float>(i), 0.0f};
    s.bodies.push_back(link);
    const sim::Vec3 at{0.0f, top - 2.0f * half.y * static_cast<float>(i), 0.0f};
    s.join(JointSceneType::kBall, i - 1, i, at);
  }
  s.first_joint = 0;
  const float end = top - 2.0f * half.y * static_cast<float>(links);
  JointSceneBody heavy;
  heavy.shape = JointSceneShape::kSphere;
  heavy.half = {0.3f, 0.3f, 0.3f};
  heavy.position = {0.0f, end - 0.3f, 0.0f};
  heavy.density = mass_ratio * s.bodies[0].mass_kg() / heavy.volume();
  s.bodies.push_back(heavy);
  s.heavy = links;
  s.join(JointSceneType::kBall, links - 1, links, {0.0f, end, 0.0f});
  s.last_joint = static_cast<int>(s.joints.size()) - 1;
  s.chain_length_m = top - end;
  return s;
}

/// `planks` planks (1 x 0.1 x 0.8 m, pine, 48 kg, a little angular
/// damping as rope and wood have) hinged end to end about z, hung between
/// two static posts 2 planks cos(0.2) apart (so they start in a shallow V,
/// 0.2 rad each side), and `loads` boxes of 0.5 m (125 kg) dropped on them
/// from 1 to 3 m above.
inline JointScene rope_bridge(int planks = 20, int loads = 8, float friction_torque_nm = 100.0f) {
  JointScene s;
  s.name = "bridge";
  s.size = planks;
  s.ticks = 600;
  const float tilt = 0.2f;
  const float c = std::cos(tilt), sn = std::sin(tilt);
  const float half_span = 0.5f * static_cast<float>(planks) * c;
  sim::Vec3 at{-half_span, 10.0f, 0.0f};
  JointSceneBody post;
  post.fixed = true;
  post.half = {0.2f, 0.2f, 0.5f};
  post.position = at - sim::Vec3{0.2f, 0.0f, 0.0f};
  s.bodies.push_back(post);
  int previous = 0;
  for (int i = 0; i < planks; ++i) {
    const bool down = i < planks / 2;
    const sim::Vec3 dir{c, down ? -sn : sn, 0.0f};
    const float angle = down ? -tilt : tilt;  // about z
    JointSceneBody plank;
    plank.half = {0.5f, 0.05f, 0.4f};
    plank.density = 600.0f;
    plank.angular_damping = 0.5f;
    plank.position = at + dir * 0.5f;
    plank.rotation = {0.0f, 0.0f, std::sin(0.5f * angle), std::cos(0.5f * angle)};
    s.bodies.push_back(plank);
    const int id = static_cast<int>(s.bodies.size()) - 1;
    s.planks.push_back(id);
    s.join(JointSceneType::kHinge, previous, id, at);
    previous = id;
    at = at + dir;
  }
  post.position = at + sim::Vec3{0.2f, 0.0f, 0.0f};
  s.bodies.push_back(post);
  s.join(JointSceneType::kHinge, previous, static_cast<int>(s.bodies.size()) - 1, at);
  for (JointSceneJoint& j : s.joints) j.friction_torque_nm = friction_torque_nm;
  for (int i = 0; i < loads; ++i) {
    JointSceneBody box;
    box.half = {0.25f, 0.25f, 0.25f};
    const float x = -half_span + 1.5f +
                    (2.0f * half_span - 3.0f) * static_cast<float>(i) /
                        static_cast<float>(loads > 1 ? loads - 1 : 1);
    box.position = {x, 11.0f + static_cast<float>(i % 3), 0.0f};
    s.bodies.push_back(box);
    s.loads.push_back(static_cast<int>(s.bodies.size()) - 1);
  }
  return s;
}

/// An n x n sheet of spheres (radius 0.15 m, 0.5 m apart, 14 kg) in the
/// horizontal plane 20 m up; each joined to its +x and +z neighbours by a
/// ball joint at their midpoint (2 n (n - 1) joints, the 29 between two
/// static spheres left out). The row at z = 0 is static: the sheet falls
/// from horizontal, swinging about that edge.
inline JointScene joint_grid(int n = 30) {
  JointScene s;
  s.name = "grid";
  s.size = n;
  s.ticks = 600;
  const float spacing = 0.5f;
  auto index = [n](int i, int k) { return k * n + i; };
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < n; ++i) {
      JointSceneBody ball;
      ball.fixed = k == 0;
      ball.shape = JointSceneShape::kSphere;
      ball.half = {0.15f, 0.15f, 0.15f};
      ball.position = {spacing * static_cast<float>(i), 20.0f, spacing * static_cast<float>(k)};
      s.bodies.push_back(ball);
    }
  }
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < n; ++i) {
      const sim::Vec3 p = s.bodies[static_cast<size_t>(index(i, k))].position;
      if (i + 1 < n && k > 0) {
        s.join(JointSceneType::kBall, index(i, k), index(i + 1, k),
               p + sim::Vec3{0.5f * spacing, 0.0f, 0.0f});
      }
      if (k + 1 < n) {
        s.join(JointSceneType::kBall, index(i, k), index(i, k + 1),
               p + sim::Vec3{0.0f, 0.0f, 0.5f * spacing});
      }
    }
  }
  double mass = 0.0;
  for (const JointSceneBody& b : s.bodies) mass += b.mass_kg();
  s.energy_scale_j = mass * 9.81 * 0.5 * spacing * (n - 1);
  return s;
}

/// A box rod (0.1 x 1 x 0.1 m, 10 kg, no damping) on a hinge about z at its
/// top end, 10.5 m up, let go `amplitude_rad` from hanging straight down.
/// Its period is that of the physical pendulum, 2 pi sqrt(I_pivot /
/// (m g d)) with d the pivot-to-centre distance, lengthened by the
/// amplitude's first-order term (1 + amplitude^2 / 16).
inline JointScene hinge_pendulum(float amplitude_rad = 0.05f) {
  JointScene s;
  s.name = "pendulum";
  s.size = 1;
  s.ticks = 600;
  const sim::Vec3 pivot{0.0f, 10.5f, 0.0f};
  JointSceneBody rod;
  rod.half = {0.05f, 0.5f, 0.05f};
  const float d = rod.half.y;
  rod.position = pivot + sim::Vec3{d * std::sin(amplitude_rad), -d * std::cos(amplitude_rad), 0.0f};
  rod.rotation = {0.0f, 0.0f, std::sin(0.5f * amplitude_rad), std::cos(0.5f * amplitude_rad)};
  s.bodies.push_back(rod);
  s.rod = 0;
  s.amplitude_rad = amplitude_rad;
  s.join(JointSceneType::kHinge, -1, 0, pivot);
  const double m = rod.mass_kg();
  const double i_pivot = static_cast<double>(rod.inertia().z) + m * d * d;
  const double t0 = 2.0 * 3.14159265358979 * std::sqrt(i_pivot / (m * 9.81 * d));
  s.analytic_period_s = t0 * (1.0 + static_cast<double>(amplitude_rad) * amplitude_rad / 16.0);
  return s;
}

/// `count` of Rewind's ragdolls (rewind/sim/ragdoll3d.h, default spec:
/// 1.8 m, 70 kg, eleven capsules, cone-twist waist, neck, shoulders and
/// hips, one-way hinges at elbows and knees) lying face up in crossed
/// layers of five, each turned a little and dropped from 0.4 m up (0.45 m
/// more a layer: 0.4 to 4.5 m for fifty) onto a static floor box (60 x 1 x
/// 60 m, top at y = 0): the pile of tests/stability/ragdoll_pile3d.h. Each
/// ragdoll is its own collision group. Parts, anchors, axes, limits,
/// densities, damping and friction are read off the ragdolls
/// create_ragdoll() makes, so the scene follows the builder. 480 ticks
/// (8 s: the pile settles). Defined in src/joint_ragdoll_pile.cpp; an empty
/// name when the builder refuses.
JointScene ragdoll_pile(int count = 50);

/// The scenes by name ("chain", "bridge", "grid", "pendulum",
/// "ragdoll_pile"); size 0 takes the scene's own. An empty name field
/// means an unknown one.
inline JointScene make_joint_scene(const std::string& name, int size = 0) {
  if (name == "chain") return hanging_chain(size > 0 ? size : 20);
  if (name == "bridge") return rope_bridge(size > 0 ? size : 20);
  if (name == "grid") return joint_grid(size > 0 ? size : 30);
  if (name == "pendulum") return hinge_pendulum();
  if (name == "ragdoll_pile") return ragdoll_pile(size > 0 ? size : 50);
  return {};
}

inline std::vector<std::string> joint_scene_names() {
  return {"pendulum", "chain", "bridge", "grid", "ragdoll_pile"};
}

// --- on Rewind ---------------------------------------------------------------

/// A scene built on a Rewind world: its bodies and joints, index for index.
struct RewindJointScene {
  std::vector<sim::BodyId> bodies;
  std::vector<sim::JointId> joints;
  std::string error;  ///< non-empty: the world refused part of the scene

  void states(const sim::World3D& world, std::vector<JointBodyState>& out) const {
    out.resize(bodies.size());
    for (size_t i = 0; i < bodies.size(); ++i) {
      out[i] = {world.position(bodies[i]), world.rotation(bodies[i]),
                world.linear_velocity(bodies[i]), world.angular_velocity(bodies[i])};
    }
  }
};

/// The layer bits of collision group `group` on Rewind: a pair of the
/// layer bits 1 to 31, a different pair for each group (the scheme
/// tests/stability/ragdoll_pile3d.h gives its ragdolls, there from bits 16
/// to 31), so no group's bits hold another's and a body whose mask is all
/// but its own bits collides with every other group and with ungrouped
/// bodies (layer bit 0, the default). 0 past the 465 groups the pairs run
/// to.
inline uint32_t rewind_group_layer(int group) {
  int n = group;
  for (uint32_t a = 1; a < 32; ++a) {
    for (uint32_t b = a + 1; b < 32; ++b) {
      if (n-- == 0) return (1u << a) | (1u << b);
    }
  }
  return 0;
}

/// Builds `scene` in `world` (whose gravity should be scene.gravity).
/// Joined bodies do not collide with each other, nor bodies of one
/// collision group (layers: rewind_group_layer()).
inline RewindJointScene build_rewind(sim::World3D& world, const JointScene& scene) {
  RewindJointScene r;
  for (const JointSceneBody& b : scene.bodies) {
    sim::BodyDef def;
    def.kind = b.fixed ? sim::BodyKind::kStatic : sim::BodyKind::kDynamic;
    switch (b.shape) {
      case JointSceneShape::kSphere:
        def.shape = sim::Shape::make_sphere(b.half.x);
        break;
      case JointSceneShape::kBox:
        def.shape = sim::Shape::make_box(b.half);
        break;
      case JointSceneShape::kCapsule:
        def.shape = sim::Shape::make_capsule(b.half.x, b.half_height);
        break;
    }
    if (b.collision_group >= 0) {
      def.layer = rewind_group_layer(b.collision_group);
      if (def.layer == 0) {
        r.error = "body: more collision groups than Rewind's layer bits hold (465)";
        return r;
      }
      def.mask = ~def.layer;
    }
    def.position = b.position;
    def.rotation = b.rotation;
    def.density = b.density;
    def.angular_damping = b.angular_damping;
    def.material.friction = b.friction;
    auto id = world.create_body(def);
    if (!id.ok()) {
      r.error = "body: " + id.status().message();
      return r;
    }
    r.bodies.push_back(*id);
  }
  for (const JointSceneJoint& j : scene.joints) {
    sim::JointDef def;
    def.type = j.type == JointSceneType::kBall ? sim::JointType::kBall : sim::JointType::kHinge;
    if (j.a >= 0) def.body_a = r.bodies[static_cast<size_t>(j.a)];
    def.body_b = r.bodies[static_cast<size_t>(j.b)];
    def.anchor_a = j.local_a;
    def.anchor_b = j.local_b;
    def.axis_a = j.axis_a;
    def.axis_b = j.axis_b;
    if (j.friction_torque_nm > 0.0f) {
      def.enable_motor = true;
      def.motor_speed = 0.0f;
      def.max_motor_torque = j.friction_torque_nm;
    }
    if (j.limited) {
      def.enable_limit = true;
      def.cone_angle = j.cone_angle;
      def.twist_lower = j.twist_lower;
      def.twist_upper = j.twist_upper;
      def.lower = j.lower;
      def.upper = j.upper;
    }
    auto id = world.create_joint(def);
    if (!id.ok()) {
      r.error = "joint: " + id.status().message();
      return r;
    }
    r.joints.push_back(*id);
  }
  return r;
}

}  // namespace rwd::scenes
