// SPDX-License-Identifier: MIT
#pragma once
// "crates": each player steers a heavy ball (the pusher) around a walled
// arena whose centre holds a tower of crates. A player scores when their
// pusher is the last to touch a crate that lands outside the centre ring.
// The arena is closed on all sides, but a jump from a pile can still clear
// a wall: anything that falls below the kill plane (or leaves the world
// bounds) comes back, pushers at their spawn point, crates above the centre.
#include <array>
#include <cstdint>

#include "rewind/game/game_on.h"
#include "rewind/sim/world3d.h"

namespace rwd::game {

/// Button bits of StickInput::buttons in crates.
inline constexpr uint32_t kCratesJump = 1u << 0;
inline constexpr uint32_t kCratesDash = 1u << 1;

struct CratesState {
  uint32_t player_count = 0;
  uint32_t crate_count = 0;
  std::array<sim::BodyId, kMaxPlayers> pushers{};
  std::array<uint32_t, kMaxPlayers> score{};
  std::array<int32_t, kMaxPlayers> cooldown_ticks{};  ///< jump/dash cooldown
  std::array<sim::BodyId, 64> crates{};
  std::array<uint8_t, 64> crate_last_toucher{};  ///< player + 1, 0 = nobody
  std::array<uint8_t, 64> crate_scored{};        ///< 1 once it counted
  std::array<uint32_t, kMaxPlayers> falls{};     ///< pusher respawns per player
  uint32_t crate_respawns = 0;
};

class CratesGame final : public GameWithState<sim::World3D, CratesState> {
 public:
  std::string_view name() const override { return "crates"; }
  /// 2: closed arena corners, kill plane and respawn of escaped bodies.
  uint32_t rules_version() const override { return 2; }
  sim::WorldConfig world_config() const override;

 protected:
  Status build_typed(const MatchSetup& setup, sim::World3D& world,
                     CratesState& state) const override;
  Status apply_typed(Tick tick, std::span<const StickInput> inputs, sim::World3D& world,
                     CratesState& state) const override;
  Status after_step_typed(Tick tick, sim::World3D& world, CratesState& state) const override;
  void hash_typed(const CratesState& state, rwd::StateHasher& hasher) const override;
  Status validate_typed(const MatchSetup& setup, const CratesState& state) const override;
};

}  // namespace rwd::game
