// SPDX-License-Identifier: MIT
// The ragdoll builder (ragdoll3d.h): lay the bones out in the figure's
// frame from their sizes, check the spec and the world's room for it, then
// make the capsules and joints through World3D's public API. Nothing here
// reaches the solver: a ragdoll is bodies and joints like any others.
//
// The layout is computed in the figure's frame (pelvis centre at the
// origin, y up, facing +z, left on +x) and placed by one rotation and
// translation, so the joints' anchors and axes in each part's own frame
// do not depend on where the figure stands.
#include "rewind/sim/ragdoll3d.h"

#include <cmath>
#include <string>

#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

constexpr uint32_t kParts = kRagdollPartCount3D;
constexpr uint32_t kJoints = kRagdollJointCount3D;
constexpr float kDeg = kPi / 180.0f;
constexpr float kMaxSpeed = 1e4f;  // World3D's velocity setters refuse beyond it

constexpr const char* kPartNames[kParts] = {"pelvis",      "spine",     "head",      "upper_arm_l",
                                            "upper_arm_r", "forearm_l", "forearm_r", "thigh_l",
                                            "thigh_r",     "shin_l",    "shin_r"};
constexpr const char* kJointNames[kJoints] = {"waist",   "neck",    "shoulder_l", "shoulder_r",
                                              "elbow_l", "elbow_r", "hip_l",      "hip_r",
                                              "knee_l",  "knee_r"};
constexpr RagdollPart3D kParent[kJoints] = {RagdollPart3D::kPelvis,    RagdollPart3D::kSpine,
                                            RagdollPart3D::kSpine,     RagdollPart3D::kSpine,
                                            RagdollPart3D::kUpperArmL, RagdollPart3D::kUpperArmR,
                                            RagdollPart3D::kPelvis,    RagdollPart3D::kPelvis,
                                            RagdollPart3D::kThighL,    RagdollPart3D::kThighR};

// Segment-mass fractions after the usual anthropometric tables (Dempster,
// as tabulated by Winter), the trunk split into pelvis and thorax with
// abdomen, hands counted with the forearms and feet with the shins.
constexpr float kMassFraction[kParts] = {0.142f, 0.355f, 0.081f, 0.028f, 0.028f, 0.022f,
                                         0.022f, 0.100f, 0.100f, 0.061f, 0.061f};
// Default bones as fractions of the height: radius, length tip to tip.
// They stack to exactly the height: shin + thigh + 1.5 pelvis radius +
// spine + head = 0.285 + 0.2375 + 0.0975 + 0.25 + 0.13.
constexpr RagdollBone3D kDefaultBone[kParts] = {
    {0.065f, 0.23f},   {0.075f, 0.25f},  {0.055f, 0.13f}, {0.028f, 0.18f},
    {0.028f, 0.18f},   {0.022f, 0.24f},  {0.022f, 0.24f}, {0.040f, 0.2375f},
    {0.040f, 0.2375f}, {0.030f, 0.285f}, {0.030f, 0.285f}};

// Each joint's limits. Ball joints: the cone's centre in the figure's
// frame for the left side (x mirrored on the right), its half angle and
// the twist range. Hinges: the angle range about the figure's right.
struct JointLimits {
  JointType type;
  Vec3 cone_centre;
  float cone;
  float lower;  // twist or hinge angle
  float upper;
};
constexpr JointLimits kLimits[kJoints] = {
    {JointType::kBall, {0.0f, 1.0f, 0.2f}, 35.0f * kDeg, -30.0f * kDeg, 30.0f * kDeg},
    {JointType::kBall, {0.0f, 1.0f, 0.15f}, 40.0f * kDeg, -60.0f * kDeg, 60.0f * kDeg},
    {JointType::kBall, {1.0f, -1.0f, 1.0f}, 85.0f * kDeg, -50.0f * kDeg, 50.0f * kDeg},
    {JointType::kBall, {-1.0f, -1.0f, 1.0f}, 85.0f * kDeg, -50.0f * kDeg, 50.0f * kDeg},
    {JointType::kHinge, {}, 0.0f, 0.0f, 145.0f * kDeg},
    {JointType::kHinge, {}, 0.0f, 0.0f, 145.0f * kDeg},
    {JointType::kBall, {0.2f, -1.0f, 0.75f}, 55.0f * kDeg, -35.0f * kDeg, 35.0f * kDeg},
    {JointType::kBall, {-0.2f, -1.0f, 0.75f}, 55.0f * kDeg, -35.0f * kDeg, 35.0f * kDeg},
    {JointType::kHinge, {}, 0.0f, -140.0f * kDeg, 0.0f},
    {JointType::kHinge, {}, 0.0f, -140.0f * kDeg, 0.0f}};
