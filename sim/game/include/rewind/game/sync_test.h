// SPDX-License-Identifier: MIT
#pragma once
// A sync test for a game's own code, like GGRS's SyncTestSession: plays a
// match alone with scripted inputs and, every tick, rolls back and
// re-simulates the last few ticks, reloads the state from its serialized
// bytes, and steps a second copy of the match built on its own. A game
// whose rules keep state outside the state block, read something that is
// not part of the match (a clock, a static counter, an address), leave a
// field out of serialization, or hash what the step does not reproduce
// shows it here, named by tick, check and first differing field, before
// it shows as a desync between players.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/body_field.h"
#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/core/tick.h"
#include "rewind/game/game.h"

namespace rwd::game {

struct SyncTestOptions {
  /// Ticks to play, [1, 1'000'000].
  uint32_t ticks = 600;
  /// Ticks rolled back and re-simulated after every tick, [1, 64]: each
  /// tick is simulated check_distance + 1 times in all.
  uint32_t check_distance = 2;
  /// Every this many ticks the state goes through serialize() and
  /// deserialize() into a fresh simulation, which must have the same
  /// checksum and step the next tick the same; 0: never.
  uint32_t round_trip_every = 1;
  /// A second simulation, created on its own, steps beside the first.
  bool second_instance = true;
  /// Seeds the scripted inputs (each player holds a random input for 1 to
  /// 6 ticks, buttons included).
  uint64_t input_seed = 1;
};

/// Fills one tick's inputs (one per player); the default scripts them.
using SyncTestInputs = std::function<void(Tick tick, std::span<PlayerInput> inputs)>;

enum class SyncCheck : uint8_t {
  kRollback,        ///< re-simulating after a restore gave another result
  kRoundTrip,       ///< a state reloaded from its bytes differs or steps differently
  kSecondInstance,  ///< a simulation built on its own differs
};
const char* sync_check_name(SyncCheck check);

struct SyncTestFailure {
  SyncCheck check = SyncCheck::kRollback;
  Tick tick = 0;          ///< the tick after which the states differ
  uint64_t expected = 0;  ///< the checksum of the first run
  uint64_t actual = 0;    ///< the checksum of the check's run
  /// The body fields that differ (first run = expected), at most 16.
  std::vector<rwd::FieldDifference> fields;
  /// The first byte of the game's state block that differs; none when the
  /// blocks are equal.
  std::optional<size_t> game_state_byte;
  /// One line: check, tick, checksums and the first difference.
  std::string describe() const;
};

struct SyncTestReport {
  uint32_t ticks = 0;              ///< ticks played before the end or the failure
  uint64_t resimulated_ticks = 0;  ///< ticks stepped again after rollbacks
  uint64_t round_trips = 0;
  uint64_t final_checksum = 0;
  std::optional<SyncTestFailure> failure;
};

/// Runs the sync test on game `game_name` (built-in or registered).
/// kInvalidArgument for an unknown game, a setup it refuses or options
/// out of range; the game's own error, naming the tick, when its rules
/// fail; otherwise a report, with `failure` set at the first check that
/// failed (the test stops there).
Result<SyncTestReport> run_sync_test(std::string_view game_name, const MatchSetup& setup,
                                     const SyncTestOptions& options,
                                     const SyncTestInputs& inputs = {});

}  // namespace rwd::game
