// SPDX-License-Identifier: MIT
#pragma once
// Plays a match from a view bundle by re-simulating it: forward tick by
// tick, or to any position through snapshots the player keeps as it first
// passes them (one every `keyframe_every` ticks), checking each tick's
// checksum against the recorded one. The same code runs natively and in
// the browser (WebAssembly), so the checksums a viewer shows are the
// engine's own.
//
// Positions count ticks simulated: position 0 is the match's initial
// state, position p the state after ticks 0 .. p-1, whose recorded
// checksum is tick p - 1's. A bundle that starts later (a live match
// joined midway: its first_tick and start_state) has positions from
// first_tick on. A live viewer appends the ticks it polls (append()).
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "rewind/core/body_field.h"
#include "rewind/core/debug_draw.h"
#include "rewind/core/status.h"
#include "rewind/game/simulation.h"
#include "rewind/viewer/live_ticks.h"
#include "rewind/viewer/view_bundle.h"

namespace rwd::viewer {

/// How position p's re-simulated checksum compared with the recording.
enum class TickCheck : uint8_t {
  kUnchecked = 0,  ///< not simulated yet (or position 0, which has no record)
  kMatch = 1,
  kMismatch = 2,
};

/// A desync report laid over the replay: the client's state against the
/// re-simulated one after the reported tick.
struct DesyncView {
  Tick position = 0;  ///< the report's tick + 1: the state it holds
  uint64_t client_checksum = 0;
  uint64_t replay_checksum = 0;
  /// Re-simulated ("expected") against the client's ("actual") fields.
  std::vector<rwd::FieldDifference> differences;
  std::vector<uint32_t> bodies;  ///< the body indices named above, ascending, once each
};

class ReplayPlayer {
 public:
  /// A player at the bundle's first position (0, or its first_tick with
  /// its start state loaded). kInvalidArgument for an unknown game or a
  /// setup the game refuses, kCorrupt for a start state that does not
  /// load or is not at first_tick. `keyframe_every` is clamped to
  /// [1, 3600]; `max_keyframes` > 0 bounds the snapshots kept (the oldest
  /// go first: a live viewer's memory stays flat over hours), 0 keeps all.
  static Result<std::unique_ptr<ReplayPlayer>> create(ViewBundle bundle,
                                                      uint32_t keyframe_every = 60,
                                                      uint32_t max_keyframes = 0);

  const ViewBundle& bundle() const { return bundle_; }
  Tick position() const { return sim_->tick(); }
  /// The first position: 0, or the bundle's first_tick.
  Tick start() const { return bundle_.first_tick; }
  /// The last position: the bundle's first tick + its ticks.
  Tick length() const { return bundle_.end_position(); }

  /// Adds a live batch's ticks after the last one. Ticks the player holds
  /// already are skipped (polls may overlap); names replace the bundle's
  /// when the batch has them. kInvalidArgument, nothing changed, for
  /// another player count or a gap (batch.first_tick past length()).
  Status append(const LiveTicks& batch);

  /// Simulates the next tick with its recorded inputs and checks it.
  /// False, changing nothing, at the end.
  bool step();
  /// Moves to `position` (clamped to [start(), length()]): from the nearest
  /// state at or before it (a snapshot the player kept, one of the
  /// bundle's recorded keyframes, or the current position), stepping the
  /// rest. A recorded keyframe is used only when it loads at its position
  /// with the recorded checksum; its position then counts as checked, and
  /// the ticks jumped over stay unchecked.
  void seek(Tick position);

  /// Re-simulates up to `max_steps` more ticks from the start, apart from
  /// what the viewer shows, so that every tick gets its check even when
  /// seeks jumped over it through recorded keyframes. A viewer calls it
  /// when idle. Returns the position verified through (length() when done).
  Tick verify(uint32_t max_steps);
  /// The position through which every tick has been re-simulated from the
  /// start, by verify() or by stepping.
  Tick verified_through() const { return verified_; }

  /// The state's checksum now, and the recorded one (none at position 0).
  uint64_t checksum() const { return sim_->checksum(); }
  std::optional<uint64_t> recorded_checksum() const;
  /// The check of `position` (kUnchecked outside [start() + 1, length()]).
  TickCheck check(Tick position) const;
  /// The first simulated position whose checksum differed from the record.
  std::optional<Tick> first_mismatch() const { return first_mismatch_; }

  void draw(const rwd::DebugDrawOptions& options, rwd::DebugDrawBuffers& out) const {
    sim_->lane().debug_draw(options, out);
  }
  rwd::WorldViewStats stats() const { return sim_->lane().view_stats(); }
  const game::Simulation& simulation() const { return *sim_; }
  /// Where body `index` is now (m; its centre of mass, z = 0 in 2D), read
  /// from the lane-neutral dump; nullopt for no live body there. For a
  /// viewer that frames a body (a desync's), not for anything per tick.
  std::optional<std::array<double, 3>> body_center(uint32_t index) const;

  /// Seeks to the bundle's desync (its tick + 1) and compares the client's
  /// state there with the re-simulated one. kNotFound without a desync in
  /// the bundle, kCorrupt when the client's state does not load.
  Result<DesyncView> open_desync();

 private:
  ReplayPlayer(ViewBundle bundle, std::unique_ptr<game::Simulation> sim, uint32_t keyframe_every,
               uint32_t max_keyframes);
  void keep_keyframe();
  /// Records the check of `position` from a re-simulated checksum.
  void record_check(Tick position, uint64_t checksum);
  /// Loads the newest usable recorded keyframe in (after, target]; false
  /// when there is none (the player is unchanged).
  bool load_recorded_state(Tick after, Tick target);
  size_t offset(Tick position) const { return static_cast<size_t>(position - bundle_.first_tick); }

  ViewBundle bundle_;
  std::unique_ptr<game::Simulation> sim_;
  uint32_t keyframe_every_;
  uint32_t max_keyframes_;
  uint32_t kept_keyframes_ = 0;
  /// keyframes_[k]: the state at position start() + k * keyframe_every_,
  /// once passed (and not yet dropped for max_keyframes).
  std::vector<std::optional<game::SimSnapshot>> keyframes_;
  std::vector<TickCheck> checks_;               ///< by position - start()
  std::vector<bool> unusable_;                  ///< bundle keyframes found not to load or match
  std::unique_ptr<game::Simulation> scratch_;   ///< where a recorded keyframe is tried
  std::unique_ptr<game::Simulation> verifier_;  ///< verify()'s own re-simulation
  Tick verified_ = 0;    ///< every tick before it re-simulated from the start (absolute)
  bool jumped_ = false;  ///< a recorded keyframe was loaded: stepping no longer verifies
  std::optional<Tick> first_mismatch_;
};

}  // namespace rwd::viewer
