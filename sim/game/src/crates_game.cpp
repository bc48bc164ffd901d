// SPDX-License-Identifier: MIT
#include "rewind/game/crates_game.h"

#include <algorithm>

#include "rewind/core/det_math.h"

namespace rwd::game {
namespace {

constexpr float kArenaHalf = 10.0f;     // m, inner half width of the arena
constexpr float kWallHeight = 8.0f;     // m, up to the roof
constexpr float kCrateHalf = 0.4f;      // m
constexpr int kTowerLevels = 4;         // 2x2 crates per level
constexpr float kPusherRadius = 0.5f;   // m
constexpr float kPusherDensity = 3000;  // kg/m^3: heavy enough to shove a crate
constexpr float kMaxSpeed = 6.0f;       // m/s at full deflection
constexpr float kSteerGain = 8.0f;      // 1/s: how fast velocity tracks the stick
constexpr float kJumpSpeed = 5.0f;      // m/s
constexpr float kDashSpeed = 10.0f;     // m/s
constexpr int32_t kCooldownTicks = 30;
constexpr float kScoreRing = 4.0f;  // m from the centre
// Below this height a body has left the arena for good and is respawned.
constexpr float kKillPlaneY = -10.0f;
// The world ends well beyond the arena: a body flung that far is disabled
// by the engine (BodyEventType::kLeftBounds) and respawned like a fall.
constexpr float kWorldHalf = 200.0f;
constexpr uint32_t kLayerWorld = 1u << 0;
constexpr uint32_t kLayerPusher = 1u << 1;
constexpr uint64_t kTagPusher = 0x100;
constexpr uint64_t kTagCrate = 0x200;

sim::BodyDef static_box(sim::Vec3 centre, sim::Vec3 half) {
  sim::BodyDef def;
  def.kind = sim::BodyKind::kStatic;
  def.shape = sim::Shape::make_box(half);
  def.position = centre;
  def.material.friction = 0.8f;
  def.layer = kLayerWorld;
  // No rule reads the arena's contacts: the pushers' own events are all
  // the game needs (after_step_typed).
  def.contact_events = false;
  return def;
}

// Spawn points spread evenly on a circle; the angle comes from det_cos/det_sin
// so every machine places pushers on the same bits.
sim::Vec3 spawn_point(uint32_t player, uint32_t player_count) {
  float angle = 2.0f * rwd::kPi * static_cast<float>(player) / static_cast<float>(player_count);
  float r = kArenaHalf - 2.0f;
  return {r * rwd::det_cos(angle), kPusherRadius + 0.01f, r * rwd::det_sin(angle)};
}

// Where crate c reappears after a fall: above the tower (whose top is at
// 3.2 m) and below the roof, spread so that two crates respawned on the same
// tick never share a spot.
sim::Vec3 crate_respawn_point(uint32_t crate) {
  const float step = 2.0f * kCrateHalf + 0.05f;
  return {(static_cast<float>(crate % 4) - 1.5f) * step,
          3.7f + static_cast<float>(crate / 4 % 4) * step, 0.0f};
}

bool fell(const sim::World3D& world, sim::BodyId id) {
  return world.is_valid(id) && (!world.is_enabled(id) || world.position(id).y < kKillPlaneY);
}

// Puts a body back into play at `where`, at rest.
void respawn(sim::World3D& world, sim::BodyId id, sim::Vec3 where) {
  (void)world.set_transform(id, where, sim::Quat{});
  (void)world.set_enabled(id, true);
  (void)world.set_linear_velocity(id, {});
  (void)world.set_angular_velocity(id, {});
}

}  // namespace

sim::WorldConfig CratesGame::world_config() const {
  sim::WorldConfig config;
  config.tick_seconds = 1.0f / 60.0f;
  config.substeps = 4;
  config.bounds_lower = {-kWorldHalf, -kWorldHalf, -kWorldHalf};
  config.bounds_upper = {kWorldHalf, kWorldHalf, kWorldHalf};
  return config;
}

Status CratesGame::build_typed(const MatchSetup& setup, sim::World3D& world,
                               CratesState& state) const {
  state.player_count = setup.player_count;

  // Arena: floor with its top at y = 0, four walls and a roof: a closed box.
  // The x walls run the floor's full length so the corners are closed; the
  // roof stops pushers squeezed up a corner pile-up (or jumping off one)
  // from going over the walls.
  const float wall_y = kWallHeight * 0.5f;
  const sim::BodyDef arena[] = {
      static_box({0, -0.5f, 0}, {kArenaHalf + 1, 0.5f, kArenaHalf + 1}),
      static_box({kArenaHalf + 0.5f, wall_y, 0}, {0.5f, wall_y, kArenaHalf + 1}),
      static_box({-kArenaHalf - 0.5f, wall_y, 0}, {0.5f, wall_y, kArenaHalf + 1}),
      static_box({0, wall_y, kArenaHalf + 0.5f}, {kArenaHalf, wall_y, 0.5f}),
      static_box({0, wall_y, -kArenaHalf - 0.5f}, {kArenaHalf, wall_y, 0.5f}),
      static_box({0, kWallHeight + 0.5f, 0}, {kArenaHalf + 1, 0.5f, kArenaHalf + 1}),
  };
  for (const sim::BodyDef& def : arena) {
    if (Result<sim::BodyId> id = world.create_body(def); !id.ok()) return id.status();
  }

  // The tower: kTowerLevels levels of 2x2 crates, resting exactly on each other.
  uint32_t crate = 0;
  for (int level = 0; level < kTowerLevels; ++level) {
    for (int i = 0; i < 4; ++i) {
      sim::BodyDef def;
      def.shape = sim::Shape::make_box({kCrateHalf, kCrateHalf, kCrateHalf});
      def.position = {(i & 1) ? kCrateHalf : -kCrateHalf, kCrateHalf + 2.0f * kCrateHalf * level,
                      (i & 2) ? kCrateHalf : -kCrateHalf};
      def.density = 300.0f;  // wood
      def.material.friction = 0.6f;
      def.layer = kLayerWorld;
      def.user_data = kTagCrate + crate;
      // A crate's contacts matter only with a pusher, and the pusher
      // reports those; crates against crates and the floor would be most
      // of the tick's events, read by nobody.
      def.contact_events = false;
      Result<sim::BodyId> id = world.create_body(def);
      if (!id.ok()) return id.status();
      state.crates[crate++] = *id;
    }
  }
  state.crate_count = crate;

  for (uint32_t p = 0; p < setup.player_count; ++p) {
    sim::BodyDef def;
    def.shape = sim::Shape::make_sphere(kPusherRadius);
    def.position = spawn_point(p, setup.player_count);
    def.density = kPusherDensity;
    def.angular_damping = 2.0f;
    def.material.friction = 0.4f;
    def.layer = kLayerPusher;
    def.user_data = kTagPusher + p;
    Result<sim::BodyId> id = world.create_body(def);
    if (!id.ok()) return id.status();
    state.pushers[p] = *id;
  }
  return Status::Ok();
}

Status CratesGame::apply_typed(Tick /*tick*/, std::span<const StickInput> inputs,
                               sim::World3D& world, CratesState& state) const {
  const float dt = world.config().tick_seconds;
  const uint32_t players = std::min<uint32_t>(state.player_count, uint32_t(inputs.size()));
  for (uint32_t p = 0; p < players; ++p) {
    const sim::BodyId pusher = state.pushers[p];
    if (!world.is_valid(pusher)) continue;
    const StickInput& in = inputs[p];
    const float ax = static_cast<float>(std::clamp<int>(in.axis_x, -kAxisMax, kAxisMax)) / kAxisMax;
    const float az = static_cast<float>(std::clamp<int>(in.axis_y, -kAxisMax, kAxisMax)) / kAxisMax;
    const float mass = world.mass(pusher);
    const sim::Vec3 v = world.linear_velocity(pusher);

    // Steer the horizontal velocity toward the stick with a first-order lag,
    // as an impulse so contacts still push back on the pusher.
    const sim::Vec3 target{ax * kMaxSpeed, 0.0f, az * kMaxSpeed};
    const float blend = std::min(1.0f, kSteerGain * dt);
    sim::Vec3 dv{(target.x - v.x) * blend, 0.0f, (target.z - v.z) * blend};

    if (state.cooldown_ticks[p] > 0) {
      --state.cooldown_ticks[p];
    } else if (in.buttons & (kCratesJump | kCratesDash)) {
      const sim::Vec3 pos = world.position(pusher);
      sim::QueryFilter ground;
      ground.layer_mask = kLayerWorld;
      const bool grounded =
          world.raycast({pos, {0, -1, 0}, kPusherRadius + 0.05f}, ground).has_value();
      if ((in.buttons & kCratesJump) && grounded) {
        dv.y = kJumpSpeed - v.y;
        state.cooldown_ticks[p] = kCooldownTicks;
      }
      if (in.buttons & kCratesDash) {
        const sim::Vec3 dir = sim::normalize_or_zero({ax, 0.0f, az});
        dv += dir * kDashSpeed;
        state.cooldown_ticks[p] = kCooldownTicks;
      }
    }
    if (!(dv == sim::Vec3{})) {
      (void)world.apply_linear_impulse(pusher, dv * mass, world.position(pusher));
    }
  }
  return Status::Ok();
}

Status CratesGame::after_step_typed(Tick /*tick*/, sim::World3D& world, CratesState& state) const {
  // Remember who touched each crate last; events are ordered by body index,
  // so when two pushers touch one crate in the same tick the later in that
  // order wins on every machine alike.
  for (const sim::ContactEvent& event : world.events()) {
    if (event.type == sim::ContactEventType::kExit) continue;
    const uint64_t ua = world.user_data(event.a);
    const uint64_t ub = world.user_data(event.b);
    const bool a_pusher = ua >= kTagPusher && ua < kTagPusher + kMaxPlayers;
    const bool b_pusher = ub >= kTagPusher && ub < kTagPusher + kMaxPlayers;
    const bool a_crate = ua >= kTagCrate && ua < kTagCrate + state.crate_count;
    const bool b_crate = ub >= kTagCrate && ub < kTagCrate + state.crate_count;
    if (a_pusher && b_crate)
      state.crate_last_toucher[ub - kTagCrate] = uint8_t(ua - kTagPusher + 1);
    if (b_pusher && a_crate)
      state.crate_last_toucher[ua - kTagCrate] = uint8_t(ub - kTagPusher + 1);
  }
  // What left the arena comes back: pushers at their spawn point, crates
  // above the centre. Both the kill plane and the engine's bounds (a body
  // flung out of the world is disabled where it crossed) lead here, in
  // player and crate order, so every machine respawns alike.
  for (uint32_t p = 0; p < state.player_count; ++p) {
    if (!fell(world, state.pushers[p])) continue;
    respawn(world, state.pushers[p], spawn_point(p, state.player_count));
    ++state.falls[p];
  }
  for (uint32_t c = 0; c < state.crate_count; ++c) {
    if (!fell(world, state.crates[c])) continue;
    respawn(world, state.crates[c], crate_respawn_point(c));
    ++state.crate_respawns;
  }
  // A crate resting outside the centre ring scores once for its last toucher.
  for (uint32_t c = 0; c < state.crate_count; ++c) {
    if (state.crate_scored[c] || state.crate_last_toucher[c] == 0) continue;
    const sim::Vec3 pos = world.position(state.crates[c]);
    if (pos.x * pos.x + pos.z * pos.z > kScoreRing * kScoreRing) {
      state.crate_scored[c] = 1;
      ++state.score[state.crate_last_toucher[c] - 1];
    }
  }
  return Status::Ok();
}

void CratesGame::hash_typed(const CratesState& state, rwd::StateHasher& hasher) const {
  hasher.add_u32(state.player_count);
  hasher.add_u32(state.crate_count);
  for (uint32_t p = 0; p < state.player_count; ++p) {
    hasher.add_id(state.pushers[p]);
    hasher.add_u32(state.score[p]);
    hasher.add_i32(state.cooldown_ticks[p]);
    hasher.add_u32(state.falls[p]);
  }
  hasher.add_u32(state.crate_respawns);
  for (uint32_t c = 0; c < state.crate_count; ++c) {
    hasher.add_id(state.crates[c]);
    hasher.add_u8(state.crate_last_toucher[c]);
    hasher.add_u8(state.crate_scored[c]);
  }
}

Status CratesGame::validate_typed(const MatchSetup& setup, const CratesState& state) const {
  auto bad = [](const std::string& what) {
    return Status::Error(ErrorCode::kCorrupt, "crates state: " + what);
  };
  if (state.player_count != setup.player_count) return bad("player count differs from the match");
  if (state.crate_count > state.crates.size()) return bad("crate count out of range");
  for (uint32_t p = 0; p < state.player_count; ++p) {
    if (state.cooldown_ticks[p] < 0 || state.cooldown_ticks[p] > kCooldownTicks) {
      return bad("cooldown out of range");
    }
  }
  for (uint32_t c = 0; c < state.crate_count; ++c) {
    if (state.crate_last_toucher[c] > state.player_count) return bad("crate toucher out of range");
    if (state.crate_scored[c] > 1) return bad("crate scored flag out of range");
  }
  return Status::Ok();
}

}  // namespace rwd::game
