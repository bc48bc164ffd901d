// SPDX-License-Identifier: MIT
#include "tag_game.h"

#include <algorithm>
#include <cstddef>
#include <memory>
#include <string>

#include <rewind/core/det_math.h>
#include <rewind/core/splitmix64.h>
#include <rewind/game/game_registry.h>

namespace tag {
namespace {

using rwd::sim::BodyId;
using rwd::sim::Vec3;

constexpr float kYardHalf = 8.0f;      // m, inner half width of the yard
constexpr float kBallRadius = 0.5f;    // m
constexpr float kRunSpeed = 5.0f;      // m/s at full deflection
constexpr float kItSpeed = 5.5f;       // m/s: "it" is a little faster
constexpr float kSteerGain = 6.0f;     // 1/s: how fast a ball follows the stick
constexpr float kSprint = 1.4f;        // speed factor while sprinting
constexpr uint64_t kTagBall = 0x7A60;  // user_data of player p's ball: kTagBall + p

rwd::sim::BodyDef wall(Vec3 centre, Vec3 half) {
  rwd::sim::BodyDef def;
  def.kind = rwd::sim::BodyKind::kStatic;
  def.shape = rwd::sim::Shape::make_box(half);
  def.position = centre;
  def.contact_events = false;  // the rules read ball-against-ball contacts only
  return def;
}

// Balls start on a circle; det_cos/det_sin give the same bits on every
// machine, where std::cos may not.
Vec3 start_point(uint32_t player, uint32_t players) {
  const float angle = 2.0f * rwd::kPi * static_cast<float>(player) / static_cast<float>(players);
  const float r = kYardHalf - 2.0f;
  return {r * rwd::det_cos(angle), kBallRadius, r * rwd::det_sin(angle)};
}

bool is_ball(uint64_t user_data, uint32_t players) {
  return user_data >= kTagBall && user_data < kTagBall + players;
}

}  // namespace

rwd::sim::WorldConfig TagGame::world_config() const {
  rwd::sim::WorldConfig config;
  config.tick_seconds = 1.0f / 60.0f;
  config.substeps = 4;
  return config;
}

rwd::Status TagGame::build_typed(const rwd::game::MatchSetup& setup, rwd::sim::World3D& world,
                                 TagState& state) const {
  state.player_count = setup.player_count;
  const rwd::sim::BodyDef yard[] = {
      wall({0, -0.5f, 0}, {kYardHalf + 1, 0.5f, kYardHalf + 1}),
      wall({kYardHalf + 0.5f, 1, 0}, {0.5f, 1, kYardHalf + 1}),
      wall({-kYardHalf - 0.5f, 1, 0}, {0.5f, 1, kYardHalf + 1}),
      wall({0, 1, kYardHalf + 0.5f}, {kYardHalf, 1, 0.5f}),
      wall({0, 1, -kYardHalf - 0.5f}, {kYardHalf, 1, 0.5f}),
  };
  // An error here (a bad body definition) ends the match with its message
  // instead of hosting a broken yard.
  for (const rwd::sim::BodyDef& def : yard) {
    if (rwd::Result<BodyId> id = world.create_body(def); !id.ok()) return id.status();
  }
  for (uint32_t p = 0; p < setup.player_count; ++p) {
    rwd::sim::BodyDef def;
    def.shape = rwd::sim::Shape::make_sphere(kBallRadius);
    def.position = start_point(p, setup.player_count);
    def.density = 1000.0f;
    def.angular_damping = 2.0f;
    def.user_data = kTagBall + p;
    rwd::Result<BodyId> ball = world.create_body(def);
    if (!ball.ok()) return ball.status();
    state.balls[p] = *ball;
  }
  // The seed picks who starts as "it", the same way on every machine.
  state.it = static_cast<uint32_t>(rwd::splitmix64_once(setup.seed) % setup.player_count);
  return rwd::Status::Ok();
}

rwd::Status TagGame::apply_typed(rwd::Tick /*tick*/, std::span<const TagInput> inputs,
                                 rwd::sim::World3D& world, TagState& state) const {
  const float blend = std::min(1.0f, kSteerGain * world.config().tick_seconds);
  const uint32_t players = std::min<uint32_t>(state.player_count, uint32_t(inputs.size()));
  for (uint32_t p = 0; p < players; ++p) {
    const BodyId ball = state.balls[p];
    if (!world.is_valid(ball)) continue;
    // Rewind has checked every input against input_spec(): the fields are
    // within their ranges here.
    const TagInput& in = inputs[p];
    const float top = (p == state.it ? kItSpeed : kRunSpeed) * (in.sprint != 0 ? kSprint : 1.0f);
    const float speed = top * static_cast<float>(in.throttle) / 100.0f;
    const float heading = static_cast<float>(in.heading) * (rwd::kPi / 1800.0f);
    const float ax = rwd::det_cos(heading);
    const float az = rwd::det_sin(heading);
    const Vec3 v = world.linear_velocity(ball);
    const Vec3 dv{(ax * speed - v.x) * blend, 0.0f, (az * speed - v.z) * blend};
    (void)world.apply_linear_impulse(ball, dv * world.mass(ball), world.position(ball));
  }
  return rwd::Status::Ok();
}

rwd::Status TagGame::after_step_typed(rwd::Tick /*tick*/, rwd::sim::World3D& world,
                                      TagState& state) const {
  if (state.tag_cooldown > 0) --state.tag_cooldown;
  // Events come in a fixed order (by body index), so when "it" touches two
  // balls in one tick every machine tags the same one: the first.
  for (const rwd::sim::ContactEvent& event : world.events()) {
    if (state.tag_cooldown > 0) break;
    if (event.type != rwd::sim::ContactEventType::kEnter) continue;
    const uint64_t a = world.user_data(event.a);
    const uint64_t b = world.user_data(event.b);
    if (!is_ball(a, state.player_count) || !is_ball(b, state.player_count)) continue;
    const uint32_t pa = static_cast<uint32_t>(a - kTagBall);
    const uint32_t pb = static_cast<uint32_t>(b - kTagBall);
    if (pa != state.it && pb != state.it) continue;
    state.it = pa == state.it ? pb : pa;
    state.tag_cooldown = kTagCooldownTicks;
    ++state.tags;
  }
  for (uint32_t p = 0; p < state.player_count; ++p) {
    if (p != state.it) ++state.points[p];
  }
  return rwd::Status::Ok();
}

void TagGame::hash_typed(const TagState& state, rwd::StateHasher& hasher) const {
  hasher.add_u32(state.player_count);
  hasher.add_u32(state.it);
  hasher.add_i32(state.tag_cooldown);
  hasher.add_u32(state.tags);
  for (uint32_t p = 0; p < state.player_count; ++p) {
    hasher.add_id(state.balls[p]);
    hasher.add_u32(state.points[p]);
  }
}

rwd::Status TagGame::validate_typed(const rwd::game::MatchSetup& setup,
                                    const TagState& state) const {
  auto bad = [](const std::string& what) {
    return rwd::Status::Error(rwd::ErrorCode::kCorrupt, "tag state: " + what);
  };
  if (state.player_count != setup.player_count) return bad("player count differs from the match");
  if (state.it >= state.player_count) return bad("'it' is not a player");
  if (state.tag_cooldown < 0 || state.tag_cooldown > kTagCooldownTicks) {
    return bad("tag cooldown out of range");
  }
  return rwd::Status::Ok();
}

namespace {

rwd::PlayerInput predict_tag_input(const rwd::PlayerInput& newest) {
  TagInput input = newest.as<TagInput>();
  input.sprint = 0;
  return rwd::PlayerInput::of(input);
}

}  // namespace

const rwd::InputSpec& TagGame::input_spec() const {
  static constexpr rwd::InputField kFields[] = {
      {"heading", rwd::InputFieldType::kI16, offsetof(TagInput, heading), 0, 3599},
      {"throttle", rwd::InputFieldType::kU8, offsetof(TagInput, throttle), 0, 100},
      {"sprint", rwd::InputFieldType::kU8, offsetof(TagInput, sprint), 0, 1},
  };
  static constexpr rwd::InputSpec kSpec{"tag", sizeof(TagInput), kFields, &predict_tag_input};
  return kSpec;
}

rwd::PlayerInput TagGame::bot_input(uint64_t seed, uint32_t player, rwd::Tick tick) const {
  // Each bot runs a wide circle of its own size and direction, and every
  // two seconds picks a new one: enough for "it" to catch someone. Integer
  // steps, so the bot needs no trig.
  const uint64_t leg =
      rwd::splitmix64_once(seed ^ rwd::splitmix64_once(player) ^ static_cast<uint64_t>(tick / 120));
  const int32_t turn = (leg & 1) ? 1 : -1;
  const int32_t start = static_cast<int32_t>(leg % 3600);
  TagInput input;
  input.heading = static_cast<int16_t>(((start + turn * 10 * (tick % 360)) % 3600 + 3600) % 3600);
  input.throttle = static_cast<uint8_t>(70 + (leg >> 12) % 31);
  input.sprint = (tick % 120) < 15 ? 1 : 0;
  return rwd::PlayerInput::of(input);
}

rwd::Status register_tag_game() {
  return rwd::game::register_game("tag", [] { return std::make_unique<TagGame>(); });
}

}  // namespace tag
