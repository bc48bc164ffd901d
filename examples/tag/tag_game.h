// SPDX-License-Identifier: MIT
#pragma once
// "tag": every player rolls a ball around a walled yard. One of them is
// "it"; when "it" touches another ball, that one becomes "it" and cannot
// pass it back for a second. Every tick a player is not "it" scores a
// point.
//
// A game written only against Rewind's installed headers: its rules
// (GameWithState over the 3D lane), its own input (TagInput, described to
// Rewind by input_spec()), its own bots (bot_input), and the registration
// that lets rewind-server, rewind-bots, rewind-replay and rewind-synctest
// host, play, verify and check it (register_tag_game()).
#include <array>
#include <cstdint>

#include <rewind/game/game_on.h>
#include <rewind/sim/world3d.h>

namespace tag {

/// Everything that must roll back besides the world: trivially copyable,
/// hashed field by field (TagGame::hash_typed).
struct TagState {
  uint32_t player_count = 0;
  uint32_t it = 0;           ///< the player who is "it"
  int32_t tag_cooldown = 0;  ///< ticks until "it" can tag again
  uint32_t tags = 0;         ///< how often "it" changed
  std::array<rwd::sim::BodyId, rwd::game::kMaxPlayers> balls{};
  std::array<uint32_t, rwd::game::kMaxPlayers> points{};
};

inline constexpr int32_t kTagCooldownTicks = 60;

/// What a tag player sends every tick: where to run and how fast, and
/// whether to sprint. Integers only, no padding (rwd::InputLayout); 4 bytes.
struct TagInput {
  int16_t heading = 0;   ///< direction to run, tenths of a degree from +x toward +z, [0, 3599]
  uint8_t throttle = 0;  ///< percent of the running speed, [0, 100]
  uint8_t sprint = 0;    ///< 1: run 40% faster this tick, [0, 1]
};

class TagGame final : public rwd::game::GameWithState<rwd::sim::World3D, TagState, TagInput> {
 public:
  std::string_view name() const override { return "tag"; }
  uint32_t rules_version() const override { return 2; }
  rwd::sim::WorldConfig world_config() const override;
  /// TagInput's fields and ranges; a missing input is predicted as the
  /// newest one without its sprint (players sprint in short bursts).
  const rwd::InputSpec& input_spec() const override;
  rwd::PlayerInput bot_input(uint64_t seed, uint32_t player, rwd::Tick tick) const override;

 protected:
  rwd::Status build_typed(const rwd::game::MatchSetup& setup, rwd::sim::World3D& world,
                          TagState& state) const override;
  rwd::Status apply_typed(rwd::Tick tick, std::span<const TagInput> inputs,
                          rwd::sim::World3D& world, TagState& state) const override;
  rwd::Status after_step_typed(rwd::Tick tick, rwd::sim::World3D& world,
                               TagState& state) const override;
  void hash_typed(const TagState& state, rwd::StateHasher& hasher) const override;
  rwd::Status validate_typed(const rwd::game::MatchSetup& setup,
                             const TagState& state) const override;
};

/// Registers "tag" with Rewind's game registry; call once from main().
rwd::Status register_tag_game();

}  // namespace tag
