// SPDX-License-Identifier: MIT
// The joust's rules: driving and charging, the wrecking ball's pump, lance
// strikes that throw riders and score, cars put back after a fall or an
// upset, riders reseated; and the rules' state hashed and checked.
#include "rewind/game/joust_game.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "joust_layout.h"
#include "rewind/core/det_math.h"
#include "rewind/sim/vehicle3d.h"

namespace rwd::game {
namespace {

using namespace joust_detail;  // NOLINT: the layout's constants

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

bool fell(const sim::World3D& world, sim::BodyId id) {
  return !world.is_enabled(id) || world.position(id).y < kKillPlaneY;
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

Status JoustGame::apply_typed(Tick /*tick*/, std::span<const StickInput> inputs,
                              sim::World3D& world, JoustState& state) const {
  const std::array<sim::WheelDef3D, 4> wheel_defs = wheels();
  std::array<sim::WheelTelemetry3D, 4> telemetry{};
  const uint32_t players = std::min<uint32_t>(state.player_count, uint32_t(inputs.size()));
  for (uint32_t p = 0; p < players; ++p) {
    const sim::BodyId chassis = state.chassis[p];
    if (!world.is_valid(chassis) || !world.is_enabled(chassis)) continue;
    const StickInput& in = inputs[p];
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
  return Status::Ok();
}

Status JoustGame::after_step_typed(Tick /*tick*/, sim::World3D& world, JoustState& state) const {
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
  return Status::Ok();
}

void JoustGame::hash_typed(const JoustState& state, rwd::StateHasher& hasher) const {
  auto add_body = [&hasher](sim::BodyId id) { hasher.add_id(id); };
  auto add_joint = [&hasher](sim::JointId id) { hasher.add_id(id); };
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
