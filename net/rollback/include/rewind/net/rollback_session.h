// SPDX-License-Identifier: MIT
#pragma once
// The rollback core shared by the server, the client SDK and the tests: a
// simulation, one input queue per player, the snapshot ring, and the record
// of which inputs each simulated tick used. Knows nothing of sockets or
// clocks: callers add inputs and call advance().
//
// Tick vocabulary: current_tick() is the next tick to simulate; the state
// "after tick t" is the state at the start of t + 1. A final tick never
// changes again, so nothing at or before final_tick() is ever re-simulated.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/game/simulation.h"
#include "rewind/net/input_queue.h"
#include "rewind/net/snapshot_ring.h"

namespace rwd::net {

struct RollbackConfig {
  /// Ticks of saved state; the deepest possible rollback. Must exceed the
  /// finalization window plus the client's lead.
  int32_t snapshot_ticks = 64;
  /// Ticks of input each queue holds ahead of the final tick.
  int32_t input_ticks = 256;
};

struct RollbackStats {
  uint64_t rollbacks = 0;          ///< restores caused by a misprediction
  uint64_t resimulated_ticks = 0;  ///< ticks stepped again after a restore
  uint64_t simulated_ticks = 0;    ///< ticks stepped for the first time
};

enum class InputResult : uint8_t {
  kAccepted,   ///< new input stored
  kDuplicate,  ///< already had exactly this input
  kConflict,   ///< a different input for that tick was already confirmed
  kFinal,      ///< the tick is already final
  kTooFar,     ///< beyond what the input queue can hold
  kBadPlayer,  ///< no such player slot
  kBadInput,   ///< the game's input spec does not allow it (check_input)
};

class RollbackSession {
 public:
  RollbackSession(std::unique_ptr<game::Simulation> sim, const RollbackConfig& config);

  uint32_t player_count() const { return player_count_; }
  Tick current_tick() const { return sim_->tick(); }
  Tick final_tick() const { return final_tick_; }
  const game::Simulation& simulation() const { return *sim_; }
  /// Mutable access for tests and debugging hooks; mutating it desyncs the session.
  game::Simulation& mutable_simulation() { return *sim_; }
  const RollbackStats& stats() const { return stats_; }
  const InputQueue& queue(uint32_t player) const { return queues_[player]; }

  /// Adds a confirmed input. Inputs for ticks already simulated mark the
  /// session for re-simulation if they differ from what was used.
  InputResult add_input(uint32_t player, Tick tick, const rwd::PlayerInput& input);
  /// Adds the server's final input, overriding anything confirmed before.
  InputResult add_final_input(uint32_t player, Tick tick, const rwd::PlayerInput& input);

  /// The input player `player` has (or is predicted to have) at `tick`.
  rwd::PlayerInput input_for(uint32_t player, Tick tick) const {
    return queues_[player].input_for(tick);
  }
  /// The input that the simulated `tick` used, for ticks in the rollback window.
  rwd::PlayerInput used_input(uint32_t player, Tick tick) const;

  /// Re-simulates from the first tick whose inputs changed, if any, so the
  /// simulation reflects every input known now. Returns false if that tick
  /// is no longer held in the snapshot ring (the caller must resync).
  bool synchronize();
  /// synchronize(), then saves a snapshot and simulates current_tick().
  bool advance();

  /// The first error the game's rules returned (Simulation::step), or Ok.
  /// Once set the session steps no more: advance() and synchronize() leave
  /// current_tick() where the rules failed, and the host ends the match
  /// with this message.
  const Status& game_error() const { return game_error_; }

  /// Checksum of the state after tick `t` (t < current_tick(), within the
  /// ring). Call synchronize() first so it reflects every known input.
  std::optional<uint64_t> checksum_after(Tick t) const;
  /// Checksum of the state at the start of `tick` (tick <= current_tick(),
  /// within the ring): the one that goes with serialize_state_at(tick).
  std::optional<uint64_t> checksum_at(Tick tick) const;
  /// The serialized state at the start of `tick`, for resync snapshots.
  /// Briefly restores that snapshot into the simulation and puts the
  /// present back, hence non-const.
  bool serialize_state_at(Tick tick, std::vector<uint8_t>& out);

  /// Declares every tick up to `t` final: their inputs are fixed (set them
  /// first) and they will never be re-simulated. Re-simulates first if a
  /// final input changed history. Frees queue space. Returns false if that
  /// re-simulation was impossible (the caller must resync).
  bool finalize_through(Tick t);

  /// Called after every step, first-time or re-simulated, with the tick
  /// just simulated. For debugging and fault-injection tests (e.g. a client
  /// that deliberately corrupts its state at one tick); empty by default.
  using StepHook = std::function<void(game::Simulation&, Tick)>;
  void set_step_hook(StepHook hook) { step_hook_ = std::move(hook); }

  /// Decodes a serialized simulation of this session's match into a fresh
  /// Simulation and, when `expected_checksum` is given, checks that it
  /// reproduces it: exactly the test reset_from() applies, so a sender can
  /// check a snapshot before it goes out (the server does, for resyncs) and
  /// a reader can inspect a dump without touching the session.
  Result<std::unique_ptr<game::Simulation>> load_snapshot(
      std::span<const uint8_t> serialized,
      std::optional<uint64_t> expected_checksum = std::nullopt) const;

  /// Replaces the state from a serialized simulation (a resync). The bytes
  /// must pass load_snapshot() before anything is replaced. The ticks before
  /// the snapshot become final; input queues keep what they know for later
  /// ticks. On error nothing changes.
  Status reset_from(std::span<const uint8_t> serialized,
                    std::optional<uint64_t> expected_checksum = std::nullopt);

 private:
  rwd::PlayerInput* used_row(Tick tick) {
    return &used_[static_cast<size_t>(tick % ring_.capacity()) * player_count_];
  }
  const rwd::PlayerInput* used_row(Tick tick) const {
    return &used_[static_cast<size_t>(tick % ring_.capacity()) * player_count_];
  }
  InputResult classify(InputQueue::AddOutcome outcome) const;
  void note_changed(Tick tick);
  void step_once();

  std::unique_ptr<game::Simulation> sim_;
  uint32_t player_count_;
  RollbackConfig config_;
  std::vector<InputQueue> queues_;
  SnapshotRing ring_;
  std::vector<rwd::PlayerInput> used_;  // ring_.capacity() rows of player_count_
  std::vector<rwd::PlayerInput> scratch_inputs_;
  Tick final_tick_ = kNoTick;
  Tick dirty_from_ = kNoTick;  // earliest tick whose inputs may have changed
  RollbackStats stats_;
  StepHook step_hook_;
  Status game_error_;
};

}  // namespace rwd::net
