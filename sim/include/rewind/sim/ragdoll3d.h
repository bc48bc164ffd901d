// SPDX-License-Identifier: MIT
#pragma once
// A humanoid ragdoll for the 3D lane: eleven dynamic capsules tied by ten
// joints, built through World3D's public API only (create_body,
// create_joint, set_transform, ...). The builder keeps nothing: the game
// owns the Ragdoll3D it returns (ids and joint anchors, plain data), and
// the world holds everything that simulates, so save/restore, snapshots
// and checksums carry ragdolls like any other bodies and joints.
//
// The figure's frame: y up, facing +z, its left hand on +x. The rest pose
// stands upright with the arms hanging at the sides; every joint's limits
// are measured from it. Units: metres, kilograms, radians, seconds.
//
//   part         capsule along    joined to    by
//   pelvis       x (hip to hip)   -            (root)
//   spine        y (up)           pelvis       waist: ball, cone-twist
//   head         y (up)           spine        neck: ball, cone-twist
//   upper_arm_*  -y (down)        spine        shoulder_*: ball, cone-twist
//   forearm_*    -y (down)        upper_arm_*  elbow_*: hinge, one way
//   thigh_*      -y (down)        pelvis       hip_*: ball, cone-twist
//   shin_*       -y (down)        thigh_*      knee_*: hinge, one way
//
// Limits (twist about the child bone, relative to the rest pose; the cone
// about a rest direction fixed in the parent; see docs/lane-3d.md, Ragdolls):
//   waist      cone 35 deg about up tilted 11 deg forward (bends 46 deg
//              forward, 24 back, 33 sideways), twist +-30 deg
//   neck       cone 40 deg about up tilted 8.5 deg forward (48 forward,
//              32 back, 39 sideways), twist +-60 deg
//   shoulder   cone 85 deg about out-forward-down (55 deg from the hanging
//              arm): the arm rises about 130 deg sideways or forward,
//              reaches 39 deg behind and 39 across the body; twist +-50 deg
//   hip        cone 55 deg about forward-down, a little out (38 deg from
//              the hanging leg): 91 deg forward, 18 back, 56 out, 33
//              across; twist +-35 deg
//   elbow      hinge about the figure's right (-x), 0 (straight) to 145 deg
//              (the forearm folds forward)
//   knee       hinge about the figure's right (-x), -140 deg to 0
//              (straight; the shin folds backward)
#include <array>
#include <cstdint>
#include <span>

#include "rewind/core/status.h"
#include "rewind/sim/body.h"
#include "rewind/sim/joint.h"
#include "rewind/sim/math.h"

