// SPDX-License-Identifier: MIT
// Rotation locks, torques and forces at a point: a body locked about every
// axis never turns, an upright character capsule stays upright when struck,
// a torque and an off-centre force change the velocities by the analytic
// amounts (no gravity, one step), locked axes take no torque, bad arguments
// change nothing, snapshots keep locks and pending torques, and a kinematic
// platform carries what rests on it by friction.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

WorldConfig no_gravity() {
  WorldConfig c;
  c.gravity = {};
  c.enable_sleep = false;
  return c;
}

TEST(RotationLock, ALockedBoxLandsOnItsCornerWithoutTurning) {
  WorldConfig c;
  c.enable_sleep = false;
  World3D world(c);
  test::add_ground(world);
  BodyDef def;
  def.position = {0.0f, 2.0f, 0.0f};
  def.rotation = Quat{0.0f, 0.0f, det_sin(0.25f), det_cos(0.25f)};  // 0.5 rad about z
  def.angular_velocity = {1.0f, 2.0f, 3.0f};                        // cleared by the lock
  def.lock_rotation = kLockRotationAll;
  const BodyId id = *world.create_body(def);
  EXPECT_EQ(world.angular_velocity(id), Vec3{});
  const Quat start = world.rotation(id);
  test::step_seconds(world, 2.0f);
  const Quat end = world.rotation(id);
  EXPECT_NEAR(end.z, start.z, 1e-6f);
  EXPECT_NEAR(end.w, start.w, 1e-6f);
  EXPECT_EQ(world.angular_velocity(id), Vec3{});
  // It came down and stands on its lowest corner: the 1 m box turned 0.5
  // rad reaches 0.5 (cos 0.5 + sin 0.5) below its centre.
  const float reach = 0.5f * (std::cos(0.5f) + std::sin(0.5f));
  EXPECT_NEAR(world.position(id).y, reach, c.linear_slop_m + 0.001f);
}

TEST(RotationLock, AStruckCharacterCapsuleStaysUpright) {
  WorldConfig c;
  c.enable_sleep = false;
  World3D world(c);
  test::add_ground(world);
  BodyDef body;
  body.shape = Shape::make_capsule(0.3f, 0.6f);
  body.position = {0.0f, 0.9f, 0.0f};
  body.lock_rotation = kLockRotationX | kLockRotationZ;
  const BodyId capsule = *world.create_body(body);
  BodyDef ball;
  ball.shape = Shape::make_sphere(0.2f);
  ball.position = {-3.0f, 1.3f, 0.1f};
  ball.linear_velocity = {8.0f, 0.0f, 0.0f};
  (void)*world.create_body(ball);
  float lean = 0.0f;
  for (int i = 0; i < 180; ++i) {
    world.step();
    // The capsule's axis (local y) in the world.
    const Vec3 axis = rotate(world.rotation(capsule), Vec3{0.0f, 1.0f, 0.0f});
    lean = std::fmax(lean, std::sqrt(axis.x * axis.x + axis.z * axis.z));
    const Vec3 w = world.angular_velocity(capsule);
    ASSERT_EQ(w.x, 0.0f);
    ASSERT_EQ(w.z, 0.0f);
  }
  EXPECT_LT(lean, 1e-5f);
  EXPECT_GT(world.position(capsule).x, 0.005f);  // the blow moved it (friction stops it soon)
  EXPECT_NEAR(world.position(capsule).y, 0.9f, c.linear_slop_m + 0.001f);
}

TEST(Torque, TurnsTheBodyByTheAnalyticAmount) {
  World3D world(no_gravity());
  BodyDef def;
  def.shape = Shape::make_box({0.5f, 0.25f, 1.0f});
  def.angular_damping = 0.0f;
  const BodyId id = *world.create_body(def);
  // I_z = m/3 (hx^2 + hy^2), m = 1000 * 1 * 0.5 * 2 = 1000 kg.
  const float m = 1000.0f;
  const float i_z = m / 3.0f * (0.25f + 0.0625f);
  ASSERT_TRUE(world.apply_torque(id, {0.0f, 0.0f, 50.0f}).ok());
  world.step();
  const float dt = world.config().tick_seconds;
  EXPECT_NEAR(world.angular_velocity(id).z, 50.0f / i_z * dt, 1e-6f);
  EXPECT_NEAR(world.angular_velocity(id).x, 0.0f, 1e-7f);
  // The torque lasts one step only.
  const float w1 = world.angular_velocity(id).z;
  world.step();
  EXPECT_NEAR(world.angular_velocity(id).z, w1, 1e-6f);
  // Locked about z, the same torque does nothing.
  ASSERT_TRUE(world.set_rotation_lock(id, kLockRotationZ).ok());
  EXPECT_EQ(world.angular_velocity(id).z, 0.0f);
  ASSERT_TRUE(world.apply_torque(id, {0.0f, 0.0f, 50.0f}).ok());
  world.step();
  EXPECT_EQ(world.angular_velocity(id).z, 0.0f);
}