constexpr Vec3 kHingeAxis{-1.0f, 0.0f, 0.0f};  // the figure's right
constexpr Vec3 kUp{0.0f, 1.0f, 0.0f};
constexpr Vec3 kDown{0.0f, -1.0f, 0.0f};

uint32_t idx(RagdollPart3D p) {
  return static_cast<uint32_t>(p);
}

// The rest pose in the figure's frame.
struct Layout {
  std::array<RagdollBone3D, kParts> bones{};
  std::array<Vec3, kParts> centre{};
  std::array<Quat, kParts> turn{};
  std::array<Vec3, kParts> bone_axis{};  // each part's long axis, pointing away from its parent
  std::array<Vec3, kJoints> joint{};
};

RagdollBone3D resolve_bone(const RagdollSpec3D& spec, uint32_t p) {
  RagdollBone3D b = spec.bones[p];
  if (b.radius_m == 0.0f) b.radius_m = kDefaultBone[p].radius_m * spec.height_m;
  if (b.length_m == 0.0f) b.length_m = kDefaultBone[p].length_m * spec.height_m;
  return b;
}

Layout lay_out(const RagdollSpec3D& spec) {
  Layout l;
  for (uint32_t p = 0; p < kParts; ++p) l.bones[p] = resolve_bone(spec, p);
  auto r = [&](RagdollPart3D p) { return l.bones[idx(p)].radius_m; };
  auto len = [&](RagdollPart3D p) { return l.bones[idx(p)].length_m; };
  auto set = [&](RagdollPart3D p, Vec3 tip, Vec3 axis) {
    l.centre[idx(p)] = tip + axis * (0.5f * len(p));
    l.bone_axis[idx(p)] = axis;
  };
  auto joint = [&](RagdollJoint3D j) -> Vec3& { return l.joint[static_cast<uint32_t>(j)]; };
  // Capsules stand along their local y; the pelvis lies along x (a quarter
  // turn about -z takes y to x). The rest stay unturned.
  for (Quat& q : l.turn) q = Quat{};
  const float h = std::sqrt(0.5f);
  l.turn[idx(RagdollPart3D::kPelvis)] = Quat{0.0f, 0.0f, -h, h};
  l.bone_axis[idx(RagdollPart3D::kPelvis)] = {1.0f, 0.0f, 0.0f};

  const float rp = r(RagdollPart3D::kPelvis);
  const float hip_x = 0.5f * len(RagdollPart3D::kPelvis) - rp;
  const float waist_y = rp;
  const float neck_y = waist_y + len(RagdollPart3D::kSpine);
  const float shoulder_y = neck_y - r(RagdollPart3D::kSpine);
  joint(RagdollJoint3D::kWaist) = {0.0f, waist_y, 0.0f};
  joint(RagdollJoint3D::kNeck) = {0.0f, neck_y, 0.0f};
  set(RagdollPart3D::kSpine, joint(RagdollJoint3D::kWaist), kUp);
  set(RagdollPart3D::kHead, joint(RagdollJoint3D::kNeck), kUp);
  for (int side = 0; side < 2; ++side) {
    const float s = side == 0 ? 1.0f : -1.0f;  // left on +x
    const auto pick = [side](auto left, auto right) { return side == 0 ? left : right; };
    const RagdollPart3D upper = pick(RagdollPart3D::kUpperArmL, RagdollPart3D::kUpperArmR);
    const RagdollPart3D fore = pick(RagdollPart3D::kForearmL, RagdollPart3D::kForearmR);
    const RagdollPart3D thigh = pick(RagdollPart3D::kThighL, RagdollPart3D::kThighR);
    const RagdollPart3D shin = pick(RagdollPart3D::kShinL, RagdollPart3D::kShinR);
    const RagdollJoint3D shoulder = pick(RagdollJoint3D::kShoulderL, RagdollJoint3D::kShoulderR);
    const RagdollJoint3D elbow = pick(RagdollJoint3D::kElbowL, RagdollJoint3D::kElbowR);
    const RagdollJoint3D hip = pick(RagdollJoint3D::kHipL, RagdollJoint3D::kHipR);
    const RagdollJoint3D knee = pick(RagdollJoint3D::kKneeL, RagdollJoint3D::kKneeR);
    const float arm_x = r(RagdollPart3D::kSpine) + 2.0f * r(upper);
    joint(shoulder) = {s * arm_x, shoulder_y, 0.0f};
    joint(elbow) = joint(shoulder) + kDown * len(upper);
    joint(hip) = {s * hip_x, -0.5f * rp, 0.0f};
    joint(knee) = joint(hip) + kDown * len(thigh);
    set(upper, joint(shoulder), kDown);
    set(fore, joint(elbow), kDown);
    set(thigh, joint(hip), kDown);
    set(shin, joint(knee), kDown);
  }
  return l;
}

