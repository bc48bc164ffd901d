// SPDX-License-Identifier: MIT
// The 3D joints as state: a scene with every joint type, limits, motors,
// springs and a break restored and re-stepped bit for bit, round-tripped
// through the snapshot bytes every tick, corrupt joint bytes refused, and
// bad definitions refused naming the field with the world unchanged.
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "joint_test_helpers.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using namespace joint_test;

// A scene with every joint type, limits, motors, springs and a break.
struct JointScene {
  World3D world;
  std::vector<JointId> joints;
  explicit JointScene(const WorldConfig& config = {}) : world(config) {
    test::add_ground(world);
    const BodyId post = add_static_box(world, {0.0f, 6.0f, 0.0f});
    BodyId prev = post;
    // A chain of ball joints with cone limits and a spring at its root.
    for (int i = 0; i < 5; ++i) {
      const float y = 5.5f - 0.5f * static_cast<float>(i);
      const BodyId link = add_capsule(world, {0.0f, y, 0.0f}, 0.08f, 0.15f);
      JointDef def = joint_at(world, JointType::kBall, prev, link, {0.0f, y + 0.25f, 0.0f}, -kY);
      def.enable_limit = i > 0;
      def.cone_angle = 0.6f;
      def.twist_lower = -0.3f;
      def.twist_upper = 0.3f;
      def.enable_spring = i == 0;
      def.hertz = 2.0f;
      joints.push_back(make(world, def));
      prev = link;
    }
    EXPECT_TRUE(world.set_linear_velocity(prev, {3.0f, 0.0f, 1.0f}).ok());
    // A motorized hinge wheel with limits off, a limited hinge flap.
    const BodyId wheel = add_capsule(world, {3.0f, 2.0f, 0.0f}, 0.3f, 0.1f);
    JointDef motor = joint_at(world, JointType::kHinge, {}, wheel, {3.0f, 2.0f, 0.0f}, kZ);
    motor.enable_motor = true;
    motor.motor_speed = 3.0f;
    motor.max_motor_torque = 20.0f;
    joints.push_back(make(world, motor));
    const BodyId flap = test::add_box(world, {4.5f, 2.0f, 0.0f}, {0.5f, 0.05f, 0.3f});
    JointDef hinge = joint_at(world, JointType::kHinge, wheel, flap, {4.0f, 2.0f, 0.0f}, kZ);
    hinge.enable_limit = true;
    hinge.lower = -0.5f;
    hinge.upper = 0.5f;
    hinge.enable_spring = true;
    hinge.hertz = 1.0f;
    joints.push_back(make(world, hinge));
    // A prismatic elevator with a spring, a weld, a soft weld.
    const BodyId car = test::add_box(world, {-3.0f, 3.0f, 0.0f}, {0.3f, 0.1f, 0.3f});
    JointDef slide = joint_at(world, JointType::kPrismatic, {}, car, {-3.0f, 3.0f, 0.0f}, kY);
    slide.enable_limit = true;
    slide.lower = -2.0f;
    slide.upper = 0.5f;
    slide.enable_spring = true;
    slide.hertz = 1.5f;
    joints.push_back(make(world, slide));
    const BodyId cargo = test::add_box(world, {-3.0f, 3.3f, 0.0f}, {0.2f, 0.2f, 0.2f});
    joints.push_back(
        make(world, joint_at(world, JointType::kWeld, car, cargo, {-3.0f, 3.1f, 0.0f})));
    const BodyId flag = test::add_box(world, {-3.0f, 3.8f, 0.0f}, {0.05f, 0.3f, 0.05f});
    JointDef soft = joint_at(world, JointType::kWeld, cargo, flag, {-3.0f, 3.5f, 0.0f});
    soft.linear_hertz = 5.0f;
    soft.angular_hertz = 2.0f;
    soft.damping_ratio = 0.3f;
    joints.push_back(make(world, soft));
    // A rope and a spring pendulum, a grab, and a joint that breaks.
    const BodyId bob = test::add_sphere(world, {6.0f, 4.0f, 0.0f}, 0.2f);
    JointDef rope =
        joint_between(world, JointType::kDistance, {}, bob, {5.0f, 6.0f, 0.0f}, {6.0f, 4.0f, 0.0f});
    rope.min_length = 0.0f;
    joints.push_back(make(world, rope));
    const BodyId weight = test::add_box(world, {8.0f, 4.0f, 0.0f}, {0.2f, 0.2f, 0.2f});
    JointDef spring = joint_between(world, JointType::kSpring, bob, weight, {6.0f, 4.0f, 0.0f},
                                    {8.0f, 4.0f, 0.0f});
    spring.hertz = 3.0f;
    spring.damping_ratio = 0.1f;
    joints.push_back(make(world, spring));
    const BodyId grabbed = test::add_sphere(world, {-6.0f, 1.0f, 0.0f}, 0.3f);
    JointDef grab = joint_at(world, JointType::kGrab, {}, grabbed, {-6.0f, 1.0f, 0.0f});
    grab.target = {-6.0f, 3.0f, 2.0f};
    grab.max_force = 2000.0f;
    joints.push_back(make(world, grab));
    const BodyId heavy = test::add_box(world, {10.0f, 3.0f, 0.0f});
    JointDef weak = joint_at(world, JointType::kBall, {}, heavy, {10.0f, 3.5f, 0.0f});
    weak.break_impulse = 5.0f;  // far below its 1000 kg weight
    joints.push_back(make(world, weak));
    // A ring of bare ball joints hung from the world (point joints, solved
    // in lane batches).
    const Vec3 ring[4] = {
        {12.0f, 4.0f, 0.0f}, {12.6f, 4.0f, 0.0f}, {12.6f, 4.0f, 0.6f}, {12.0f, 4.0f, 0.6f}};
    BodyId beads[4];
    for (int i = 0; i < 4; ++i) beads[i] = test::add_sphere(world, ring[i], 0.15f);
    for (int i = 0; i < 4; ++i) {
      joints.push_back(make(world, joint_at(world, JointType::kBall, beads[i], beads[(i + 1) % 4],
                                            (ring[i] + ring[(i + 1) % 4]) * 0.5f)));
    }
    joints.push_back(make(
        world, joint_at(world, JointType::kBall, {}, beads[0], ring[0] + Vec3{0.0f, 0.3f, 0.0f})));
  }
};

