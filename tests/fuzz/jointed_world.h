// SPDX-License-Identifier: MIT
#pragma once
// A small 3D world with every kind of joint state for the snapshot fuzz
// entry and its corpus: a chain (a joint tree) with cone limits, a hinge
// with a motor and limits, a prismatic with a spring, a weld, a rope, a
// grab and a joint that breaks, stepped `ticks` ticks.
#include "rewind/sim/world3d.h"

namespace rwd::fuzz {

inline void build_jointed_world(sim::World3D& world, int ticks) {
  using namespace rwd::sim;
  auto add = [&](BodyKind kind, const Shape& shape, Vec3 p) {
    BodyDef def;
    def.kind = kind;
    def.shape = shape;
    def.position = p;
    return *world.create_body(def);
  };
  add(BodyKind::kStatic, Shape::make_box({10.0f, 0.5f, 10.0f}), {0.0f, -0.5f, 0.0f});
  BodyId prev = add(BodyKind::kStatic, Shape::make_box({0.2f, 0.2f, 0.2f}), {0.0f, 5.2f, 0.0f});
  for (int i = 0; i < 4; ++i) {
    const float y = 5.0f - 0.4f * static_cast<float>(i) - 0.2f;
    const BodyId link = add(BodyKind::kDynamic, Shape::make_capsule(0.05f, 0.15f), {0.0f, y, 0.0f});
    JointDef def =
        joint_at(world, JointType::kBall, prev, link, {0.0f, y + 0.2f, 0.0f}, {0.0f, -1.0f, 0.0f});
    def.enable_limit = true;
    def.cone_angle = 0.5f;
    (void)world.create_joint(def);
    prev = link;
  }
  (void)world.set_linear_velocity(prev, {3.0f, 0.0f, 1.0f});
  const BodyId wheel =
      add(BodyKind::kDynamic, Shape::make_box({0.3f, 0.1f, 0.1f}), {2.0f, 2.0f, 0.0f});
  JointDef hinge =
      joint_at(world, JointType::kHinge, {}, wheel, {2.0f, 2.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
  hinge.enable_motor = true;
  hinge.motor_speed = 2.0f;
  hinge.max_motor_torque = 5.0f;
  hinge.enable_limit = true;
  hinge.lower = -1.0f;
  hinge.upper = 1.0f;
  (void)world.create_joint(hinge);
  const BodyId car =
      add(BodyKind::kDynamic, Shape::make_box({0.2f, 0.1f, 0.2f}), {-2.0f, 2.0f, 0.0f});
  JointDef slide =
      joint_at(world, JointType::kPrismatic, {}, car, {-2.0f, 2.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
  slide.enable_spring = true;
  slide.hertz = 2.0f;
  (void)world.create_joint(slide);
  const BodyId cargo = add(BodyKind::kDynamic, Shape::make_sphere(0.1f), {-2.0f, 2.2f, 0.0f});
  (void)world.create_joint(joint_at(world, JointType::kWeld, car, cargo, {-2.0f, 2.1f, 0.0f}));
  const BodyId bob = add(BodyKind::kDynamic, Shape::make_sphere(0.2f), {4.0f, 3.0f, 0.0f});
  JointDef rope =
      joint_between(world, JointType::kDistance, {}, bob, {4.0f, 4.0f, 0.0f}, {4.0f, 3.0f, 0.0f});
  rope.min_length = 0.0f;
  (void)world.create_joint(rope);
  const BodyId grabbed = add(BodyKind::kDynamic, Shape::make_sphere(0.2f), {-4.0f, 1.0f, 0.0f});
  JointDef grab = joint_at(world, JointType::kGrab, {}, grabbed, {-4.0f, 1.0f, 0.0f});
  grab.target = {-4.0f, 2.0f, 0.0f};
  (void)world.create_joint(grab);
  const BodyId heavy =
      add(BodyKind::kDynamic, Shape::make_box({0.3f, 0.3f, 0.3f}), {6.0f, 3.0f, 0.0f});
  JointDef weak = joint_at(world, JointType::kBall, {}, heavy, {6.0f, 3.3f, 0.0f});
  weak.break_impulse = 20.0f;
  (void)world.create_joint(weak);
  for (int t = 0; t < ticks; ++t) world.step();
}

}  // namespace rwd::fuzz