Status invalid(const std::string& what) {
  return Status::Error(ErrorCode::kInvalidArgument, what);
}

bool in_range(float v, float lo, float hi) {
  return std::isfinite(v) && v >= lo && v <= hi;
}

// The capsule the world will make of a bone (its sizes on the canonical
// grid), and the density that gives it its share of the mass.
Shape capsule_of(const RagdollBone3D& b) {
  return Shape::make_capsule(quantize(b.radius_m), quantize(0.5f * b.length_m - b.radius_m));
}

float capsule_volume(const Shape& s) {
  const float r = s.radius;
  return kPi * r * r * (2.0f * s.half_height) + (4.0f / 3.0f) * kPi * r * r * r;
}

float part_density(const RagdollSpec3D& spec, const Layout& l, uint32_t p) {
  return spec.mass_kg * kMassFraction[p] / capsule_volume(capsule_of(l.bones[p]));
}

// Everything that does not need a world.
Status check_spec(const RagdollSpec3D& spec, Layout& l) {
  if (!in_range(spec.height_m, 0.1f, 100.0f)) {
    return invalid("height_m must be finite, in [0.1, 100] m");
  }
  if (!(std::isfinite(spec.mass_kg) && spec.mass_kg > 0.0f && spec.mass_kg <= 1e6f)) {
    return invalid("mass_kg must be finite, in (0, 1e6] kg");
  }
  for (uint32_t p = 0; p < kParts; ++p) {
    const RagdollBone3D& given = spec.bones[p];
    const std::string at = std::string("bones[") + kPartNames[p] + "].";
    if (given.radius_m != 0.0f && !in_range(given.radius_m, 0.001f, 100.0f)) {
      return invalid(at + "radius_m must be 0 (from height_m) or finite, in [0.001, 100] m");
    }
    if (given.length_m != 0.0f && !in_range(given.length_m, 0.0f, 200.0f)) {
      return invalid(at + "length_m must be 0 (from height_m) or finite, in (0, 200] m");
    }
  }
  l = lay_out(spec);
  for (uint32_t p = 0; p < kParts; ++p) {
    const RagdollBone3D& b = l.bones[p];
    const std::string at = std::string("bones[") + kPartNames[p] + "].";
    if (!(b.length_m > 2.0f * b.radius_m + 0.001f) || !(quantize(b.radius_m) > 0.0f) ||
        !(capsule_of(b).half_height > 0.0f)) {
      return invalid(at + "length_m must exceed twice radius_m by more than 1 mm (length " +
                     std::to_string(b.length_m) + " m, radius " + std::to_string(b.radius_m) +
                     " m)");
    }
    const float density = part_density(spec, l, p);
    if (!(std::isfinite(density) && quantize(density) > 0.0f && density <= 1e9f)) {
      return invalid(std::string("mass_kg: part ") + kPartNames[p] +
                     " would need a density outside (0, 1e9] kg/m^3 (" + std::to_string(density) +
                     ")");
    }
  }
  if (!is_finite(spec.position)) return invalid("position must be finite");
  if (!is_finite(spec.rotation) || length_squared(spec.rotation) < 1e-6f) {
    return invalid("rotation must be a finite, non-zero quaternion");
  }
  if (spec.self_layer == 0) return invalid("self_layer must have at least one bit set");
  if (!in_range(spec.friction, 0.0f, 10.0f)) return invalid("friction must be in [0, 10]");
  if (!in_range(spec.restitution, 0.0f, 1.0f)) return invalid("restitution must be in [0, 1]");
  if (!in_range(spec.linear_damping, 0.0f, 100.0f)) {
    return invalid("linear_damping must be in [0, 100] 1/s");
  }
  if (!in_range(spec.angular_damping, 0.0f, 100.0f)) {
    return invalid("angular_damping must be in [0, 100] 1/s");
  }
  if (!in_range(spec.joint_friction, 0.0f, 1.0f)) {
    return invalid("joint_friction must be in [0, 1]");
  }
  return Status::Ok();
}

