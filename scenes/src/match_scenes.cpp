// SPDX-License-Identifier: MIT
// The sample match's world as a scene: what a rollback server re-simulates
// many times a tick, measured on every engine like the other scenes.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "scene_factories.h"
#include "scene_kit.h"

namespace rwd::scenes {
namespace {

/// The `crates` sample match with `players` pushers: a closed arena (a
/// 20 m floor, four 8 m walls and a roof), a tower of sixteen 0.8 m wooden
/// crates in the middle, and one heavy 0.5 m ball per player, spawned on a
/// circle and driven by scripted sticks as the game drives them (each tick
/// an impulse steers the ball's horizontal velocity toward the stick's at a
/// first-order lag). Every 1.5 s each stick changes: a third of the
/// players charge the tower, the others run off in their own direction,
/// so the balls knock the tower down, roll into each other and the walls.
/// The bodies, sizes, densities, frictions and damping are the game's
/// (sim/game/src/crates_game.cpp); 10 s. Nothing may leave the arena and
/// nothing may be flung faster than a charge sends it.
class CratesScene final : public kit::SpecScene {
 public:
  explicit CratesScene(int players) : SpecScene(players) {
    const auto wall = [&](Vec3 centre, Vec3 half) {
      BodySpec s = kit::fixed(kit::box(centre, half, 0.8f));
      add(s);
    };
    const float wall_y = 0.5f * kWallHeight;
    wall({0.0f, -0.5f, 0.0f}, {kArenaHalf + 1.0f, 0.5f, kArenaHalf + 1.0f});
    wall({kArenaHalf + 0.5f, wall_y, 0.0f}, {0.5f, wall_y, kArenaHalf + 1.0f});
    wall({-kArenaHalf - 0.5f, wall_y, 0.0f}, {0.5f, wall_y, kArenaHalf + 1.0f});
    wall({0.0f, wall_y, kArenaHalf + 0.5f}, {kArenaHalf, wall_y, 0.5f});
    wall({0.0f, wall_y, -kArenaHalf - 0.5f}, {kArenaHalf, wall_y, 0.5f});
    wall({0.0f, kWallHeight + 0.5f, 0.0f}, {kArenaHalf + 1.0f, 0.5f, kArenaHalf + 1.0f});
    first_moving_ = specs_.size();
    for (int level = 0; level < 4; ++level) {
      for (int i = 0; i < 4; ++i) {
        const Vec3 p{(i & 1) ? kCrateHalf : -kCrateHalf,
                     kCrateHalf + 2.0f * kCrateHalf * static_cast<float>(level),
                     (i & 2) ? kCrateHalf : -kCrateHalf};
        BodySpec crate = kit::box(p, {kCrateHalf, kCrateHalf, kCrateHalf}, 0.6f);
        crate.density = 300.0f;
        add(crate);
      }
    }
    first_pusher_ = specs_.size();
    for (int p = 0; p < players; ++p) {
      const float angle =
          2.0f * kit::kPi * static_cast<float>(p) / static_cast<float>(std::max(players, 1));
      const float r = kArenaHalf - 2.0f;
      BodySpec ball = kit::sphere({r * std::cos(angle), kPusherRadius + 0.01f, r * std::sin(angle)},
                                  kPusherRadius, 0.4f);
      ball.density = kPusherDensity;
      ball.angular_damping = 2.0f;
      add(ball);
    }
  }
  std::string_view name() const override { return "crates"; }
  WorldSpec world() const override {
    WorldSpec w;
    w.bounds_lower = {-200.0f, -200.0f, -200.0f};
    w.bounds_upper = {200.0f, 200.0f, 200.0f};
    return w;
  }
  Tick ticks() const override { return 600; }
  void before_step(Tick tick, Engine& engine) override {
    const float mass =
        kPusherDensity * 4.0f / 3.0f * kit::kPi * kPusherRadius * kPusherRadius * kPusherRadius;
    const float blend = std::min(1.0f, kSteerGain / 60.0f);
    const int phase = static_cast<int>(tick / kPhaseTicks);
    for (size_t k = first_pusher_; k < handles_.size(); ++k) {
      const BodyHandle ball = handles_[k];
      if (!engine.enabled(ball)) continue;
      const int player = static_cast<int>(k - first_pusher_);
      const Vec3 at = engine.position(ball);
      Vec3 stick{};
      if ((player + phase) % 3 == 0) {
        // Charge the tower.
        const float d = std::sqrt(at.x * at.x + at.z * at.z);
        if (d > 1e-3f) stick = {-at.x / d, 0.0f, -at.z / d};
      } else {
        // Off in a direction of this player's and phase's own.
        const float turns = 0.37f * static_cast<float>(player) + 0.61f * static_cast<float>(phase);
        const float a = 2.0f * kit::kPi * (turns - std::floor(turns));
        stick = {std::cos(a), 0.0f, std::sin(a)};
      }
      const Vec3 v = engine.linear_velocity(ball);
      const Vec3 dv{(stick.x * kMaxSpeed - v.x) * blend, 0.0f, (stick.z * kMaxSpeed - v.z) * blend};
      engine.apply_impulse(ball, {dv.x * mass, 0.0f, dv.z * mass}, at);
    }
  }
  void after_step(Tick, const Engine& engine) override {
    for (size_t k = first_moving_; k < handles_.size(); ++k) {
      const BodyHandle h = handles_[k];
      if (escaped_[k]) continue;
      const Vec3 p = engine.position(h);
      const bool inside = engine.enabled(h) && std::fabs(p.x) < kArenaHalf &&
                          std::fabs(p.z) < kArenaHalf && p.y > -0.1f && p.y < kWallHeight;
      if (!inside) {
        escaped_[k] = true;
        ++escaped_count_;
        continue;
      }
      const Vec3 v = engine.linear_velocity(h);
      fastest_ =
          std::max(fastest_, static_cast<double>(std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z)));
    }
  }
  bool build(Engine& engine, std::string& error) override {
    escaped_.assign(specs_.size(), false);
    return SpecScene::build(engine, error);
  }
  std::vector<Metric> metrics() const override {
    return {kit::at_most("escaped", "bodies", static_cast<double>(escaped_count_), 0.0,
                         "every crate and ball stays inside the closed arena"),
            kit::at_most("max_speed_mps", "m/s", fastest_, 12.0,
                         "nothing moves faster than twice a ball's charge (6 m/s)")};
  }

 private:
  static constexpr float kArenaHalf = 10.0f;
  static constexpr float kWallHeight = 8.0f;
  static constexpr float kCrateHalf = 0.4f;
  static constexpr float kPusherRadius = 0.5f;
  static constexpr float kPusherDensity = 3000.0f;
  static constexpr float kMaxSpeed = 6.0f;   // m/s at full stick
  static constexpr float kSteerGain = 8.0f;  // 1/s
  static constexpr Tick kPhaseTicks = 90;
  size_t first_moving_ = 0;
  size_t first_pusher_ = 0;
  std::vector<bool> escaped_;
  int escaped_count_ = 0;
  double fastest_ = 0.0;
};

}  // namespace

std::unique_ptr<Scene> make_crates(int players) {
  if (players < 1 || players > 32) return nullptr;
  return std::make_unique<CratesScene>(players);
}

}  // namespace rwd::scenes
