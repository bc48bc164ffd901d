// SPDX-License-Identifier: MIT
// The ragdoll's joint friction (RagdollSpec3D::joint_friction): each
// joint's motor holds at zero relative speed with the spec's share of the
// torque its hanging parts weigh held out level; a limb held out level
// falls when that share is below one and stays when friction outweighs
// it.
#include <cmath>

#include <gtest/gtest.h>

#include "rewind/sim/ragdoll3d.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

constexpr float kStandardGravity = 9.81f;

// The elbow in the world and the forearm's hanging torque held out level.
float forearm_torque(const World3D& world, const Ragdoll3D& r) {
  const BodyId upper = r.part(RagdollPart3D::kUpperArmL);
  const BodyId fore = r.part(RagdollPart3D::kForearmL);
  const uint32_t elbow = static_cast<uint32_t>(RagdollJoint3D::kElbowL);
  const Vec3 joint = world.position(upper) + rotate(world.rotation(upper), r.anchor_parent[elbow]);
  return world.mass(fore) * kStandardGravity * length(world.position(fore) - joint);
}

TEST(Ragdoll3DFriction, EachJointResistsWithItsShareOfTheHangingTorque) {
  WorldConfig config;
  config.gravity = {};
  World3D world(config);
  RagdollSpec3D spec;
  spec.position = {0.0f, 2.0f, 0.0f};
  spec.joint_friction = 0.4f;
  auto r = create_ragdoll(world, spec);
  ASSERT_TRUE(r.ok()) << r.status().message();
  const JointRecord& elbow = world.state().joints[r->joint(RagdollJoint3D::kElbowL).index];
  EXPECT_NE(elbow.flags & kJointMotor, 0u);
  EXPECT_EQ(elbow.motor_speed, 0.0f);
  EXPECT_NEAR(elbow.max_motor, 0.4f * forearm_torque(world, *r), 1e-3f * elbow.max_motor);
  // The waist carries the most (everything above the pelvis), a forearm
  // the least.
  const JointRecord& waist = world.state().joints[r->joint(RagdollJoint3D::kWaist).index];
  EXPECT_GT(waist.max_motor, 10.0f * elbow.max_motor);

  spec.joint_friction = 0.0f;
  spec.position = {3.0f, 2.0f, 0.0f};
  auto free = create_ragdoll(world, spec);
  ASSERT_TRUE(free.ok());
  for (const JointId j : free->joints) {
    EXPECT_EQ(world.state().joints[j.index].flags & kJointMotor, 0u);
  }
}

// A ragdoll face down with its arms reaching out level toward its feet,
// its trunk and left upper arm welded to the world: gravity folds the left elbow
// forward against its friction. Under gravity whose torque on the forearm
// is more than the friction's share it falls; under a gravity whose
// torque is less (0.15 of the standard against 0.25) it stays level.
TEST(Ragdoll3DFriction, AForearmHeldOutLevelFallsOnlyWhenItsWeightOutweighsTheFriction) {
  for (const float g : {kStandardGravity, 0.15f * kStandardGravity}) {
    WorldConfig config;
    config.gravity = {0.0f, -g, 0.0f};
    World3D world(config);
    RagdollSpec3D spec;
    spec.joint_friction = 0.25f;
    const float half_turn = 0.25f * 3.14159265f;  // a quarter turn about x: face down
    spec.rotation = {std::sin(half_turn), 0.0f, 0.0f, std::cos(half_turn)};
    spec.position = {0.0f, 5.0f, 0.0f};
    auto r = create_ragdoll(world, spec);
    ASSERT_TRUE(r.ok()) << r.status().message();
    // The trunk and the upper arm held where they are, so what dangles
    // from the trunk does not swing the arm.
    for (const RagdollPart3D held : {RagdollPart3D::kSpine, RagdollPart3D::kUpperArmL}) {
      JointDef weld;
      weld.type = JointType::kWeld;
      weld.body_b = r->part(held);
      weld.anchor_a = world.position(weld.body_b);
      weld.anchor_b = {0.0f, 0.0f, 0.0f};
      ASSERT_TRUE(world.create_joint(weld).ok());
    }
    const JointId elbow = r->joint(RagdollJoint3D::kElbowL);
    for (int t = 0; t < 60; ++t) world.step();
    const float folded = world.joint_position(elbow);
    if (g == kStandardGravity) {
      EXPECT_GT(folded, 0.5f) << "the forearm did not fall (elbow at " << folded << " rad)";
    } else {
      EXPECT_LT(std::fabs(folded), 0.03f) << "the forearm moved (elbow at " << folded << " rad)";
    }
  }
}

}  // namespace
}  // namespace rwd::sim