TEST(ForceAtPoint, PushesAndTurns) {
  World3D world(no_gravity());
  BodyDef def;
  def.shape = Shape::make_sphere(0.5f);
  def.angular_damping = 0.0f;
  const BodyId id = *world.create_body(def);
  const float m = world.mass(id);
  const float i = 0.4f * m * 0.25f;
  // 100 N along x at the top of the sphere: F/m along x, and (r x F)/I
  // about -z.
  ASSERT_TRUE(world.apply_force_at(id, {100.0f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f}).ok());
  world.step();
  const float dt = world.config().tick_seconds;
  EXPECT_NEAR(world.linear_velocity(id).x, 100.0f / m * dt, 1e-6f);
  EXPECT_NEAR(world.angular_velocity(id).z, -0.5f * 100.0f / i * dt, 1e-5f);
}

TEST(LocksAndTorques, BadArgumentsChangeNothing) {
  World3D world(no_gravity());
  test::add_ground(world);
  BodyDef def;
  def.position = {0.0f, 3.0f, 0.0f};
  def.lock_rotation = 8;
  EXPECT_FALSE(world.create_body(def).ok());
  def.lock_rotation = 0;
  const BodyId id = *world.create_body(def);
  const uint64_t before = world.checksum();
  EXPECT_FALSE(world.set_rotation_lock(id, 9).ok());
  EXPECT_FALSE(world.apply_torque(id, {std::nanf(""), 0.0f, 0.0f}).ok());
  EXPECT_FALSE(world.apply_torque(id, {2e12f, 0.0f, 0.0f}).ok());
  EXPECT_FALSE(world.apply_force_at(id, {1.0f, 0.0f, 0.0f}, {INFINITY, 0.0f, 0.0f}).ok());
  // A force whose torque about the centre would be too large is refused
  // whole: neither the force nor the torque is kept.
  EXPECT_FALSE(world.apply_force_at(id, {0.0f, 0.0f, 9e11f}, {1e4f, 3.0f, 0.0f}).ok());
  EXPECT_FALSE(world.apply_torque(BodyId{0, 1}, {1.0f, 0.0f, 0.0f}).ok());  // static ground
  EXPECT_FALSE(world.apply_torque(BodyId{7, 1}, {1.0f, 0.0f, 0.0f}).ok());  // no such body
  EXPECT_EQ(world.checksum(), before);
}

TEST(LocksAndTorques, SnapshotsKeepLocksAndPendingTorques) {
  World3D world(no_gravity());
  BodyDef def;
  def.lock_rotation = kLockRotationY;
  const BodyId id = *world.create_body(def);
  ASSERT_TRUE(world.apply_torque(id, {3.0f, 4.0f, 5.0f}).ok());
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  World3D loaded;
  ASSERT_TRUE(loaded.deserialize(bytes).ok());
  EXPECT_EQ(loaded.checksum(), world.checksum());
  EXPECT_EQ(loaded.state().infos[id.index].lock_rotation, kLockRotationY);
  world.step();
  loaded.step();
  EXPECT_EQ(loaded.checksum(), world.checksum());
  EXPECT_EQ(world.angular_velocity(id).y, 0.0f);
  EXPECT_GT(world.angular_velocity(id).x, 0.0f);
  // A stored body turning about its locked axis is refused.
  WorldState bad = world.state();
  bad.sims[id.index].angular_velocity.y = 1.0f;
  World3D writer;
  writer.restore(bad);
  writer.serialize(bytes);
  EXPECT_FALSE(loaded.deserialize(bytes).ok());
}

TEST(KinematicPlatform, CarriesWhatRestsOnItByFriction) {
  // A kinematic platform moving at 1 m/s carries a box resting on it: after
  // the box catches up (friction, mu 0.6) it moves with the platform.
  WorldConfig c;
  c.enable_sleep = false;
  World3D world(c);
  BodyDef platform;
  platform.kind = BodyKind::kKinematic;
  platform.shape = Shape::make_box({3.0f, 0.25f, 3.0f});
  platform.position = {0.0f, 0.0f, 0.0f};
  platform.linear_velocity = {1.0f, 0.0f, 0.0f};
  const BodyId deck = *world.create_body(platform);
  const BodyId box = test::add_box(world, {0.0f, 0.75f, 0.0f});
  test::step_seconds(world, 1.0f);
  EXPECT_NEAR(world.linear_velocity(box).x, 1.0f, 0.01f);
  // It rides along: the platform moved 1 m, the box nearly as far.
  EXPECT_NEAR(world.position(deck).x, 1.0f, 1e-4f);
  EXPECT_GT(world.position(box).x, 0.9f);
  EXPECT_NEAR(world.position(box).y, 0.75f, c.linear_slop_m + 0.001f);
}

}  // namespace
}  // namespace rwd::sim