// The rest pose placed at the spec's root.
void place(const RagdollSpec3D& spec, const Layout& l, std::span<RagdollPartPose3D> out) {
  const Quat q = normalize(spec.rotation);
  for (uint32_t p = 0; p < kParts; ++p) {
    out[p] = RagdollPartPose3D{spec.position + rotate(q, l.centre[p]), normalize(q * l.turn[p]),
                               Vec3{}, Vec3{}};
  }
}

bool inside(const WorldConfig& c, Vec3 p) {
  return p.x >= c.bounds_lower.x && p.x <= c.bounds_upper.x && p.y >= c.bounds_lower.y &&
         p.y <= c.bounds_upper.y && p.z >= c.bounds_lower.z && p.z <= c.bounds_upper.z;
}

bool speed_ok(Vec3 v) {
  return is_finite(v) && length_squared(v) <= kMaxSpeed * kMaxSpeed &&
         length_squared(quantize(v)) <= kMaxSpeed * kMaxSpeed;
}

// The torque what hangs below joint j weighs held out level, N m: the
// mass of its child and the parts beyond it, under standard gravity, at
// the distance from the joint to their centre of mass in the rest pose.
// Parts come parents first, so one pass finds the parts below.
float hanging_torque(const RagdollSpec3D& spec, const Layout& l, uint32_t j) {
  constexpr float kStandardGravity = 9.81f;
  std::array<bool, kParts> below{};
  below[j + 1] = true;
  float mass = 0.0f;
  Vec3 moment{};
  for (uint32_t p = j + 1; p < kParts; ++p) {
    if (p > j + 1) below[p] = below[idx(kParent[p - 1])];
    if (!below[p]) continue;
    const float m = kMassFraction[p] * spec.mass_kg;
    mass += m;
    moment += l.centre[p] * m;
  }
  const float lever = length(moment * (1.0f / mass) - l.joint[j]);
  return spec.joint_friction * mass * kStandardGravity * lever;
}

// A joint's definition in its two parts' own frames.
JointDef joint_def(const Layout& l, uint32_t j, BodyId parent, BodyId child, float friction_nm) {
  const uint32_t a = idx(kParent[j]);
  const uint32_t b = j + 1;
  const JointLimits& lim = kLimits[j];
  JointDef def;
  def.type = lim.type;
  def.body_a = parent;
  def.body_b = child;
  def.anchor_a = inv_rotate(l.turn[a], l.joint[j] - l.centre[a]);
  def.anchor_b = inv_rotate(l.turn[b], l.joint[j] - l.centre[b]);
  def.enable_limit = true;
  // Joint friction: a motor toward no relative turn, as strong as the
  // friction torque and no stronger.
  def.enable_motor = friction_nm > 0.0f;
  def.max_motor_torque = friction_nm;
  if (lim.type == JointType::kHinge) {
    def.axis_a = inv_rotate(l.turn[a], kHingeAxis);
    def.axis_b = inv_rotate(l.turn[b], kHingeAxis);
    def.lower = lim.lower;
    def.upper = lim.upper;
  } else {
    // The twist axis is the child bone; the cone's centre is fixed in the
    // parent, away from the bone where the joint reaches further one way.
    def.axis_a = inv_rotate(l.turn[a], normalize_or_zero(lim.cone_centre));
    def.axis_b = inv_rotate(l.turn[b], l.bone_axis[b]);
    def.cone_angle = lim.cone;
    def.twist_lower = lim.lower;
    def.twist_upper = lim.upper;
  }
  return def;
}