namespace rwd::sim {

class World3D;

/// The eleven parts, parents before children. L is the figure's left (+x).
enum class RagdollPart3D : uint8_t {
  kPelvis = 0,
  kSpine = 1,  ///< the torso, waist to neck
  kHead = 2,
  kUpperArmL = 3,
  kUpperArmR = 4,
  kForearmL = 5,  ///< forearm and hand, elbow to fingertips
  kForearmR = 6,
  kThighL = 7,
  kThighR = 8,
  kShinL = 9,  ///< shin and foot, knee to sole
  kShinR = 10,
};
inline constexpr uint32_t kRagdollPartCount3D = 11;

/// The ten joints. Joint j joins part j + 1 (its child) to that part's
/// parent (ragdoll_joint_parent()).
enum class RagdollJoint3D : uint8_t {
  kWaist = 0,      ///< pelvis - spine, ball
  kNeck = 1,       ///< spine - head, ball
  kShoulderL = 2,  ///< spine - upper_arm_l, ball
  kShoulderR = 3,
  kElbowL = 4,  ///< upper_arm_l - forearm_l, hinge
  kElbowR = 5,
  kHipL = 6,  ///< pelvis - thigh_l, ball
  kHipR = 7,
  kKneeL = 8,  ///< thigh_l - shin_l, hinge
  kKneeR = 9,
};
inline constexpr uint32_t kRagdollJointCount3D = 10;

/// "pelvis", "spine", "head", "upper_arm_l", "upper_arm_r", "forearm_l",
/// "forearm_r", "thigh_l", "thigh_r", "shin_l", "shin_r"; "?" out of range.
const char* ragdoll_part_name(RagdollPart3D part);
/// "waist", "neck", "shoulder_l", "shoulder_r", "elbow_l", "elbow_r",
/// "hip_l", "hip_r", "knee_l", "knee_r"; "?" out of range.
const char* ragdoll_joint_name(RagdollJoint3D joint);
/// The part a joint hangs from (body_a of its JointDef) and the part it
/// moves (body_b: the part whose index is the joint's plus one).
RagdollPart3D ragdoll_joint_parent(RagdollJoint3D joint);
RagdollPart3D ragdoll_joint_child(RagdollJoint3D joint);
/// The share of the whole mass a part gets (standard segment-mass
/// fractions: pelvis 0.142, spine 0.355, head 0.081, upper arm 0.028,
/// forearm with hand 0.022, thigh 0.100, shin with foot 0.061; they sum
/// to 1).
float ragdoll_mass_fraction(RagdollPart3D part);

/// A bone's capsule: its radius and its length from tip to tip (caps
/// included), m. Zero fields take their value from the height.
struct RagdollBone3D {
  float radius_m = 0.0f;
  float length_m = 0.0f;
};

/// What a ragdoll is made from. create_ragdoll() checks every field and
/// names the one it refuses.
struct RagdollSpec3D {
  /// Standing height, soles to crown, m, in [0.1, 100]. The default bones
  /// scale with it (fractions of the height, radius / length):
  ///   pelvis 0.065 / 0.23, spine 0.075 / 0.25, head 0.055 / 0.13,
  ///   upper arm 0.028 / 0.18, forearm 0.022 / 0.24,
  ///   thigh 0.040 / 0.2375, shin 0.030 / 0.285,
  /// which stand exactly `height_m` tall, shoulders at 0.795 of it, hips at
  /// 0.52, knees at 0.285 and fingertips at 0.375 (close to the usual
  /// anthropometric tables).
  float height_m = 1.8f;
  /// Whole mass, kg, in (0, 1e6]: shared by ragdoll_mass_fraction() and set
  /// through each capsule's density, so the parts' World3D::mass() sums to
  /// it.
  float mass_kg = 70.0f;
  /// Per part (index RagdollPart3D): a zero field keeps the default above.
  /// A given radius must be in [0.001, 100] m and a given length in
  /// (2 radius + 0.001, 200] m (a capsule with a straight part).
  ///
  /// The bones are laid out from their sizes: the pelvis lies across the
  /// hips; the hip joints sit at its cap centres, half its radius below its
  /// axis; each thigh hangs from its hip and each shin from the thigh's
  /// lower tip (the knee); the waist is a pelvis radius above the pelvis
  /// centre and the spine stands on it; the neck is at the spine's top tip
  /// and the head stands on it; the shoulders are at the height of the
  /// spine's upper cap centre, the spine radius plus two upper arm radii
  /// out; each forearm hangs from its upper arm's lower tip (the elbow).
  std::array<RagdollBone3D, kRagdollPartCount3D> bones{};
  /// Where the pelvis centre goes, m (the root of the figure; in the rest
  /// pose the soles are ragdoll_pelvis_height() below it), and how the
  /// whole figure is turned about it (normalized; finite and non-zero).
  /// Every part must land inside the world bounds.
  Vec3 position;
  Quat rotation;
  /// The collision layer bits every part is on (non-zero). Each part's
  /// mask is `mask` without these bits, so the parts of one ragdoll never
  /// collide with each other while they collide with everything else that
  /// agrees (the world's default layer 1 and mask ~0 do). Ragdolls that
  /// should collide with each other need different self_layer bits.
  uint32_t self_layer = 1u << 31;
  /// The layers the parts collide with (self_layer is removed from it).
  uint32_t mask = 0xFFFFFFFFu;
  /// The parts' surface, as Material: friction in [0, 10], restitution in
  /// [0, 1].
  float friction = 0.7f;
  float restitution = 0.0f;
  /// The parts' damping, 1/s, each in [0, 100]: a little angular damping
  /// lets a limp body settle instead of rocking on its round capsules.
  float linear_damping = 0.0f;
  float angular_damping = 0.5f;
  /// Joint friction, in [0, 1]: each joint resists turning with up to this
  /// share of the torque that what hangs below it (its child part and the
  /// parts beyond) weighs held out level under standard gravity, 9.81
  /// m/s^2 (the rest pose's lever from the joint to their centre of mass).
  /// Built as the joint's motor toward no relative turn
  /// (JointDef::enable_motor, max_motor_torque), so a limb still falls
  /// while a swinging head or a rocking arm comes to rest and a heap of
  /// figures can sleep. 0: free joints, no motor.
  float joint_friction = 0.25f;
  /// 0 leaves every part's user_data 0; otherwise part p gets
  /// user_data_base + p (so a contact's body names the ragdoll and part).
  uint64_t user_data_base = 0;
};

/// A part's capsule with the defaults applied (zero sizes when the spec's
/// height is not finite and positive).
RagdollBone3D ragdoll_bone(const RagdollSpec3D& spec, RagdollPart3D part);
/// The pelvis centre's height above the soles in the rest pose, m: stand a
/// ragdoll on a floor at y = f with position = (x, f + this, z).
float ragdoll_pelvis_height(const RagdollSpec3D& spec);

/// A ragdoll in a world: plain data the game owns (a rollback restores the
/// world; the ids stay right because the world restores them too).
struct Ragdoll3D {
  std::array<BodyId, kRagdollPartCount3D> parts{};
  std::array<JointId, kRagdollJointCount3D> joints{};
  /// Each joint's point in its parent's and its child's authored frame
  /// (the frame World3D::position() and rotation() report), m: the two
  /// meet in the world while the joint holds (ragdoll_joint_gap()).
  std::array<Vec3, kRagdollJointCount3D> anchor_parent{};
  std::array<Vec3, kRagdollJointCount3D> anchor_child{};