TEST(Joints, RestoreAndReStepIsBitForBit) {
  JointScene scene;
  World3D& world = scene.world;
  std::vector<uint64_t> reference;
  WorldState at_30;
  for (int i = 0; i < 120; ++i) {
    if (i == 30) world.save(at_30);
    world.step();
    reference.push_back(world.checksum());
  }
  world.restore(at_30);
  for (int i = 30; i < 120; ++i) {
    world.step();
    ASSERT_EQ(world.checksum(), reference[i]) << "tick " << i;
  }
  // A second world built the same way gives the same bits.
  JointScene twin;
  for (int i = 0; i < 120; ++i) {
    twin.world.step();
    ASSERT_EQ(twin.world.checksum(), reference[i]) << "tick " << i;
  }
}

TEST(Joints, EveryTickRoundTripsThroughTheSnapshotBytes) {
  JointScene scene;
  World3D& world = scene.world;
  JointScene reader;
  std::vector<uint8_t> bytes;
  bool broke = false;
  for (int i = 0; i < 150; ++i) {
    world.step();
    broke |= !world.broken_joints().empty();
    world.serialize(bytes);
    ASSERT_TRUE(reader.world.deserialize(bytes).ok()) << "tick " << i;
    ASSERT_EQ(reader.world.checksum(), world.checksum()) << "tick " << i;
  }
  EXPECT_TRUE(broke);  // the weak joint broke within the run
  // Loaded, it steps on exactly as the original.
  for (int i = 0; i < 30; ++i) {
    world.step();
    reader.world.step();
    ASSERT_EQ(reader.world.checksum(), world.checksum());
  }
  // The dump names the joint fields; the checksum sees an impulse bit.
  std::string text;
  world.dump_state(text);
  EXPECT_NE(text.find("joint[0].type = "), std::string::npos);
  EXPECT_NE(text.find("joint[0].linear_impulse = "), std::string::npos);
  WorldState s = world.state();
  s.joints[1].linear_impulse.x = std::nextafter(s.joints[1].linear_impulse.x, 1e9f);
  World3D changed;
  changed.restore(s);
  EXPECT_NE(changed.checksum(), world.checksum());
}

