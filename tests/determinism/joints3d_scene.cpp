// SPDX-License-Identifier: MIT
// The 3D joint scene of det_checksums (joints3d_scene.h).
#include "joints3d_scene.h"

#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>
#include <vector>

#include "rewind/sim/character3d.h"
#include "rewind/sim/vehicle3d.h"
#include "rewind/sim/world3d.h"

namespace rwd::determinism {
namespace {

using namespace rwd::sim;

constexpr Vec3 kX{1.0f, 0.0f, 0.0f};
constexpr Vec3 kY{0.0f, 1.0f, 0.0f};
constexpr Vec3 kZ{0.0f, 0.0f, 1.0f};

BodyId body(World3D& world, BodyKind kind, const Shape& shape, Vec3 position, Quat rotation = {}) {
  BodyDef def;
  def.kind = kind;
  def.shape = shape;
  def.position = position;
  def.rotation = rotation;
  def.material.friction = 0.7f;
  auto id = world.create_body(def);
  return id.ok() ? *id : BodyId{};
}

BodyId dynamic(World3D& world, const Shape& shape, Vec3 position, Quat rotation = {}) {
  return body(world, BodyKind::kDynamic, shape, position, rotation);
}

void joint(World3D& world, const JointDef& def) {
  if (!world.create_joint(def).ok()) std::printf("joints3d JOINT-REFUSED\n");
}

struct Scene {
  World3D world;
  BodyId chassis;
  std::vector<WheelDef3D> wheels;
  CharacterState3D character;
  CharacterConfig3D character_config;