  BodyId part(RagdollPart3D p) const { return parts[static_cast<uint32_t>(p)]; }
  JointId joint(RagdollJoint3D j) const { return joints[static_cast<uint32_t>(j)]; }
};

/// One part's pose and motion, world frame: the capsule's centre (its
/// body's position), rotation, linear velocity (m/s) and angular velocity
/// (rad/s). The hand-over from an animated skeleton.
struct RagdollPartPose3D {
  Vec3 position;
  Quat rotation;
  Vec3 linear_velocity;
  Vec3 angular_velocity;
};

/// Checks the spec and builds the ragdoll in its rest pose at
/// spec.position and spec.rotation, at rest: eleven dynamic capsules and
/// ten joints. Refuses, naming the field (kInvalidArgument), a non-finite
/// or out-of-range value, a part outside the world bounds, and (kCapacity)
/// a world without room for eleven bodies and ten joints. Everything is
/// checked before anything is made, so a refused spec leaves the world,
/// its checksum included, as it was; should the world still refuse a part
/// or joint, whatever was made is destroyed again.
Result<Ragdoll3D> create_ragdoll(World3D& world, const RagdollSpec3D& spec);

/// The rest pose's part poses (zero velocities) at spec.position and
/// spec.rotation into `out`, indexed by RagdollPart3D: where
/// create_ragdoll() puts the parts. kInvalidArgument for a spec it would
/// refuse (the world's bounds aside) or an `out` that is not exactly
/// kRagdollPartCount3D long.
Status ragdoll_rest_pose(const RagdollSpec3D& spec, std::span<RagdollPartPose3D> out);

/// Teleports every part to `parts` (indexed by RagdollPart3D; exactly
/// kRagdollPartCount3D of them) and sets its velocities, waking the
/// ragdoll: the hand-over from animation to physics. The joints keep the
/// limits of the rest pose, so the poses should come from a skeleton of
/// the same proportions. Everything is checked first (live, enabled
/// parts; finite values; rotations not zero; positions inside the world
/// bounds; speeds at most 1e4 m/s and rad/s), and a refused pose
/// (kInvalidArgument naming the part and field, kNotFound for a part that
/// is gone) changes nothing.
Status pose_ragdoll(World3D& world, const Ragdoll3D& ragdoll,
                    std::span<const RagdollPartPose3D> parts);

/// The world distance between a joint's two anchors as the parts stand,
/// m (0 when a part is gone): how far the joint has opened.
float ragdoll_joint_gap(const World3D& world, const Ragdoll3D& ragdoll, RagdollJoint3D joint);

/// Destroys every part still live (their joints go with them) and nulls
/// all the ids. kNotFound, changing nothing, when no part was live.
Status destroy_ragdoll(World3D& world, Ragdoll3D& ragdoll);

}  // namespace rwd::sim