TEST(Joints, CorruptJointBytesAreRefusedAndChangeNothing) {
  JointScene scene;
  World3D& world = scene.world;
  for (int i = 0; i < 10; ++i) world.step();
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  const uint64_t before = world.checksum();
  // Every truncation is refused.
  for (size_t cut = bytes.size() - 1; cut + 400 > bytes.size(); --cut) {
    const std::span<const uint8_t> part(bytes.data(), cut);
    ASSERT_FALSE(world.deserialize(part).ok()) << cut;
  }
  // A joint naming a body that is not there.
  WorldState s = world.state();
  s.joints[0].index_b = 999;
  World3D bad;
  bad.restore(s);
  std::vector<uint8_t> corrupt;
  bad.serialize(corrupt);
  const Status status = world.deserialize(corrupt);
  EXPECT_EQ(status.code(), ErrorCode::kCorrupt);
  EXPECT_NE(status.message().find("joint 0"), std::string::npos) << status.message();
  EXPECT_EQ(world.checksum(), before);
}

TEST(Joints, BadDefinitionsAreRefusedNamingTheField) {
  World3D world;
  const BodyId ground = test::add_ground(world);
  const BodyId a = test::add_box(world, {0.0f, 2.0f, 0.0f});
  const BodyId b = test::add_box(world, {2.0f, 2.0f, 0.0f});
  const BodyId gone = test::add_box(world, {4.0f, 2.0f, 0.0f});
  ASSERT_TRUE(world.destroy_body(gone).ok());
  const uint64_t before = world.checksum();
  const JointDef good = joint_at(world, JointType::kHinge, a, b, {1.0f, 2.0f, 0.0f}, kZ);
  auto refused = [&](JointDef def, const char* field) {
    auto r = world.create_joint(def);
    ASSERT_FALSE(r.ok()) << field;
    EXPECT_NE(r.status().message().find(field), std::string::npos)
        << field << ": " << r.status().message();
    EXPECT_EQ(world.checksum(), before) << field;
    EXPECT_EQ(world.joint_count(), 0u);
  };
  JointDef d = good;
  d.body_b = gone;
  refused(d, "body_b");
  d = good;
  d.body_a = gone;
  refused(d, "body_a");
  d = good;
  d.body_b = a;
  refused(d, "body_b");
  d = good;
  d.body_a = ground;
  d.body_b = ground;
  refused(d, "body_b");
  d = good;
  d.axis_a = {0.0f, 0.0f, 0.0f};
  refused(d, "axis_a");
  d = good;
  d.axis_b = {NAN, 0.0f, 1.0f};
  refused(d, "axis_b");
  d = good;
  d.anchor_a = {INFINITY, 0.0f, 0.0f};
  refused(d, "anchor_a");
  d = good;
  d.enable_limit = true;
  d.lower = 0.5f;
  d.upper = -0.5f;
  refused(d, "lower");
  d = good;
  d.enable_limit = true;
  d.lower = -4.0f;
  refused(d, "lower");
  d = good;
  d.type = JointType::kBall;
  d.enable_limit = true;
  d.cone_angle = 4.0f;
  refused(d, "cone_angle");
  d.cone_angle = 0.0f;
  refused(d, "cone_angle");
  d = good;
  d.type = JointType::kDistance;
  d.min_length = 2.0f;
  d.max_length = 1.0f;
  refused(d, "min_length");
  d = good;
  d.enable_motor = true;
  d.max_motor_torque = -1.0f;
  refused(d, "max_motor_torque");
  d = good;
  d.type = JointType::kSpring;
  d.hertz = 0.0f;
  refused(d, "hertz");
  d = good;
  d.break_impulse = -1.0f;
  refused(d, "break_impulse");
  d = good;
  d.type = JointType::kGrab;
  refused(d, "body_a");
  d.body_a = {};
  d.max_force = 0.0f;
  refused(d, "max_force");
  d = good;
  d.type = static_cast<JointType>(42);
  refused(d, "type");
  // The good one is accepted.
  EXPECT_TRUE(world.create_joint(good).ok());
}

}  // namespace
}  // namespace rwd::sim