void destroy_parts(World3D& world, const std::array<BodyId, kParts>& parts, uint32_t made) {
  for (uint32_t p = made; p-- > 0;) {
    if (world.is_valid(parts[p])) (void)world.destroy_body(parts[p]);
  }
}

}  // namespace

const char* ragdoll_part_name(RagdollPart3D part) {
  const auto p = static_cast<uint32_t>(part);
  return p < kParts ? kPartNames[p] : "?";
}

const char* ragdoll_joint_name(RagdollJoint3D joint) {
  const auto j = static_cast<uint32_t>(joint);
  return j < kJoints ? kJointNames[j] : "?";
}

RagdollPart3D ragdoll_joint_parent(RagdollJoint3D joint) {
  const auto j = static_cast<uint32_t>(joint);
  return j < kJoints ? kParent[j] : RagdollPart3D::kPelvis;
}

RagdollPart3D ragdoll_joint_child(RagdollJoint3D joint) {
  const auto j = static_cast<uint32_t>(joint);
  return j < kJoints ? static_cast<RagdollPart3D>(j + 1) : RagdollPart3D::kPelvis;
}

float ragdoll_mass_fraction(RagdollPart3D part) {
  const auto p = static_cast<uint32_t>(part);
  return p < kParts ? kMassFraction[p] : 0.0f;
}

RagdollBone3D ragdoll_bone(const RagdollSpec3D& spec, RagdollPart3D part) {
  const auto p = static_cast<uint32_t>(part);
  if (p >= kParts || !(std::isfinite(spec.height_m) && spec.height_m > 0.0f)) return {};
  return resolve_bone(spec, p);
}

float ragdoll_pelvis_height(const RagdollSpec3D& spec) {
  const RagdollBone3D shin = ragdoll_bone(spec, RagdollPart3D::kShinL);
  const RagdollBone3D thigh = ragdoll_bone(spec, RagdollPart3D::kThighL);
  const RagdollBone3D pelvis = ragdoll_bone(spec, RagdollPart3D::kPelvis);
  return shin.length_m + thigh.length_m + 0.5f * pelvis.radius_m;
}

Status ragdoll_rest_pose(const RagdollSpec3D& spec, std::span<RagdollPartPose3D> out) {
  if (out.size() != kParts) return invalid("out must hold exactly 11 part poses");
  Layout l;
  if (Status s = check_spec(spec, l); !s.ok()) return s;
  place(spec, l, out);
  return Status::Ok();
}

Result<Ragdoll3D> create_ragdoll(World3D& world, const RagdollSpec3D& spec) {
  Layout l;
  if (Status s = check_spec(spec, l); !s.ok()) return s;
  std::array<RagdollPartPose3D, kParts> pose;
  place(spec, l, pose);
  const WorldConfig& config = world.config();
  for (uint32_t p = 0; p < kParts; ++p) {
    if (!inside(config, pose[p].position) || !inside(config, quantize(pose[p].position))) {
      return invalid(std::string("position: part ") + kPartNames[p] +
                     " would lie outside the world bounds");
    }
  }
  // Joints share the bodies' capacity (World3D::create_joint).
  if (world.body_count() + kParts > config.max_bodies ||
      world.joint_count() + kJoints > config.max_bodies) {
    return Status::Error(ErrorCode::kCapacity,
                         "world has no room for 11 more bodies and 10 more joints (max_bodies)");
  }

  Ragdoll3D r;
  for (uint32_t p = 0; p < kParts; ++p) {
    BodyDef def;
    def.kind = BodyKind::kDynamic;
    def.shape = capsule_of(l.bones[p]);
    def.position = pose[p].position;
    def.rotation = pose[p].rotation;
    def.density = part_density(spec, l, p);
    def.linear_damping = spec.linear_damping;
    def.angular_damping = spec.angular_damping;
    def.material.friction = spec.friction;
    def.material.restitution = spec.restitution;
    def.layer = spec.self_layer;
    def.mask = spec.mask & ~spec.self_layer;
    def.user_data = spec.user_data_base == 0 ? 0 : spec.user_data_base + p;
    Result<BodyId> id = world.create_body(def);
    if (!id.ok()) {
      destroy_parts(world, r.parts, p);
      return Status::Error(id.status().code(),
                           std::string("part ") + kPartNames[p] + ": " + id.status().message());
    }
    r.parts[p] = *id;
  }
  for (uint32_t j = 0; j < kJoints; ++j) {
    const JointDef def =
        joint_def(l, j, r.parts[idx(kParent[j])], r.parts[j + 1], hanging_torque(spec, l, j));
    Result<JointId> id = world.create_joint(def);
    if (!id.ok()) {
      destroy_parts(world, r.parts, kParts);
      return Status::Error(id.status().code(),
                           std::string("joint ") + kJointNames[j] + ": " + id.status().message());
    }
    r.joints[j] = *id;
    r.anchor_parent[j] = def.anchor_a;
    r.anchor_child[j] = def.anchor_b;
  }
  return r;
}