  Scene() {
    body(world, BodyKind::kStatic, Shape::make_box({40.0f, 0.5f, 40.0f}), {0.0f, -0.5f, 0.0f});
    const BodyId post =
        body(world, BodyKind::kStatic, Shape::make_box({0.2f, 0.2f, 0.2f}), {0.0f, 8.2f, 0.0f});
    // A chain of capsules (a tree) holding a heavy ball, kicked sideways.
    BodyId prev = post;
    for (int i = 0; i < 8; ++i) {
      const float y = 8.0f - 0.3f * (static_cast<float>(i) + 0.5f);
      const BodyId link = dynamic(world, Shape::make_capsule(0.05f, 0.1f), {0.0f, y, 0.0f});
      JointDef def = joint_at(world, JointType::kBall, prev, link,
                              {0.0f, 8.0f - 0.3f * static_cast<float>(i), 0.0f}, -kY);
      def.enable_limit = i % 2 == 1;
      def.cone_angle = 0.8f;
      def.twist_lower = -0.4f;
      def.twist_upper = 0.4f;
      joint(world, def);
      prev = link;
    }
    const BodyId ball = dynamic(world, Shape::make_sphere(0.3f), {0.0f, 5.3f, 0.0f});
    joint(world, joint_at(world, JointType::kBall, prev, ball, {0.0f, 5.6f, 0.0f}));
    (void)world.set_linear_velocity(ball, {4.0f, 0.0f, 1.5f});
    // A branching figure (a tree with a three-joint hub) with hinges.
    const BodyId hub = dynamic(world, Shape::make_box({0.2f, 0.3f, 0.15f}), {5.0f, 4.0f, 0.0f});
    joint(world, joint_at(world, JointType::kBall, {}, hub, {5.0f, 4.3f, 0.0f}));
    for (int side = -1; side <= 1; side += 2) {
      const float s = static_cast<float>(side);
      const BodyId arm =
          dynamic(world, Shape::make_capsule(0.06f, 0.2f), {5.0f + 0.45f * s, 4.2f, 0.0f},
                  Quat{0.0f, 0.0f, 0.70710678f, 0.70710678f});
      JointDef elbow =
          joint_at(world, JointType::kHinge, hub, arm, {5.0f + 0.2f * s, 4.2f, 0.0f}, kZ);
      elbow.enable_limit = true;
      elbow.lower = -1.2f;
      elbow.upper = 0.3f;
      elbow.enable_spring = side > 0;
      elbow.hertz = 2.0f;
      joint(world, elbow);
    }
    const BodyId leg = dynamic(world, Shape::make_capsule(0.07f, 0.25f), {5.0f, 3.3f, 0.0f});
    JointDef hip = joint_at(world, JointType::kBall, hub, leg, {5.0f, 3.7f, 0.0f}, -kY);
    hip.enable_limit = true;
    hip.cone_angle = 0.6f;
    hip.enable_motor = true;
    hip.motor_velocity = {0.0f, 1.0f, 0.5f};
    hip.max_motor_torque = 20.0f;
    joint(world, hip);
    // A ring of four boxes (a loop: solved joint by joint).
    const Vec3 ring[4] = {
        {-5.0f, 3.0f, 0.0f}, {-4.0f, 3.0f, 0.0f}, {-4.0f, 3.0f, 1.0f}, {-5.0f, 3.0f, 1.0f}};
    BodyId boxes[4];
    for (int i = 0; i < 4; ++i)
      boxes[i] = dynamic(world, Shape::make_box({0.2f, 0.2f, 0.2f}), ring[i]);
    for (int i = 0; i < 4; ++i) {
      joint(world, joint_at(world, JointType::kBall, boxes[i], boxes[(i + 1) % 4],
                            (ring[i] + ring[(i + 1) % 4]) * 0.5f));
    }
    joint(world, joint_between(world, JointType::kDistance, {}, boxes[0],
                               ring[0] + Vec3{0.0f, 1.0f, 0.0f}, ring[0]));
    // A 4 x 4 sheet of spheres on bare ball joints (point joints, coloured
    // into full and partly empty lane batches), its first row held to the
    // world, falling from horizontal.
    BodyId sheet[4][4];
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        sheet[r][c] = dynamic(
            world, Shape::make_sphere(0.12f),
            {8.0f + 0.4f * static_cast<float>(c), 4.0f, -2.0f + 0.4f * static_cast<float>(r)});
      }
    }
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        const Vec3 at{8.0f + 0.4f * static_cast<float>(c), 4.0f,
                      -2.0f + 0.4f * static_cast<float>(r)};
        if (r == 0)
          joint(world, joint_at(world, JointType::kBall, {}, sheet[r][c], at - kZ * 0.2f));
        if (c + 1 < 4)
          joint(world,
                joint_at(world, JointType::kBall, sheet[r][c], sheet[r][c + 1], at + kX * 0.2f));
        if (r + 1 < 4)
          joint(world,
                joint_at(world, JointType::kBall, sheet[r][c], sheet[r + 1][c], at + kZ * 0.2f));
      }
    }
    // A motorized prismatic lift with limits and a spring, a weld, a soft
    // weld, a rope, a spring, a grab and a joint that breaks.
    const BodyId lift = dynamic(world, Shape::make_box({0.4f, 0.1f, 0.4f}), {-8.0f, 2.0f, 0.0f});
    JointDef slide = joint_at(world, JointType::kPrismatic, {}, lift, {-8.0f, 2.0f, 0.0f}, kY);
    slide.enable_limit = true;
    slide.lower = -1.5f;
    slide.upper = 1.0f;
    slide.enable_motor = true;
    slide.motor_speed = 0.7f;
    slide.max_motor_force = 2000.0f;
    joint(world, slide);
    const BodyId cargo =
        dynamic(world, Shape::make_box({0.15f, 0.15f, 0.15f}), {-8.0f, 2.25f, 0.0f});
    joint(world, joint_at(world, JointType::kWeld, lift, cargo, {-8.0f, 2.1f, 0.0f}));
    const BodyId flag = dynamic(world, Shape::make_box({0.03f, 0.3f, 0.03f}), {-8.0f, 2.7f, 0.0f});
    JointDef soft = joint_at(world, JointType::kWeld, cargo, flag, {-8.0f, 2.4f, 0.0f});
    soft.linear_hertz = 6.0f;
    soft.angular_hertz = 3.0f;
    soft.damping_ratio = 0.2f;
    joint(world, soft);
    const BodyId bob = dynamic(world, Shape::make_sphere(0.2f), {10.0f, 5.0f, 0.0f});
    JointDef rope = joint_between(world, JointType::kDistance, {}, bob, {9.0f, 7.0f, 0.0f},
                                  {10.0f, 5.0f, 0.0f});
    rope.min_length = 0.0f;
    joint(world, rope);
    const BodyId weight = dynamic(world, Shape::make_box({0.2f, 0.2f, 0.2f}), {12.0f, 5.0f, 0.0f});
    JointDef spring = joint_between(world, JointType::kSpring, bob, weight, {10.0f, 5.0f, 0.0f},
                                    {12.0f, 5.0f, 0.0f});
    spring.hertz = 2.5f;
    spring.damping_ratio = 0.1f;
    joint(world, spring);
    const BodyId grabbed = dynamic(world, Shape::make_sphere(0.3f), {-12.0f, 1.0f, 0.0f});
    JointDef grab = joint_at(world, JointType::kGrab, {}, grabbed, {-12.0f, 1.0f, 0.0f});
    grab.target = {-12.0f, 3.0f, 2.0f};
    grab.max_force = 3000.0f;
    joint(world, grab);
    const BodyId heavy = dynamic(world, Shape::make_box({0.5f, 0.5f, 0.5f}), {14.0f, 3.0f, 0.0f});
    JointDef weak = joint_at(world, JointType::kHinge, {}, heavy, {14.0f, 3.5f, 0.0f}, kZ);
    weak.break_impulse = 60.0f;
    joint(world, weak);
    // A car on four raycast wheels, and a character walking by.
    chassis = dynamic(world, Shape::make_box({0.9f, 0.25f, 2.0f}), {0.0f, 1.0f, 10.0f});
    for (int i = 0; i < 4; ++i) {
      WheelDef3D w;
      w.attachment = {i % 2 == 0 ? -0.8f : 0.8f, -0.2f, i < 2 ? 1.5f : -1.5f};
      w.rest_length_m = 0.5f;
      w.max_travel_m = 0.35f;
      w.radius_m = 0.35f;
      w.stiffness_npm = 0.25f * world.mass(chassis) * 40.0f;
      w.damping_nspm =
          2.0f * 0.4f * 1.2f * std::sqrt(w.stiffness_npm * 0.25f * world.mass(chassis));
      w.steers = i < 2;
      w.drives = true;
      wheels.push_back(w);
    }
    character.position = {-3.0f, 1.2f, 8.0f};
  }

  void drive(int t) {
    VehicleDef3D def;
    def.chassis = chassis;
    def.wheels = wheels;
    def.max_drive_force_n = 0.5f * world.mass(chassis) * 9.81f;
    VehicleControls3D controls;
    controls.throttle = t < 200 ? 0.8f : -0.3f;
    controls.brake = t > 250 ? 0.5f : 0.0f;
    controls.steer_rad = 0.3f * ((t / 40) % 2 == 0 ? 1.0f : -1.0f);
    WheelTelemetry3D telemetry[4];
    (void)update_vehicle(world, def, controls, telemetry);
    const float dt = world.config().tick_seconds;
    character.velocity.y -= 9.81f * dt;
    const Vec3 walk{1.5f, 0.0f, (t / 60) % 2 == 0 ? 1.0f : -1.0f};
    move_character(world, character, (walk + Vec3{0.0f, character.velocity.y, 0.0f}) * dt,
                   character_config);
  }

  uint64_t checksum() const {
    // The character is the game's state: fold it in.
    StateHasher hasher;
    world.hash(hasher);
    hasher.add_f32(character.position.x);
    hasher.add_f32(character.position.y);
    hasher.add_f32(character.position.z);
    hasher.add_f32(character.velocity.y);
    hasher.add_u8(character.grounded ? 1 : 0);
    return hasher.digest();
  }
};

}  // namespace

