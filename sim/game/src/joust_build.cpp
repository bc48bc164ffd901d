// SPDX-License-Identifier: MIT
// The joust arena built: the height field, walls, gantry and wrecking
// ball, the cars with their lances and seated riders; and putting a car or
// a rider back in place.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "joust_layout.h"
#include "rewind/core/det_math.h"
#include "rewind/game/joust_game.h"
#include "rewind/sim/ragdoll3d.h"

namespace rwd::game {
namespace {

using namespace joust_detail;  // NOLINT: the layout's constants

// A triangle wave over integer samples, period 8, in [-1, 1].
float tri(int32_t i) {
  const int32_t m = ((i % 8) + 8) % 8;
  return static_cast<float>(m < 4 ? m : 8 - m) * 0.5f - 1.0f;
}

// Height of sample (row, col) of the field: integers in, + - * only.
float field_height(int32_t row, int32_t col) {
  const int32_t x = col - kFieldHalfCells;
  const int32_t z = row - kFieldHalfCells;
  const int32_t d = std::max(std::abs(x), std::abs(z)) - kFlatHalf;
  const float rim = d > 0 ? kRimCurve * static_cast<float>(d * d) : 0.0f;
  // No bumps under the gantry: the ball swings low over flat ground.
  const bool centre = std::abs(x) <= 5 && std::abs(z) <= 5;
  return rim + (centre ? 0.0f : kBumpHeight * tri(col) * tri(row));
}

sim::BodyDef static_box(sim::Vec3 centre, sim::Vec3 half) {
  sim::BodyDef def;
  def.kind = sim::BodyKind::kStatic;
  def.shape = sim::Shape::make_box(half);
  def.position = centre;
  def.material.friction = 0.8f;
  def.layer = kLayerGround;
  def.contact_events = false;
  return def;
}

sim::BodyId create(sim::World3D& world, const sim::BodyDef& def) {
  Result<sim::BodyId> id = world.create_body(def);
  return id.ok() ? *id : sim::BodyId{};
}

sim::JointId create(sim::World3D& world, const sim::JointDef& def) {
  Result<sim::JointId> id = world.create_joint(def);
  return id.ok() ? *id : sim::JointId{};
}

sim::Quat yaw(float angle) {
  return {0.0f, rwd::det_sin(0.5f * angle), 0.0f, rwd::det_cos(0.5f * angle)};
}

// Moves `id` to its place in the chassis frame (chassis at `p`, `q`),
// enabled and moving with the chassis (`v`, `w` about `com`).
void pose_on(sim::World3D& world, sim::BodyId id, sim::Vec3 local, sim::Vec3 p, sim::Quat q,
             sim::Vec3 v, sim::Vec3 w, sim::Vec3 com) {
  const sim::Vec3 at = p + sim::rotate(q, local);
  (void)world.set_transform(id, at, q);
  (void)world.set_enabled(id, true);
  (void)world.set_linear_velocity(id, v + sim::cross(w, at - com));
  (void)world.set_angular_velocity(id, w);
}

// Player p's rider as the ragdoll builder sees it (the ids; the anchors
// are the builder's business).
sim::RagdollSpec3D rider_spec(uint32_t p, sim::Vec3 position, sim::Quat rotation) {
  sim::RagdollSpec3D spec;
  spec.height_m = kRiderHeight;
  spec.mass_kg = kRiderMass;
  spec.position = position;
  spec.rotation = rotation;
  spec.self_layer = 1u << (kRiderLayerFirst + p % kRiderLayerCount);
  spec.user_data_base = kTagRider + 16u * p;
  return spec;
}

sim::Ragdoll3D rider_of(const JoustState& state, uint32_t p) {
  sim::Ragdoll3D rider;
  rider.parts = state.riders[p];
  rider.joints = state.rider_joints[p];
  return rider;
}

// The seated pose in the chassis frame: the rest pose with the thighs and
// shins turned a quarter turn forward about the hips and the forearms
// about the elbows (within the hip cone and the elbow hinge), the pelvis
// at kSeat.
std::array<sim::RagdollPartPose3D, sim::kRagdollPartCount3D> seated_pose() {
  using Part = sim::RagdollPart3D;
  const sim::RagdollSpec3D spec = rider_spec(0, kSeat, {});
  std::array<sim::RagdollPartPose3D, sim::kRagdollPartCount3D> pose{};
  (void)sim::ragdoll_rest_pose(spec, pose);
  const float h = std::sqrt(0.5f);
  const sim::Quat forward{-h, 0.0f, 0.0f, h};  // -y onto +z, about x
  auto fold = [&](Part part, sim::Vec3 pivot) {
    sim::RagdollPartPose3D& q = pose[static_cast<uint32_t>(part)];
    q.position = pivot + sim::rotate(forward, q.position - pivot);
    q.rotation = forward * q.rotation;
  };
  auto top_of = [&](Part part) {  // the upper tip of a hanging bone
    return pose[static_cast<uint32_t>(part)].position +
           sim::Vec3{0.0f, 0.5f * sim::ragdoll_bone(spec, part).length_m, 0.0f};
  };
  const sim::Vec3 hip_l = top_of(Part::kThighL);
  const sim::Vec3 hip_r = top_of(Part::kThighR);
  const sim::Vec3 elbow_l = top_of(Part::kForearmL);
  const sim::Vec3 elbow_r = top_of(Part::kForearmR);
  fold(Part::kThighL, hip_l);
  fold(Part::kShinL, hip_l);
  fold(Part::kThighR, hip_r);
  fold(Part::kShinR, hip_r);
  fold(Part::kForearmL, elbow_l);
  fold(Part::kForearmR, elbow_r);
  return pose;
}

}  // namespace

namespace joust_detail {

void spawn_pose(const sim::World3D& world, uint32_t player, uint32_t player_count,
                sim::Vec3& position, sim::Quat& rotation) {
  const float a = 2.0f * rwd::kPi * static_cast<float>(player) / static_cast<float>(player_count);
  const float ca = rwd::det_cos(a);
  const float sa = rwd::det_sin(a);
  const float x = kSpawnRadius * ca;
  const float z = kSpawnRadius * sa;
  sim::QueryFilter ground;
  ground.layer_mask = kLayerGround;
  ground.include_dynamic = false;
  const auto hit = world.raycast({{x, 20.0f, z}, {0.0f, -1.0f, 0.0f}, 40.0f}, ground);
  const float ground_y = hit ? hit->point.y : 0.0f;
  // Chassis centre where the wheels' rays just reach the ground.
  position = {x, ground_y - kWheelAttachY + kRestLength + kWheelRadius + 0.05f, z};
  // Forward (+z) turned onto (-cos a, 0, -sin a).
  rotation = yaw(rwd::det_atan2(-ca, -sa));
}

// While seated the rider holds its posture: each joint's motor at zero
// speed acts as a muscle that resists turning up to these torques (N m,
// by sim::RagdollJoint3D: waist, neck, shoulders, elbows, hips, knees),
// enough to sit up through driving, far too little to hold against a
// lance. Thrown, it goes limp.
constexpr std::array<float, sim::kRagdollJointCount3D> kRiderTone = {
    200.0f, 30.0f, 30.0f, 30.0f, 15.0f, 15.0f, 100.0f, 100.0f, 60.0f, 60.0f};

void set_rider_tone(sim::World3D& world, const JoustState& state, uint32_t p, bool on) {
  for (uint32_t j = 0; j < sim::kRagdollJointCount3D; ++j) {
    const sim::JointId id = state.rider_joints[p][j];
    if (world.joint_type(id) == sim::JointType::kHinge) {
      (void)world.set_joint_motor(id, on, 0.0f, kRiderTone[j]);
    } else {
      (void)world.set_joint_motor_velocity(id, on, {}, kRiderTone[j]);
    }
  }
}

}  // namespace joust_detail

sim::WorldConfig JoustGame::world_config() const {
  sim::WorldConfig config;
  config.tick_seconds = 1.0f / 60.0f;
  // Four substeps, the shortest substep a world accepts at 60 Hz ticks
  // (sim::kMaxSubstepSeconds).
  config.substeps = 4;
  config.bounds_lower = {-kWorldHalf, -kWorldHalf, -kWorldHalf};
  config.bounds_upper = {kWorldHalf, kWorldHalf, kWorldHalf};
  return config;
}

bool JoustGame::seat_rider(sim::World3D& world, JoustState& state, uint32_t p) {
  if (p >= state.player_count) return false;
  const sim::BodyId chassis = state.chassis[p];
  if (!world.is_valid(chassis)) return false;
  if (!state.seats[p].is_null()) {
    (void)world.destroy_joint(state.seats[p]);
    state.seats[p] = {};
  }
  const sim::Vec3 pos = world.position(chassis);
  const sim::Quat rot = world.rotation(chassis);
  const sim::Vec3 v = world.linear_velocity(chassis);
  const sim::Vec3 w = world.angular_velocity(chassis);
  const sim::Vec3 com = world.center_of_mass(chassis);
  // Parts flung out of the world were disabled where they left it: back
  // into play first (pose_ragdoll moves only live, enabled parts).
  for (const sim::BodyId part : state.riders[p]) {
    if (!world.is_valid(part)) return false;
    (void)world.set_enabled(part, true);
  }
  std::array<sim::RagdollPartPose3D, sim::kRagdollPartCount3D> pose = seated_pose();
  for (sim::RagdollPartPose3D& part : pose) {
    part.position = pos + sim::rotate(rot, part.position);
    part.rotation = rot * part.rotation;
    part.linear_velocity = v + sim::cross(w, part.position - com);
    part.angular_velocity = w;
  }
  if (!sim::pose_ragdoll(world, rider_of(state, p), pose).ok()) return false;
  const sim::BodyId pelvis = state.riders[p][static_cast<uint32_t>(sim::RagdollPart3D::kPelvis)];
  sim::JointDef seat =
      sim::joint_at(world, sim::JointType::kWeld, chassis, pelvis, pos + sim::rotate(rot, kSeat));
  seat.break_impulse = kSeatBreakImpulse;
  state.seats[p] = create(world, seat);
  set_rider_tone(world, state, p, true);
  return !state.seats[p].is_null();
}

bool JoustGame::place_car(sim::World3D& world, JoustState& state, uint32_t p, sim::Vec3 position,
                          sim::Quat rotation) {
  if (p >= state.player_count || !world.is_valid(state.chassis[p]) ||
      !world.is_valid(state.lances[p])) {
    return false;
  }
  pose_on(world, state.chassis[p], {}, position, rotation, {}, {}, position);
  pose_on(world, state.lances[p], kLanceCentre, position, rotation, {}, {}, position);
  if (!state.seats[p].is_null() && !seat_rider(world, state, p)) {
    state.respawn_ticks[p] = 1;  // seated again on the next tick
    return false;
  }
  return true;
}

float JoustGame::chain_opening(const sim::World3D& world, const JoustState& state) {
  // Each link's joints sit on its cap centres' ends, +-L/2 along its
  // local y; the ball's on its top, +R; the top joint on the beam's pivot.
  auto end_of = [&](sim::BodyId id, float local_y) {
    return world.position(id) + sim::rotate(world.rotation(id), {0.0f, local_y, 0.0f});
  };
  float worst = 0.0f;
  sim::Vec3 above{0.0f, kPivotY, 0.0f};
  for (uint32_t i = 0; i <= kJoustChainLinks; ++i) {
    const bool ball = i == kJoustChainLinks;
    const sim::BodyId body = ball ? state.ball : state.chain[i];
    const sim::Vec3 top = end_of(body, ball ? kBallRadius : 0.5f * kLinkLength);
    worst = std::max(worst, sim::length(top - above));
    if (!ball) above = end_of(body, -0.5f * kLinkLength);
  }
  return worst;
}

Status JoustGame::build_typed(const MatchSetup& setup, sim::World3D& world,
                              JoustState& state) const {
  state.player_count = setup.player_count;

  // The ground: one height field, its sample (0, 0) at the arena's corner.
  std::vector<float> heights(kFieldSamples * kFieldSamples);
  for (uint32_t r = 0; r < kFieldSamples; ++r) {
    for (uint32_t c = 0; c < kFieldSamples; ++c) {
      heights[r * kFieldSamples + c] =
          field_height(static_cast<int32_t>(r), static_cast<int32_t>(c));
    }
  }
  Result<sim::GeometryId> field =
      world.geometry().add_height_field(kFieldSamples, kFieldSamples, {1.0f, 1.0f, 1.0f}, heights);
  if (field.ok()) {
    sim::BodyDef ground;
    ground.kind = sim::BodyKind::kStatic;
    ground.shape = sim::Shape::make_height_field(*field);
    const float corner = -static_cast<float>(kFieldHalfCells);
    ground.position = {corner, 0.0f, corner};
    ground.material.friction = 0.9f;
    ground.layer = kLayerGround;
    ground.contact_events = false;
    (void)create(world, ground);
  }
  // Walls around it, above the top of the rim.
  const float edge = static_cast<float>(kFieldHalfCells);
  const float wall_y = 0.5f * kWallHeight - 1.0f;
  const float half_h = 0.5f * kWallHeight;
  (void)create(world, static_box({edge + 0.5f, wall_y, 0}, {0.5f, half_h, edge + 1.0f}));
  (void)create(world, static_box({-edge - 0.5f, wall_y, 0}, {0.5f, half_h, edge + 1.0f}));
  (void)create(world, static_box({0, wall_y, edge + 0.5f}, {edge, half_h, 0.5f}));
  (void)create(world, static_box({0, wall_y, -edge - 0.5f}, {edge, half_h, 0.5f}));

  // The gantry: two posts and the beam the chain hangs from.
  const float post_half = 0.5f * (kPivotY + 0.5f);
  (void)create(world, static_box({kPostX, kPivotY - post_half, 0}, {0.3f, post_half, 0.3f}));
  (void)create(world, static_box({-kPostX, kPivotY - post_half, 0}, {0.3f, post_half, 0.3f}));
  state.gantry = create(world, static_box({0, kPivotY + 0.25f, 0}, {kPostX + 0.5f, 0.25f, 0.3f}));

  // The chain, straight, released kReleaseAngle out toward -z; the ball at
  // its end. Each link's axis (local y) lies along the chain.
  const sim::Quat tilt{rwd::det_sin(0.5f * kReleaseAngle), 0.0f, 0.0f,
                       rwd::det_cos(0.5f * kReleaseAngle)};
  const sim::Vec3 down = sim::rotate(tilt, {0.0f, -1.0f, 0.0f});
  const sim::Vec3 pivot{0.0f, kPivotY, 0.0f};
  sim::BodyId above = state.gantry;
  for (uint32_t i = 0; i < kJoustChainLinks; ++i) {
    sim::BodyDef link;
    link.shape = sim::Shape::make_capsule(kLinkRadius, 0.5f * kLinkLength - kLinkRadius);
    link.position = pivot + down * (kLinkLength * (static_cast<float>(i) + 0.5f));
    link.rotation = tilt;
    link.density = kLinkDensity;
    link.angular_damping = 0.0f;
    link.layer = kLayerChain;
    link.user_data = kTagChain + i;
    link.contact_events = false;
    state.chain[i] = create(world, link);
    state.chain_joints[i] =
        create(world, sim::joint_at(world, sim::JointType::kBall, above, state.chain[i],
                                    pivot + down * (kLinkLength * static_cast<float>(i))));
    above = state.chain[i];
  }
  const float chain_length = kLinkLength * static_cast<float>(kJoustChainLinks);
  sim::BodyDef ball;
  ball.shape = sim::Shape::make_sphere(kBallRadius);
  ball.position = pivot + down * (chain_length + kBallRadius);
  ball.rotation = tilt;
  ball.density = kBallDensity;
  ball.angular_damping = 0.0f;
  ball.material.friction = 0.3f;
  ball.material.restitution = 0.2f;
  ball.layer = kLayerChain;
  ball.user_data = kTagBall;
  ball.contact_events = false;
  state.ball = create(world, ball);
  state.chain_joints[kJoustChainLinks] = create(
      world,
      sim::joint_at(world, sim::JointType::kBall, above, state.ball, pivot + down * chain_length));

  // The cars: chassis, lance welded on, rider seated.
  for (uint32_t p = 0; p < setup.player_count; ++p) {
    sim::Vec3 position;
    sim::Quat rotation;
    spawn_pose(world, p, setup.player_count, position, rotation);

    sim::BodyDef chassis;
    chassis.shape = sim::Shape::make_box(kChassisHalf);
    chassis.position = position;
    chassis.rotation = rotation;
    chassis.density = kChassisMass / (8.0f * kChassisHalf.x * kChassisHalf.y * kChassisHalf.z);
    chassis.angular_damping = 0.3f;
    chassis.material.friction = 0.5f;
    chassis.layer = kLayerCar;
    chassis.user_data = kTagChassis + p;
    chassis.contact_events = false;
    state.chassis[p] = create(world, chassis);

    sim::BodyDef lance;
    lance.shape = sim::Shape::make_box(kLanceHalf);
    lance.position = position + sim::rotate(rotation, kLanceCentre);
    lance.rotation = rotation;
    lance.density = kLanceDensity;
    lance.material.friction = 0.3f;
    lance.layer = kLayerCar;
    lance.user_data = kTagLance + p;
    state.lances[p] = create(world, lance);
    const sim::Vec3 lance_base = kLanceCentre - sim::Vec3{0.0f, 0.0f, kLanceHalf.z};
    state.lance_welds[p] =
        create(world, sim::joint_at(world, sim::JointType::kWeld, state.chassis[p], state.lances[p],
                                    position + sim::rotate(rotation, lance_base)));

    // The rider, made standing on the seat and seated at once.
    Result<sim::Ragdoll3D> rider = sim::create_ragdoll(
        world, rider_spec(p, position + sim::rotate(rotation, kSeat), rotation));
    if (rider.ok()) {
      state.riders[p] = rider->parts;
      state.rider_joints[p] = rider->joints;
    }
    (void)seat_rider(world, state, p);
  }
  return Status::Ok();
}

}  // namespace rwd::game
