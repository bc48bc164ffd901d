// SPDX-License-Identifier: MIT
#include "rewind/game/arena_game.h"

#include <algorithm>
#include <string>

#include "rewind/core/state_hasher.h"
#include "rewind/fixed/fx_literal.h"
#include "rewind/fixed/trig.h"

namespace rwd::game {
namespace {

using fixed::Fx;
using fixed::Vec2;
using sim2d::BodyDef2D;
using sim2d::BodyId2D;
using sim2d::BodyKind2D;
using sim2d::World2D;
using namespace fixed::literals;

constexpr Fx kHalfWidth = 12_fx;  // m, inner half extents of the arena
constexpr Fx kHalfHeight = 8_fx;
constexpr Fx kWallHalf = 0.5_fx;  // m, wall half thickness
constexpr Fx kGoalHalf = 2_fx;    // m, half the mouth of a goal
constexpr Fx kDiscRadius = 0.5_fx;
constexpr Fx kDiscDensity = 4_fx;  // heavier than a crate, so a disc shoves
constexpr Fx kCrateHalf = 0.4_fx;
constexpr Fx kMaxSpeed = 6_fx;       // m/s at full deflection
constexpr Fx kSteerBlend = 0.15_fx;  // share of the velocity error closed per tick
constexpr Fx kDashSpeed = 9_fx;      // m/s added by a dash
constexpr int32_t kDashCooldownTicks = 45;
constexpr Fx kSpinnerSpeed = 1.5_fx;  // rad/s
constexpr uint32_t kCrates = 12;
constexpr uint32_t kLayerWorld = 1u << 0;
constexpr uint32_t kLayerDisc = 1u << 1;
constexpr uint64_t kTagDisc = 0x100;
constexpr uint64_t kTagCrate = 0x200;
constexpr uint64_t kTagGoal = 0x300;

BodyId2D create(World2D& world, const BodyDef2D& def) {
  Result<BodyId2D> id = world.create_body(def);
  return id.ok() ? *id : BodyId2D{};
}

BodyDef2D wall(Vec2 centre, Fx half_width, Fx half_height) {
  BodyDef2D def;
  def.kind = BodyKind2D::kStatic;
  def.shape = *sim2d::make_box(half_width, half_height);
  def.position = centre;
  def.material.friction = 0.3_fx;
  def.material.restitution = 0.3_fx;
  def.layer = kLayerWorld;
  return def;
}

// Spawn points on an ellipse inside the arena, evenly spaced by angle; the
// angle's sine and cosine come from the fixed-point CORDIC, so every
// machine places discs on the same bits.
Vec2 spawn_point(uint32_t player, uint32_t player_count) {
  const Fx angle = Fx::two_pi() * static_cast<int32_t>(player) / static_cast<int32_t>(player_count);
  const fixed::SinCos sc = fixed::sin_cos(angle);
  return {sc.cos * (kHalfWidth - 2_fx), sc.sin * (kHalfHeight - 2_fx)};
}

// Crates start in a 4 x 3 block left and right of the spinner; a scored
// crate comes back at its own start, so two never share a spot.
Vec2 crate_home(uint32_t crate) {
  const int32_t column = static_cast<int32_t>(crate % 4);
  const int32_t row = static_cast<int32_t>(crate / 4);
  const Fx x = (column < 2 ? -6_fx : 4_fx) + Fx(column % 2) * 2;
  return {x, Fx(row - 1) * 2};
}

bool tagged(uint64_t tag, uint64_t base, uint32_t count) {
  return tag >= base && tag < base + count;
}

}  // namespace

sim2d::World2DConfig ArenaGame::world_config() const {
  sim2d::World2DConfig config;
  config.gravity = {};  // top-down: the floor's drag is each body's damping
  config.tick_hz = 60;
  config.substeps = 4;
  config.bounds_lower = {-100_fx, -100_fx};
  config.bounds_upper = {100_fx, 100_fx};
  return config;
}

Status ArenaGame::build_typed(const MatchSetup& setup, World2D& world, ArenaState& state) const {
  state.player_count = setup.player_count;
  const Fx outer_x = kHalfWidth + kWallHalf;
  const Fx outer_y = kHalfHeight + kWallHalf;
  // Top and bottom walls, and the end walls in two pieces around each goal.
  create(world, wall({Fx(), outer_y}, kHalfWidth + 2 * kWallHalf, kWallHalf));
  create(world, wall({Fx(), -outer_y}, kHalfWidth + 2 * kWallHalf, kWallHalf));
  const Fx piece_half = (kHalfHeight - kGoalHalf) / 2;
  const Fx piece_y = kGoalHalf + piece_half;
  for (const Fx x : {outer_x, -outer_x}) {
    create(world, wall({x, piece_y}, kWallHalf, piece_half));
    create(world, wall({x, -piece_y}, kWallHalf, piece_half));
  }
  // Goals: a pocket behind each mouth, walled at the back and the sides,
  // with a sensor filling it.
  for (uint32_t g = 0; g < 2; ++g) {
    const Fx side = g == 0 ? -1_fx : 1_fx;
    BodyDef2D goal = wall({side * (kHalfWidth + 1.5_fx), Fx()}, 1_fx, kGoalHalf);
    goal.sensor = true;
    goal.user_data = kTagGoal + g;
    state.goals[g] = create(world, goal);
    create(world, wall({side * (kHalfWidth + 3_fx), Fx()}, kWallHalf, kGoalHalf + 2 * kWallHalf));
    for (const Fx y : {kGoalHalf + kWallHalf, -kGoalHalf - kWallHalf}) {
      create(world, wall({side * (kHalfWidth + 1.75_fx), y}, 1.75_fx, kWallHalf));
    }
  }
  // Two posts, and the spinning bar between them (kinematic: it sweeps
  // whatever it meets and nothing slows it).
  for (const Fx y : {4_fx, -4_fx}) {
    BodyDef2D post;
    post.kind = BodyKind2D::kStatic;
    post.shape = *sim2d::make_circle(0.75_fx);
    post.position = {Fx(), y};
    post.layer = kLayerWorld;
    create(world, post);
  }
  BodyDef2D bar;
  bar.kind = BodyKind2D::kKinematic;
  bar.shape = *sim2d::make_box(2.5_fx, 0.25_fx);
  bar.angular_velocity = kSpinnerSpeed;
  bar.layer = kLayerWorld;
  state.spinner = create(world, bar);

  // Jointed obstacles: a free turnstile hinged at its middle, and a gate
  // hinged at one end that swings up to a quarter turn either way and
  // springs back shut.
  {
    BodyDef2D turnstile;
    turnstile.shape = *sim2d::make_box(1.5_fx, 0.15_fx);
    turnstile.position = {-4_fx, 6_fx};
    turnstile.density = 2_fx;
    turnstile.angular_damping = 1_fx;
    turnstile.layer = kLayerWorld;
    // Each hinge's pin is a small static post (joined bodies do not collide).
    auto pin = [&](Vec2 at) {
      BodyDef2D post;
      post.kind = BodyKind2D::kStatic;
      post.shape = *sim2d::make_circle(0.2_fx);
      post.position = at;
      post.layer = kLayerWorld;
      return create(world, post);
    };
    sim2d::JointDef2D hinge;
    hinge.type = sim2d::JointType2D::kRevolute;
    hinge.body_a = pin(turnstile.position);
    hinge.body_b = create(world, turnstile);
    hinge.anchor_a = turnstile.position;
    hinge.anchor_b = turnstile.position;
    (void)world.create_joint(hinge);

    BodyDef2D gate;
    gate.shape = *sim2d::make_box(1.5_fx, 0.15_fx);
    gate.position = {4_fx, -6_fx};
    gate.density = 2_fx;
    gate.layer = kLayerWorld;
    sim2d::JointDef2D gate_hinge = hinge;
    gate_hinge.body_b = create(world, gate);
    gate_hinge.anchor_a = {2.5_fx, -6_fx};
    gate_hinge.anchor_b = gate_hinge.anchor_a;
    gate_hinge.body_a = pin(gate_hinge.anchor_a);
    gate_hinge.enable_limit = true;
    gate_hinge.lower = -Fx::half_pi();
    gate_hinge.upper = Fx::half_pi();
    gate_hinge.enable_spring = true;
    gate_hinge.hertz = 1_fx;
    gate_hinge.damping_ratio = 0.5_fx;
    (void)world.create_joint(gate_hinge);
  }

  state.crate_count = kCrates;
  for (uint32_t c = 0; c < kCrates; ++c) {
    BodyDef2D def;
    def.shape = *sim2d::make_box(kCrateHalf, kCrateHalf);
    def.position = crate_home(c);
    def.linear_damping = 2_fx;
    def.angular_damping = 2_fx;
    def.material.friction = 0.4_fx;
    def.layer = kLayerWorld;
    def.user_data = kTagCrate + c;
    state.crates[c] = create(world, def);
  }
  for (uint32_t p = 0; p < setup.player_count; ++p) {
    BodyDef2D def;
    def.shape = *sim2d::make_circle(kDiscRadius);
    def.position = spawn_point(p, setup.player_count);
    def.density = kDiscDensity;
    def.linear_damping = 1_fx;
    def.angular_damping = 3_fx;
    def.material.friction = 0.2_fx;
    def.material.restitution = 0.2_fx;
    def.layer = kLayerDisc;
    def.user_data = kTagDisc + p;
    state.discs[p] = create(world, def);
  }
  return Status::Ok();
}

Status ArenaGame::apply_typed(Tick /*tick*/, std::span<const StickInput> inputs, World2D& world,
                              ArenaState& state) const {
  const uint32_t players = std::min<uint32_t>(state.player_count, uint32_t(inputs.size()));
  for (uint32_t p = 0; p < players; ++p) {
    const BodyId2D disc = state.discs[p];
    if (!world.is_valid(disc)) continue;
    const StickInput& in = inputs[p];
    const Vec2 stick{Fx::ratio(std::clamp<int>(in.axis_x, -kAxisMax, kAxisMax), kAxisMax),
                     Fx::ratio(std::clamp<int>(in.axis_y, -kAxisMax, kAxisMax), kAxisMax)};
    const Vec2 v = world.linear_velocity(disc);
    // Steer toward the stick's velocity by an impulse, so what the disc
    // hits still pushes back.
    Vec2 dv = (stick * kMaxSpeed - v) * kSteerBlend;
    if (state.dash_cooldown[p] > 0) {
      --state.dash_cooldown[p];
    } else if ((in.buttons & kArenaDash) && !(stick == Vec2{})) {
      dv += fixed::normalized(stick) * kDashSpeed;
      state.dash_cooldown[p] = kDashCooldownTicks;
    }
    if (!(dv == Vec2{})) {
      (void)world.apply_linear_impulse(disc, dv * world.mass(disc).to_fx(), world.position(disc));
    }
  }
  return Status::Ok();
}

Status ArenaGame::after_step_typed(Tick /*tick*/, World2D& world, ArenaState& state) const {
  // Events are ordered by body index, so when two discs touch a crate in
  // one tick the later in that order is its last toucher on every machine.
  for (const sim2d::ContactEvent2D& event : world.events()) {
    if (event.type == sim2d::ContactEventType2D::kExit) continue;
    const uint64_t ua = world.user_data(event.a);
    const uint64_t ub = world.user_data(event.b);
    if (tagged(ua, kTagDisc, state.player_count) && tagged(ub, kTagCrate, state.crate_count)) {
      state.crate_last_toucher[ub - kTagCrate] = static_cast<uint8_t>(ua - kTagDisc + 1);
    }
    if (tagged(ub, kTagDisc, state.player_count) && tagged(ua, kTagCrate, state.crate_count)) {
      state.crate_last_toucher[ua - kTagCrate] = static_cast<uint8_t>(ub - kTagDisc + 1);
    }
  }
  // A crate that entered a goal scores for its last toucher and goes home.
  for (const sim2d::ContactEvent2D& event : world.events()) {
    if (event.type != sim2d::ContactEventType2D::kEnter || !event.sensor) continue;
    const uint64_t ua = world.user_data(event.a);
    const uint64_t ub = world.user_data(event.b);
    const uint64_t crate_tag = tagged(ua, kTagCrate, state.crate_count) ? ua : ub;
    const uint64_t goal_tag = crate_tag == ua ? ub : ua;
    if (!tagged(crate_tag, kTagCrate, state.crate_count) || !tagged(goal_tag, kTagGoal, 2))
      continue;
    const uint32_t crate = static_cast<uint32_t>(crate_tag - kTagCrate);
    if (state.crate_last_toucher[crate] != 0) ++state.score[state.crate_last_toucher[crate] - 1];
    state.crate_last_toucher[crate] = 0;
    ++state.goals_scored;
    (void)world.set_transform(state.crates[crate], crate_home(crate), Fx());
    (void)world.set_linear_velocity(state.crates[crate], {});
    (void)world.set_angular_velocity(state.crates[crate], Fx());
  }
  // Anything the engine stopped at the world bounds comes back home.
  for (uint32_t p = 0; p < state.player_count; ++p) {
    if (world.is_valid(state.discs[p]) && !world.is_enabled(state.discs[p])) {
      (void)world.set_transform(state.discs[p], spawn_point(p, state.player_count), Fx());
      (void)world.set_enabled(state.discs[p], true);
    }
  }
  for (uint32_t c = 0; c < state.crate_count; ++c) {
    if (world.is_valid(state.crates[c]) && !world.is_enabled(state.crates[c])) {
      (void)world.set_transform(state.crates[c], crate_home(c), Fx());
      (void)world.set_enabled(state.crates[c], true);
    }
  }
  return Status::Ok();
}

void ArenaGame::hash_typed(const ArenaState& state, rwd::StateHasher& hasher) const {
  hasher.add_u32(state.player_count);
  hasher.add_u32(state.crate_count);
  for (uint32_t p = 0; p < state.player_count; ++p) {
    hasher.add_id(state.discs[p]);
    hasher.add_u32(state.score[p]);
    hasher.add_i32(state.dash_cooldown[p]);
  }
  for (uint32_t c = 0; c < state.crate_count; ++c) {
    hasher.add_id(state.crates[c]);
    hasher.add_u8(state.crate_last_toucher[c]);
  }
  for (const BodyId2D& goal : state.goals) {
    hasher.add_id(goal);
  }
  hasher.add_id(state.spinner);
  hasher.add_u32(state.goals_scored);
}

Status ArenaGame::validate_typed(const MatchSetup& setup, const ArenaState& state) const {
  auto bad = [](const std::string& what) {
    return Status::Error(ErrorCode::kCorrupt, "arena state: " + what);
  };
  if (state.player_count != setup.player_count) return bad("player count differs from the match");
  if (state.crate_count > kArenaMaxCrates) return bad("crate count out of range");
  for (uint32_t p = 0; p < state.player_count; ++p) {
    if (state.dash_cooldown[p] < 0 || state.dash_cooldown[p] > kDashCooldownTicks) {
      return bad("dash cooldown out of range");
    }
  }
  for (uint32_t c = 0; c < state.crate_count; ++c) {
    if (state.crate_last_toucher[c] > state.player_count) return bad("crate toucher out of range");
  }
  return Status::Ok();
}

}  // namespace rwd::game