Status pose_ragdoll(World3D& world, const Ragdoll3D& ragdoll,
                    std::span<const RagdollPartPose3D> parts) {
  if (parts.size() != kParts) return invalid("parts must hold exactly 11 part poses");
  const WorldConfig& config = world.config();
  for (uint32_t p = 0; p < kParts; ++p) {
    const std::string at = std::string("parts[") + kPartNames[p] + "]";
    const RagdollPartPose3D& pose = parts[p];
    if (!world.is_valid(ragdoll.parts[p])) {
      return Status::Error(ErrorCode::kNotFound, at + ": the part's body is not live");
    }
    if (!world.is_enabled(ragdoll.parts[p])) {
      return invalid(at + ": the part's body is disabled (enable it first)");
    }
    if (!is_finite(pose.position) || !inside(config, pose.position) ||
        !inside(config, quantize(pose.position))) {
      return invalid(at + ".position must be finite and inside the world bounds");
    }
    if (!is_finite(pose.rotation) || length_squared(pose.rotation) < 1e-6f) {
      return invalid(at + ".rotation must be a finite, non-zero quaternion");
    }
    if (!speed_ok(pose.linear_velocity)) {
      return invalid(at + ".linear_velocity must be finite, at most 1e4 m/s");
    }
    if (!speed_ok(pose.angular_velocity)) {
      return invalid(at + ".angular_velocity must be finite, at most 1e4 rad/s");
    }
  }
  // Everything the setters check has passed: they cannot refuse now.
  for (uint32_t p = 0; p < kParts; ++p) {
    const BodyId id = ragdoll.parts[p];
    if (Status s = world.set_transform(id, parts[p].position, parts[p].rotation); !s.ok()) return s;
    if (Status s = world.set_linear_velocity(id, parts[p].linear_velocity); !s.ok()) return s;
    if (Status s = world.set_angular_velocity(id, parts[p].angular_velocity); !s.ok()) return s;
  }
  return Status::Ok();
}

float ragdoll_joint_gap(const World3D& world, const Ragdoll3D& ragdoll, RagdollJoint3D joint) {
  const auto j = static_cast<uint32_t>(joint);
  if (j >= kJoints) return 0.0f;
  const BodyId a = ragdoll.parts[idx(kParent[j])];
  const BodyId b = ragdoll.parts[j + 1];
  if (!world.is_valid(a) || !world.is_valid(b)) return 0.0f;
  const Vec3 pa = world.position(a) + rotate(world.rotation(a), ragdoll.anchor_parent[j]);
  const Vec3 pb = world.position(b) + rotate(world.rotation(b), ragdoll.anchor_child[j]);
  return length(pb - pa);
}

Status destroy_ragdoll(World3D& world, Ragdoll3D& ragdoll) {
  bool any = false;
  for (const BodyId id : ragdoll.parts) any = any || world.is_valid(id);
  if (!any) return Status::Error(ErrorCode::kNotFound, "no part of the ragdoll is live");
  destroy_parts(world, ragdoll.parts, kParts);
  ragdoll = Ragdoll3D{};
  return Status::Ok();
}

}  // namespace rwd::sim
