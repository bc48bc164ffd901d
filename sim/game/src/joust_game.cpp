// SPDX-License-Identifier: MIT
#include "rewind/game/joust_game.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "rewind/sim/det_math.h"
#include "rewind/sim/ragdoll3d.h"
#include "rewind/sim/vehicle3d.h"

namespace rwd::game {
namespace {

// --- the arena ---------------------------------------------------------------
// A square height field of 1 m cells centred on the origin: flat (with low
// bumps) out to kFlatHalf, then a bowl rim rising to the walls.
constexpr int32_t kFieldHalfCells = 24;
constexpr uint32_t kFieldSamples = 2 * kFieldHalfCells + 1;
constexpr int32_t kFlatHalf = 16;   // m: where the rim starts rising
constexpr float kRimCurve = 0.05f;  // m of rim per m^2 beyond kFlatHalf
constexpr float kBumpHeight = 0.18f;
constexpr float kWallHeight = 8.0f;
constexpr float kKillPlaneY = -10.0f;
constexpr float kWorldHalf = 200.0f;
constexpr float kSpawnRadius = 10.0f;

// --- the cars ----------------------------------------------------------------
// A 900 kg box chassis facing +z (+x is the car's left) on four raycast
// wheels; with its lance and rider it weighs about a tonne.
constexpr sim::Vec3 kChassisHalf{0.9f, 0.3f, 1.8f};
constexpr float kChassisMass = 900.0f;
constexpr float kWheelX = 0.8f;
constexpr float kWheelZ = 1.2f;
constexpr float kWheelAttachY = -0.2f;
constexpr float kRestLength = 0.4f;
constexpr float kMaxTravel = 0.3f;
constexpr float kWheelRadius = 0.35f;
// A 1.6 Hz ride for a quarter of a tonne per wheel, damping ratio 0.4.
constexpr float kStiffness = 26000.0f;
constexpr float kDamping = 2100.0f;
constexpr float kTireFriction = 1.1f;
// The stick sets a speed (full deflection: kTopSpeedMps ahead or behind);
// the drive pushes toward it with up to kDriveForce, at full force from
// kSpeedBandMps away.
constexpr float kDriveForce = 6500.0f;  // N
constexpr float kTopSpeedMps = 12.0f;
constexpr float kSpeedBandMps = 3.0f;
constexpr float kChargeFactor = 2.2f;        // drive force multiplier while charging
constexpr float kChargeTopSpeedMps = 18.0f;  // top speed while charging
constexpr float kBrakeForce = 14000.0f;
constexpr float kMaxSteer = 0.6f;          // rad at a standstill
constexpr float kSteerFalloffMps = 20.0f;  // steering halves at this speed
constexpr int32_t kChargeTicks = 60;
constexpr int32_t kChargeCooldownTicks = 240;
// A car this far over (its up axis below this height) for kUpsetTicks is
// put back at its spawn point.
constexpr float kUpsetUpY = 0.3f;
constexpr int32_t kUpsetTicks = 120;

// The lance: a 4 m pole on the car's left at a rider's chest height,
// welded at its back end, its tip 2.8 m ahead of the bumper.
constexpr sim::Vec3 kLanceHalf{0.06f, 0.06f, 2.0f};
constexpr sim::Vec3 kLanceCentre{0.55f, 0.85f, 2.6f};
constexpr float kLanceDensity = 500.0f;

// The rider: the engine's ragdoll (ragdoll3d.h), 1.8 m and 70 kg, sitting
// on the roof behind the lance's foot with its legs out along the car and
// its forearms forward. kSeat is the pelvis centre in the chassis frame:
// the legs, level with the hips, just clear the roof.
constexpr float kRiderHeight = 1.8f;
constexpr float kRiderMass = 70.0f;
constexpr sim::Vec3 kSeat{0.0f, 0.44f, -0.4f};
// The seat weld lets go when one tick's reaction exceeds this (N s, or
// N m s for its turning part): a crash, a roll, a lance or the ball. Riding
// over the bumps and cornering hard load it well below.
constexpr float kSeatBreakImpulse = 150.0f;
// A lance striking a rider with at least this normal impulse in one tick
// throws the rider off whatever the weld says, and flings it.
constexpr float kUnseatImpulse = 40.0f;
constexpr float kThrowSpeed = 4.0f;  // m/s along the striking lance
constexpr float kThrowLift = 2.5f;   // m/s up
constexpr int32_t kHitMemoryTicks = 45;
// A rider thrown with no strike remembered scores for the first opponent
// lance to touch it within this many ticks.
constexpr int32_t kCreditTicks = 6;
constexpr int32_t kRespawnTicks = 180;

// --- the wrecking ball -------------------------------------------------------
// A static gantry (two posts and a beam along x) over the centre; a chain
// of capsule links on ball joints, the ball at its end, released 50 degrees
// out in the y-z plane.
constexpr float kPivotY = 6.8f;
constexpr float kPostX = 4.5f;
constexpr float kLinkLength = 0.6f;  // cap to cap
constexpr float kLinkRadius = 0.09f;
constexpr float kLinkDensity = 3000.0f;
constexpr float kBallRadius = 0.7f;
constexpr float kBallDensity = 1500.0f;
constexpr float kReleaseAngle = 50.0f * sim::kPi / 180.0f;
// Near the bottom of its swing the ball gets a small push along its motion
// while slower than this, so it keeps swinging all match.
constexpr float kPumpSpeedMps = 5.5f;
constexpr float kPumpDeltaMps = 0.05f;
constexpr float kPumpZone = 0.6f;  // m either side of the gantry

constexpr uint32_t kLayerGround = 1u << 0;
constexpr uint32_t kLayerCar = 1u << 1;
constexpr uint32_t kLayerChain = 1u << 3;
// Each rider's parts are on one of the top 24 bits (player p on bit
// 8 + p % 24) and skip only their own bit: a figure's parts never collide
// with each other, and riders collide with each other's (but for players
// 24 slots apart, whose riders share a bit and pass through each other).
constexpr uint32_t kRiderLayerFirst = 8;
constexpr uint32_t kRiderLayerCount = 24;
constexpr uint32_t kLayerRiders = 0xFFFFFF00u;
constexpr uint64_t kTagChassis = 0x100;
constexpr uint64_t kTagLance = 0x200;
constexpr uint64_t kTagRider = 0x1000;  // + player * 16 + part
constexpr uint64_t kTagChain = 0x800;
constexpr uint64_t kTagBall = 0x900;

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
  return {0.0f, sim::det_sin(0.5f * angle), 0.0f, sim::det_cos(0.5f * angle)};
}

// Where player p's car starts and comes back: on a circle, facing the
// centre, dropped just onto the ground.
void spawn_pose(const sim::World3D& world, uint32_t player, uint32_t player_count,
                sim::Vec3& position, sim::Quat& rotation) {
  const float a = 2.0f * sim::kPi * static_cast<float>(player) / static_cast<float>(player_count);
  const float ca = sim::det_cos(a);
  const float sa = sim::det_sin(a);
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
  rotation = yaw(sim::det_atan2(-ca, -sa));
}

std::array<sim::WheelDef3D, 4> wheels() {
  std::array<sim::WheelDef3D, 4> w{};
  for (uint32_t i = 0; i < 4; ++i) {
    w[i].attachment = {(i % 2 == 0) ? kWheelX : -kWheelX, kWheelAttachY,
                       (i < 2) ? kWheelZ : -kWheelZ};
    w[i].rest_length_m = kRestLength;
    w[i].max_travel_m = kMaxTravel;
    w[i].radius_m = kWheelRadius;
    w[i].stiffness_npm = kStiffness;
    w[i].damping_nspm = kDamping;
    w[i].friction = kTireFriction;
    w[i].steers = i < 2;
    w[i].drives = true;
    w[i].brakes = true;
  }
  return w;
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

bool fell(const sim::World3D& world, sim::BodyId id) {
  return !world.is_enabled(id) || world.position(id).y < kKillPlaneY;
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

// Player p's car back at its spawn point, at rest.
void reset_car(sim::World3D& world, JoustState& state, uint32_t p) {
  sim::Vec3 position;
  sim::Quat rotation;
  spawn_pose(world, p, state.player_count, position, rotation);
  (void)JoustGame::place_car(world, state, p, position, rotation);
  state.upset_ticks[p] = 0;
  ++state.car_resets[p];
}

// Flings player p's thrown rider along the lance of the player who struck
// it, and up.
void fling(sim::World3D& world, const JoustState& state, uint32_t p, uint32_t hitter) {
  const sim::Vec3 ahead = sim::rotate(world.rotation(state.lances[hitter]), {0.0f, 0.0f, 1.0f});
  const sim::Vec3 kick = sim::normalize_or_zero(sim::Vec3{ahead.x, 0.0f, ahead.z}) * kThrowSpeed +
                         sim::Vec3{0.0f, kThrowLift, 0.0f};
  for (const sim::BodyId part : state.riders[p]) {
    if (!world.is_enabled(part)) continue;
    (void)world.apply_linear_impulse(part, kick * world.mass(part), world.center_of_mass(part));
  }
}

// Which player a tag belongs to as a lance / a rider part, or -1.
int32_t lance_owner(uint64_t tag, uint32_t players) {
  return tag >= kTagLance && tag < kTagLance + players ? static_cast<int32_t>(tag - kTagLance) : -1;
}
int32_t rider_owner(uint64_t tag, uint32_t players) {
  return tag >= kTagRider && tag < kTagRider + 16u * players
             ? static_cast<int32_t>((tag - kTagRider) / 16)
             : -1;
}

}  // namespace

sim::WorldConfig JoustGame::world_config() const {
  sim::WorldConfig config;
  config.tick_seconds = 1.0f / 60.0f;
  // Two substeps: the joint trees (each car with its lance and rider, the
  // chain) are solved exactly every pass, so more buy little accuracy here
  // and each one costs a refactorization of every tree.
  config.substeps = 2;
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

void JoustGame::build_typed(const MatchSetup& setup, sim::World3D& world, JoustState& state) const {
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
  const sim::Quat tilt{sim::det_sin(0.5f * kReleaseAngle), 0.0f, 0.0f,
                       sim::det_cos(0.5f * kReleaseAngle)};
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
}

void JoustGame::apply_typed(Tick /*tick*/, std::span<const PlayerInput> inputs, sim::World3D& world,
                            JoustState& state) const {
  const std::array<sim::WheelDef3D, 4> wheel_defs = wheels();
  std::array<sim::WheelTelemetry3D, 4> telemetry{};
  const uint32_t players = std::min<uint32_t>(state.player_count, uint32_t(inputs.size()));
  for (uint32_t p = 0; p < players; ++p) {
    const sim::BodyId chassis = state.chassis[p];
    if (!world.is_valid(chassis) || !world.is_enabled(chassis)) continue;
    const PlayerInput& in = inputs[p];
    const float ax = static_cast<float>(std::clamp<int>(in.axis_x, -kAxisMax, kAxisMax)) / kAxisMax;
    const float ay = static_cast<float>(std::clamp<int>(in.axis_y, -kAxisMax, kAxisMax)) / kAxisMax;

    if (state.charge_ticks[p] > 0) --state.charge_ticks[p];
    if (state.cooldown_ticks[p] > 0) {
      --state.cooldown_ticks[p];
    } else if (in.buttons & kJoustCharge) {
      state.charge_ticks[p] = kChargeTicks;
      state.cooldown_ticks[p] = kChargeCooldownTicks;
    }

    const sim::Vec3 forward = sim::rotate(world.rotation(chassis), {0.0f, 0.0f, 1.0f});
    const float speed = sim::dot(world.linear_velocity(chassis), forward);
    const bool charging = state.charge_ticks[p] > 0;
    const float top = charging ? kChargeTopSpeedMps : kTopSpeedMps;
    sim::VehicleDef3D def;
    def.chassis = chassis;
    def.wheels = wheel_defs;
    def.max_drive_force_n = charging ? kDriveForce * kChargeFactor : kDriveForce;
    def.max_brake_force_n = kBrakeForce;
    def.filter.layer_mask = kLayerGround | kLayerCar | kLayerRiders;
    sim::VehicleControls3D controls;
    // Toward the stick's speed: a released stick rolls the car to a stop.
    controls.throttle = std::clamp((ay * top - speed) / kSpeedBandMps, -1.0f, 1.0f);
    controls.brake = (in.buttons & kJoustBrake) ? 1.0f : 0.0f;
    // The stick's right is a clockwise turn; less lock the faster it goes.
    controls.steer_rad = -ax * kMaxSteer / (1.0f + std::abs(speed) / kSteerFalloffMps);
    (void)sim::update_vehicle(world, def, controls, telemetry);
  }

  // Keep the wrecking ball swinging: a nudge along its motion as it passes
  // under the gantry, while it is slower than the pump speed.
  const sim::BodyId ball = state.ball;
  if (world.is_valid(ball) && world.is_enabled(ball)) {
    const sim::Vec3 pos = world.position(ball);
    const sim::Vec3 v = world.linear_velocity(ball);
    const sim::Vec3 flat{v.x, 0.0f, v.z};
    const float speed = sim::length(flat);
    if (std::abs(pos.z) < kPumpZone && speed > 0.5f && speed < kPumpSpeedMps) {
      const sim::Vec3 push = flat * (kPumpDeltaMps * world.mass(ball) / speed);
      (void)world.apply_linear_impulse(ball, push, world.center_of_mass(ball));
    }
  }
}

void JoustGame::after_step_typed(Tick /*tick*/, sim::World3D& world, JoustState& state) const {
  const uint32_t players = state.player_count;
  // Lance strikes on other players' riders, in event order (by body index):
  // the later strike of one tick is the one remembered, on every machine.
  std::array<uint8_t, kMaxPlayers> knocked{};
  for (const sim::ContactEvent& event : world.events()) {
    if (event.type == sim::ContactEventType::kExit || event.sensor) continue;
    const uint64_t ua = world.user_data(event.a);
    const uint64_t ub = world.user_data(event.b);
    int32_t hitter = lance_owner(ua, players);
    int32_t victim = rider_owner(ub, players);
    if (hitter < 0 || victim < 0) {
      hitter = lance_owner(ub, players);
      victim = rider_owner(ua, players);
    }
    if (hitter < 0 || victim < 0 || hitter == victim) continue;
    const auto v = static_cast<uint32_t>(victim);
    const auto h = static_cast<uint32_t>(hitter);
    if (!state.seats[v].is_null()) {
      state.last_hitter[v] = static_cast<uint8_t>(h + 1);
      state.hit_ticks[v] = kHitMemoryTicks;
      if (event.impulse >= kUnseatImpulse) knocked[v] = 1;
    } else if (state.credit_ticks[v] > 0) {
      // The weld broke a moment before the contact was reported (the
      // solver's speculative contact pushes before the shapes touch): the
      // strike that follows it gets the point.
      state.credit_ticks[v] = 0;
      ++state.score[h];
      fling(world, state, v, h);
    }
  }

  for (uint32_t p = 0; p < players; ++p) {
    // Thrown: by a strong lance strike, or the seat weld broke (a strike,
    // a crash, the ball). A lance strike shortly before scores.
    if (!state.seats[p].is_null() && (knocked[p] || world.is_joint_broken(state.seats[p]))) {
      (void)world.destroy_joint(state.seats[p]);
      state.seats[p] = {};
      set_rider_tone(world, state, p, false);
      state.respawn_ticks[p] = kRespawnTicks;
      ++state.unseated[p];
      if (state.hit_ticks[p] > 0 && state.last_hitter[p] != 0) {
        const uint32_t hitter = state.last_hitter[p] - 1u;
        ++state.score[hitter];
        fling(world, state, p, hitter);
      } else {
        state.credit_ticks[p] = kCreditTicks;
      }
      state.last_hitter[p] = 0;
      state.hit_ticks[p] = 0;
    }
    if (state.credit_ticks[p] > 0) --state.credit_ticks[p];
    if (state.hit_ticks[p] > 0 && --state.hit_ticks[p] == 0) state.last_hitter[p] = 0;

    // A car out of the arena, or on its side or roof for too long, goes
    // back to its spawn point.
    const sim::BodyId chassis = state.chassis[p];
    if (fell(world, chassis) || fell(world, state.lances[p])) {
      reset_car(world, state, p);
    } else {
      const sim::Vec3 up = sim::rotate(world.rotation(chassis), {0.0f, 1.0f, 0.0f});
      state.upset_ticks[p] = up.y < kUpsetUpY ? state.upset_ticks[p] + 1 : 0;
      if (state.upset_ticks[p] >= kUpsetTicks) reset_car(world, state, p);
    }

    // A thrown rider is back on its car after kRespawnTicks.
    if (state.seats[p].is_null() && --state.respawn_ticks[p] <= 0) {
      state.respawn_ticks[p] = seat_rider(world, state, p) ? 0 : 1;
    }
  }
}

void JoustGame::hash_typed(const JoustState& state, sim::StateHasher& hasher) const {
  auto add_body = [&hasher](sim::BodyId id) {
    hasher.add_u32(id.index);
    hasher.add_u32(id.generation);
  };
  auto add_joint = [&hasher](sim::JointId id) {
    hasher.add_u32(id.index);
    hasher.add_u32(id.generation);
  };
  hasher.add_u32(state.player_count);
  for (uint32_t p = 0; p < std::min<uint32_t>(state.player_count, kMaxPlayers); ++p) {
    add_body(state.chassis[p]);
    add_body(state.lances[p]);
    add_joint(state.lance_welds[p]);
    for (const sim::BodyId part : state.riders[p]) add_body(part);
    for (const sim::JointId joint : state.rider_joints[p]) add_joint(joint);
    add_joint(state.seats[p]);
    hasher.add_u32(state.score[p]);
    hasher.add_u32(state.unseated[p]);
    hasher.add_u32(state.car_resets[p]);
    hasher.add_i32(state.respawn_ticks[p]);
    hasher.add_u8(state.last_hitter[p]);
    hasher.add_i32(state.hit_ticks[p]);
    hasher.add_i32(state.credit_ticks[p]);
    hasher.add_i32(state.charge_ticks[p]);
    hasher.add_i32(state.cooldown_ticks[p]);
    hasher.add_i32(state.upset_ticks[p]);
  }
  for (const sim::BodyId link : state.chain) add_body(link);
  add_body(state.ball);
  for (const sim::JointId joint : state.chain_joints) add_joint(joint);
  add_body(state.gantry);
}

Status JoustGame::validate_typed(const MatchSetup& setup, const JoustState& state) const {
  auto bad = [](const std::string& what) {
    return Status::Error(ErrorCode::kCorrupt, "joust state: " + what);
  };
  if (state.player_count != setup.player_count) return bad("player count differs from the match");
  if (state.player_count > kMaxPlayers) return bad("player count out of range");
  for (uint32_t p = 0; p < state.player_count; ++p) {
    if (state.respawn_ticks[p] < 0 || state.respawn_ticks[p] > kRespawnTicks) {
      return bad("respawn ticks out of range");
    }
    if (state.seats[p].is_null() != (state.respawn_ticks[p] > 0)) {
      return bad("seat and respawn countdown disagree");
    }
    if (state.last_hitter[p] > state.player_count) return bad("last hitter out of range");
    if (state.hit_ticks[p] < 0 || state.hit_ticks[p] > kHitMemoryTicks) {
      return bad("hit memory out of range");
    }
    if (state.credit_ticks[p] < 0 || state.credit_ticks[p] > kCreditTicks) {
      return bad("throw credit out of range");
    }
    if (state.charge_ticks[p] < 0 || state.charge_ticks[p] > kChargeTicks) {
      return bad("charge out of range");
    }
    if (state.cooldown_ticks[p] < 0 || state.cooldown_ticks[p] > kChargeCooldownTicks) {
      return bad("charge cooldown out of range");
    }
    if (state.upset_ticks[p] < 0 || state.upset_ticks[p] > kUpsetTicks) {
      return bad("upset ticks out of range");
    }
  }
  return Status::Ok();
}

}  // namespace rwd::game
