// SPDX-License-Identifier: MIT
// The ragdoll builder refuses a bad spec (ragdoll3d.h) naming the field,
// and a world without room for the figure, leaving the world unchanged.
#include <array>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "rewind/sim/ragdoll3d.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

constexpr uint32_t kParts = kRagdollPartCount3D;

TEST(Ragdoll3D, BadSpecsAreRefusedNamingTheFieldWithTheWorldUnchanged) {
  WorldConfig config;
  config.max_bodies = 30;
  config.bounds_lower = {-20.0f, -20.0f, -20.0f};
  config.bounds_upper = {20.0f, 20.0f, 20.0f};
  World3D world(config);
  test::add_ground(world);
  RagdollSpec3D good;
  good.position = {0.0f, 2.0f, 0.0f};
  ASSERT_TRUE(create_ragdoll(world, good).ok());  // 12 bodies
  world.step();
  const uint64_t before = world.checksum();
  const uint32_t bodies = world.body_count();
  const uint32_t joints = world.joint_count();
  auto refused = [&](const RagdollSpec3D& spec, const char* field) {
    auto r = create_ragdoll(world, spec);
    ASSERT_FALSE(r.ok()) << field;
    EXPECT_NE(r.status().message().find(field), std::string::npos)
        << field << ": " << r.status().message();
    EXPECT_EQ(world.checksum(), before) << field;
    EXPECT_EQ(world.body_count(), bodies) << field;
    EXPECT_EQ(world.joint_count(), joints) << field;
    std::array<RagdollPartPose3D, kParts> out{};
    if (std::string(field) != "position" && std::string(field) != "max_bodies") {
      EXPECT_FALSE(ragdoll_rest_pose(spec, out).ok()) << field;
    }
  };
  RagdollSpec3D s = good;
  s.height_m = NAN;
  refused(s, "height_m");
  s.height_m = 0.05f;
  refused(s, "height_m");
  s = good;
  s.mass_kg = -70.0f;
  refused(s, "mass_kg");
  s.mass_kg = INFINITY;
  refused(s, "mass_kg");
  s = good;
  s.bones[3].radius_m = -0.1f;
  refused(s, "bones[upper_arm_l].radius_m");
  s = good;
  s.bones[9].length_m = NAN;
  refused(s, "bones[shin_l].length_m");
  s = good;
  s.bones[2].radius_m = 0.2f;  // the head: 0.234 m long, 0.4 m across
  refused(s, "bones[head].length_m");
  s = good;
  s.position = {0.0f, 19.5f, 0.0f};  // the head would stick out of the bounds
  refused(s, "position");
  s.position = {NAN, 2.0f, 0.0f};
  refused(s, "position");
  s = good;
  s.rotation = Quat{0.0f, 0.0f, 0.0f, 0.0f};
  refused(s, "rotation");
  s = good;
  s.self_layer = 0;
  refused(s, "self_layer");
  s = good;
  s.friction = 11.0f;
  refused(s, "friction");
  s = good;
  s.restitution = -0.5f;
  refused(s, "restitution");
  s = good;
  s.angular_damping = NAN;
  refused(s, "angular_damping");
  s = good;
  s.linear_damping = 1e3f;
  refused(s, "linear_damping");
  s = good;
  s.joint_friction = 1.5f;
  refused(s, "joint_friction");
  s.joint_friction = NAN;
  refused(s, "joint_friction");
  // 12 bodies in a world of 30: one more ragdoll fits, a second does not.
  s = good;
  s.position = {3.0f, 2.0f, 0.0f};
  ASSERT_TRUE(create_ragdoll(world, s).ok());
  const uint64_t full = world.checksum();
  s.position = {-3.0f, 2.0f, 0.0f};
  auto r = create_ragdoll(world, s);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), ErrorCode::kCapacity);
  EXPECT_NE(r.status().message().find("max_bodies"), std::string::npos);
  EXPECT_EQ(world.checksum(), full);
  EXPECT_EQ(world.body_count(), 23u);
}

}  // namespace
}  // namespace rwd::sim