bool run_joints3d_scene(int ticks) {
  Scene scene;
  std::vector<uint8_t> bytes;
  std::vector<uint64_t> first_pass;
  for (int t = 0; t < ticks; ++t) {
    if (t % 30 == 10) {
      // Rollback: ten ticks, back, the same ten again.
      WorldState saved;
      scene.world.save(saved);
      const CharacterState3D character = scene.character;
      first_pass.clear();
      for (int i = 0; i < 10; ++i) {
        scene.drive(t + i);
        scene.world.step();
        first_pass.push_back(scene.checksum());
      }
      scene.world.restore(saved);
      scene.character = character;
      for (int i = 0; i < 10; ++i) {
        scene.drive(t + i);
        scene.world.step();
        if (scene.checksum() != first_pass[static_cast<size_t>(i)]) {
          std::printf("joints3d ROLLBACK-MISMATCH %d\n", t + i);
          return false;
        }
      }
      scene.world.restore(saved);
      scene.character = character;
    }
    if (t % 50 == 25) {
      // Reload from the world's own bytes into a fresh world.
      scene.world.serialize(bytes);
      World3D reloaded(scene.world.config(), scene.world.shared_geometry());
      if (!reloaded.deserialize(bytes).ok() || reloaded.checksum() != scene.world.checksum()) {
        std::printf("joints3d RELOAD-MISMATCH %d\n", t);
        return false;
      }
      scene.world = std::move(reloaded);
    }
    scene.drive(t);
    scene.world.step();
    std::printf("joints3d %d %016" PRIx64 " %zu\n", t, scene.checksum(),
                scene.world.broken_joints().size());
  }
  return true;
}

}  // namespace rwd::determinism
