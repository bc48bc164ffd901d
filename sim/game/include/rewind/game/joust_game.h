// SPDX-License-Identifier: MIT
#pragma once
// "joust": each player drives a car (a raycast-wheel vehicle, vehicle3d.h)
// across a bumpy height-field arena whose edges rise into a bowl. A lance is
// welded to the left of every car, pointing ahead at riding height, and a
// rider (a ragdoll) sits on the car, held by a weld that breaks under a hard
// knock. A lance that strikes another player's rider hard enough throws it
// off (the seat weld goes, the figure flies): a point for the lance's owner.
// Crashes and the wrecking ball swinging from the gantry in the middle throw
// riders too, for no point. A thrown rider is seated again on its car a few
// seconds later; a car on its roof (or out of the arena) is put back at its
// spawn point.
//
// Controls (StickInput): axis_y sets the speed the car drives toward
// (full deflection 12 m/s ahead or behind; released, it rolls to a stop),
// axis_x steers (+ right), kJoustBrake brakes, kJoustCharge starts a
// charge (more drive force and top speed for a second, then a cooldown).
#include <array>
#include <cstdint>

#include "rewind/game/game_on.h"
#include "rewind/sim/ragdoll3d.h"
#include "rewind/sim/world3d.h"

namespace rwd::game {

/// Button bits of StickInput::buttons in joust.
inline constexpr uint32_t kJoustBrake = 1u << 0;
inline constexpr uint32_t kJoustCharge = 1u << 1;

/// Links of the wrecking ball's chain (the ball hangs from the last).
inline constexpr uint32_t kJoustChainLinks = 7;

/// Everything the rules keep between ticks; the bodies and joints it names
/// live in the world's state.
struct JoustState {
  uint32_t player_count = 0;
  std::array<sim::BodyId, kMaxPlayers> chassis{};
  std::array<sim::BodyId, kMaxPlayers> lances{};
  std::array<sim::JointId, kMaxPlayers> lance_welds{};
  /// Each rider, a ragdoll (ragdoll3d.h): its parts, indexed by
  /// sim::RagdollPart3D, and its joints, by sim::RagdollJoint3D.
  std::array<std::array<sim::BodyId, sim::kRagdollPartCount3D>, kMaxPlayers> riders{};
  std::array<std::array<sim::JointId, sim::kRagdollJointCount3D>, kMaxPlayers> rider_joints{};
  /// The weld holding the rider on its car; null while the rider is off.
  std::array<sim::JointId, kMaxPlayers> seats{};
  std::array<uint32_t, kMaxPlayers> score{};     ///< opponents unseated
  std::array<uint32_t, kMaxPlayers> unseated{};  ///< times this rider was thrown
  std::array<uint32_t, kMaxPlayers> car_resets{};
  /// Ticks until a thrown rider is seated again (0 while seated).
  std::array<int32_t, kMaxPlayers> respawn_ticks{};
  /// Player + 1 whose lance last struck this rider (0 = nobody) and the
  /// ticks that strike is still remembered for: a rider thrown within them
  /// scores for that player.
  std::array<uint8_t, kMaxPlayers> last_hitter{};
  std::array<int32_t, kMaxPlayers> hit_ticks{};
  /// Ticks a rider thrown with no strike remembered may still be credited
  /// to the first opponent lance that touches it.
  std::array<int32_t, kMaxPlayers> credit_ticks{};
  std::array<int32_t, kMaxPlayers> charge_ticks{};    ///< charge left
  std::array<int32_t, kMaxPlayers> cooldown_ticks{};  ///< until the next charge
  std::array<int32_t, kMaxPlayers> upset_ticks{};     ///< car on its side or roof
  /// The wrecking ball: chain links from the gantry down, the ball, and the
  /// ball joints from the gantry (joint 0) to the ball (the last).
  std::array<sim::BodyId, kJoustChainLinks> chain{};
  sim::BodyId ball;
  std::array<sim::JointId, kJoustChainLinks + 1> chain_joints{};
  sim::BodyId gantry;  ///< the static cross beam the chain hangs from
};

class JoustGame final : public GameWithState<sim::World3D, JoustState> {
 public:
  std::string_view name() const override { return "joust"; }
  uint32_t rules_version() const override { return 2; }
  sim::WorldConfig world_config() const override;

  /// Seats player p's rider on its car now (the ragdoll posed sitting on
  /// the roof, moving with the car, a fresh seat weld), whether or not it
  /// was seated. For the
  /// rules' respawn and for tests; false when the car or rider is missing.
  static bool seat_rider(sim::World3D& world, JoustState& state, uint32_t player);
  /// Puts player p's car (chassis, lance, and the rider while seated) at
  /// `position` (the chassis centre) turned by `rotation`, at rest. For
  /// the rules' car reset and for tests; false when a body is missing.
  static bool place_car(sim::World3D& world, JoustState& state, uint32_t player, sim::Vec3 position,
                        sim::Quat rotation);
  /// The chain's largest gap between the two anchors of one of its ball
  /// joints, m: how far the chain has opened.
  static float chain_opening(const sim::World3D& world, const JoustState& state);

 protected:
  Status build_typed(const MatchSetup& setup, sim::World3D& world,
                     JoustState& state) const override;
  Status apply_typed(Tick tick, std::span<const StickInput> inputs, sim::World3D& world,
                     JoustState& state) const override;
  Status after_step_typed(Tick tick, sim::World3D& world, JoustState& state) const override;
  void hash_typed(const JoustState& state, rwd::StateHasher& hasher) const override;
  Status validate_typed(const MatchSetup& setup, const JoustState& state) const override;
};

}  // namespace rwd::game
