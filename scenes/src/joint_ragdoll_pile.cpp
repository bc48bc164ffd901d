// SPDX-License-Identifier: MIT
// The ragdoll pile of rewind/scenes/joint_scenes.h (ragdoll_pile()). Its
// ragdolls are not described a second time here: one is made with
// create_ragdoll() in a scratch world and read back through the public
// state (its capsules, densities, damping and friction; its joints'
// anchors, axes, limits and friction), and each ragdoll of the pile is placed with
// ragdoll_rest_pose(). A change to the builder's defaults reaches this
// scene, so Bullet always gets the ragdoll Rewind's stability suite
// stacks. Where they go repeats tests/stability/ragdoll_pile3d.h.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "rewind/core/det_math.h"
#include "rewind/scenes/joint_scenes.h"
#include "rewind/sim/ragdoll3d.h"
#include "rewind/sim/world_state.h"

namespace rwd::scenes {
namespace {

constexpr uint32_t kParts = sim::kRagdollPartCount3D;
constexpr uint32_t kJoints = sim::kRagdollJointCount3D;

sim::Quat about(sim::Vec3 axis, float angle) {
  const float s = rwd::det_sin(0.5f * angle);
  return {axis.x * s, axis.y * s, axis.z * s, rwd::det_cos(0.5f * angle)};
}

bool close(float a, float b) {
  return std::fabs(a - b) <= 1e-4f * std::fmax(std::fabs(a), std::fabs(b));
}

/// One ragdoll as the builder makes it: its parts (shape and material;
/// the pose is each placement's) and its joints, a and b naming parts.
struct RagdollTemplate {
  std::array<JointSceneBody, kParts> parts{};
  std::array<JointSceneJoint, kJoints> joints{};
  std::string error;
};

RagdollTemplate read_ragdoll(const sim::RagdollSpec3D& spec) {
  RagdollTemplate t;
  sim::World3D world;
  const Result<sim::Ragdoll3D> made = sim::create_ragdoll(world, spec);
  if (!made.ok()) {
    t.error = "create_ragdoll: " + made.status().message();
    return t;
  }
  const sim::WorldState& state = world.state();
  for (uint32_t p = 0; p < kParts; ++p) {
    const sim::BodyId id = made->parts[p];
    const sim::BodyInfo& info = state.infos[id.index];
    JointSceneBody& body = t.parts[p];
    body.shape = JointSceneShape::kCapsule;
    body.half = {info.shape.radius, info.shape.radius, info.shape.radius};
    body.half_height = info.shape.half_height;
    body.density = info.density;
    body.angular_damping = info.angular_damping;
    body.friction = info.material.friction;
    // What the description cannot carry, and what it computes itself,
    // must agree with the world, or Bullet would get another ragdoll.
    if (info.shape.type != sim::ShapeType::kCapsule || info.linear_damping != 0.0f ||
        info.material.restitution != 0.0f) {
      t.error = "ragdoll part " +
                std::string(sim::ragdoll_part_name(static_cast<sim::RagdollPart3D>(p))) +
                ": not a capsule, or linear damping or restitution the scene does not carry";
      return t;
    }
    const sim::BodyMass& mass = state.masses[id.index];
    const sim::Vec3 inertia = body.inertia();
    if (!close(body.mass_kg() * mass.inv_mass, 1.0f) ||
        !close(inertia.x * mass.inv_inertia_local.x, 1.0f) ||
        !close(inertia.y * mass.inv_inertia_local.y, 1.0f) ||
        !close(inertia.z * mass.inv_inertia_local.z, 1.0f)) {
      t.error = "ragdoll part " +
                std::string(sim::ragdoll_part_name(static_cast<sim::RagdollPart3D>(p))) +
                ": the description's capsule mass or inertia differs from Rewind's";
      return t;
    }
  }
  for (uint32_t j = 0; j < kJoints; ++j) {
    const auto which = static_cast<sim::RagdollJoint3D>(j);
    const sim::JointRecord& record = state.joints[made->joints[j].index];
    JointSceneJoint& joint = t.joints[j];
    joint.type =
        record.type == sim::JointType::kHinge ? JointSceneType::kHinge : JointSceneType::kBall;
    joint.a = static_cast<int>(sim::ragdoll_joint_parent(which));
    joint.b = static_cast<int>(sim::ragdoll_joint_child(which));
    joint.local_a = made->anchor_parent[j];
    joint.local_b = made->anchor_child[j];
    // A capsule's mass frame is its authored frame, so the record's joint
    // frames are in the parts' own frames; their x axis is the hinge or
    // twist axis (and, on the parent of a ball joint, the cone's centre).
    // Read back this way an axis can differ from the builder's by a
    // rounding (the waist's, on the turned pelvis, does): the pile is
    // chaotic, so Rewind does not step it bit for bit as the stability
    // suite does, only alike.
    joint.axis_a = sim::rotate(record.frame_a, {1.0f, 0.0f, 0.0f});
    joint.axis_b = sim::rotate(record.frame_b, {1.0f, 0.0f, 0.0f});
    joint.limited = (record.flags & sim::kJointLimit) != 0;
    joint.cone_angle = record.cone_angle;
    joint.twist_lower = record.twist_lower;
    joint.twist_upper = record.twist_upper;
    joint.lower = record.lower;
    joint.upper = record.upper;
    // The builder's joint friction: a motor held at zero relative speed.
    if ((record.flags & sim::kJointMotor) != 0) joint.friction_torque_nm = record.max_motor;
    if (record.type != sim::JointType::kHinge && record.type != sim::JointType::kBall) {
      t.error = std::string("ragdoll joint ") + sim::ragdoll_joint_name(which) +
                ": neither a ball joint nor a hinge";
      return t;
    }
  }
  return t;
}

}  // namespace

JointScene ragdoll_pile(int count) {
  JointScene s;
  const sim::RagdollSpec3D defaults;
  const RagdollTemplate ragdoll = read_ragdoll(defaults);
  if (!ragdoll.error.empty() || count <= 0) return s;
  s.name = "ragdoll_pile";
  s.size = count;
  s.ticks = 480;

  // The floor first, as the stability suite makes it (its material the
  // default one, friction 0.6).
  JointSceneBody floor;
  floor.fixed = true;
  floor.half = {30.0f, 0.5f, 30.0f};
  floor.position = {0.0f, -0.5f, 0.0f};
  s.bodies.push_back(floor);

  const sim::Quat lying = about({1.0f, 0.0f, 0.0f}, -0.5f * rwd::kPi);  // face up, head to +z
  std::array<sim::RagdollPartPose3D, kParts> pose;
  for (int i = 0; i < count; ++i) {
    const auto layer = static_cast<uint32_t>(i / 5);
    const auto slot = static_cast<uint32_t>(i % 5);
    const float across = (static_cast<float>(slot) - 2.0f) * 0.6f;
    const float yaw = (layer % 2 == 0 ? 0.0f : 0.5f * rwd::kPi) +
                      0.25f * rwd::det_sin(1.7f * static_cast<float>(i) + 0.3f);
    sim::RagdollSpec3D spec = defaults;
    spec.rotation = about({0.0f, 1.0f, 0.0f}, yaw) * lying;
    const float along = 0.3f * rwd::det_cos(2.3f * static_cast<float>(i));
    const float height = 0.4f + 0.45f * static_cast<float>(layer);
    spec.position =
        layer % 2 == 0 ? sim::Vec3{across, height, along} : sim::Vec3{along, height, across};
    if (!sim::ragdoll_rest_pose(spec, pose).ok()) return {};
    const int base = static_cast<int>(s.bodies.size());
    for (uint32_t p = 0; p < kParts; ++p) {
      JointSceneBody part = ragdoll.parts[p];
      part.position = pose[p].position;
      part.rotation = pose[p].rotation;
      part.collision_group = i;
      s.bodies.push_back(part);
    }
    for (JointSceneJoint joint : ragdoll.joints) {
      joint.a += base;
      joint.b += base;
      s.joints.push_back(joint);
    }
  }
  return s;
}

}  // namespace rwd::scenes
