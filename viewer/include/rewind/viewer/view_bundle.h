// SPDX-License-Identifier: MIT
#pragma once
// What a viewer needs to replay a match, in one flat little-endian file
// that a browser loads whole: the game, its setup, every final tick's
// inputs and recorded checksum, the players' names and, for a desync, the
// client's state after the tick it reported. Native tools write it from a
// replay file (rewind/replay/replay_view.h); the viewer, native or
// WebAssembly, reads it with no protobuf and re-simulates from it.
//
// Layout (version 3), every integer little-endian, strings and byte runs
// as a u32 length and that many bytes:
//   "RWDVIEW1"  u32 version
//   str game  u32 player_count  u64 seed  u32 tick_rate_hz
//   u8 identity_matches  str identity_note
//   u32 name_count  str name...               (0 or player_count names)
//   i32 first_tick  bytes start_state         (version 2; version 1 has
//   u32 keyframe_count                         none of these: 0, empty, none)
//     per keyframe: i32 position  bytes state
//   u32 tick_count  per tick: u64 checksum  u64 substituted_mask
//                             player_count x (u8 n  n bytes: the input
//                             without its trailing zeros; versions 1 and 2:
//                             i16 axis_x  i16 axis_y  u32 buttons)
//   u8 has_desync  [i32 tick  u32 player  str headline  bytes client_state]
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/core/tick.h"
#include "rewind/game/game.h"

namespace rwd::viewer {

inline constexpr uint32_t kViewBundleVersion = 3;
/// Bounds a reader enforces (a bundle is untrusted input).
inline constexpr uint32_t kViewMaxTicks = 1u << 24;        ///< 77 hours at 60 Hz
inline constexpr uint32_t kViewMaxString = 256;            ///< bytes, names and notes
inline constexpr uint32_t kViewMaxHeadline = 4096;         ///< bytes
inline constexpr uint32_t kViewMaxStateBytes = 64u << 20;  ///< a client's state

/// A recorded state a viewer may jump to instead of re-simulating up to
/// it: Simulation::serialize bytes of the state at `position` (after tick
/// position - 1), such as a replay's keyframes.
struct ViewKeyframe {
  Tick position = 0;
  std::vector<uint8_t> state;
};

/// A client's desync report as the viewer shows it: the final tick whose
/// checksums differed and the client's whole state after that tick
/// (Simulation::serialize bytes, the server's desync_p*_t*_r*.bin).
struct ViewDesync {
  Tick tick = 0;
  uint32_t player = 0;
  std::string headline;
  std::vector<uint8_t> client_state;
};

struct ViewBundle {
  std::string game;  ///< a built-in game's name ("crates", "arena", "joust")
  game::MatchSetup setup;
  uint32_t tick_rate_hz = 60;
  /// Whether the recording engine, rules and world config are this
  /// build's; when not, `identity_note` says what differs and re-simulated
  /// checksums are not expected to match.
  bool identity_matches = true;
  std::string identity_note;
  std::vector<std::string> player_names;  ///< empty, or one per player
  /// The first tick the bundle holds. 0: the match from its start, from
  /// the setup alone (or `start_state` when given). Later (a live match
  /// joined midway): `start_state` is the state before that tick.
  Tick first_tick = 0;
  /// Simulation::serialize bytes of the state at position first_tick;
  /// empty: the setup's initial state (only with first_tick 0).
  std::vector<uint8_t> start_state;
  /// States to seek through, positions ascending in (first_tick,
  /// end_position()]. A player uses one only when it loads, is at its
  /// position and has the recorded checksum there.
  std::vector<ViewKeyframe> keyframes;
  /// Tick first_tick + i's inputs are inputs[i * player_count .. + player_count).
  std::vector<rwd::PlayerInput> inputs;
  std::vector<uint64_t> checksums;          ///< recorded, after each tick
  std::vector<uint64_t> substituted_masks;  ///< bit p: player p's input was substituted
  std::optional<ViewDesync> desync;

  uint32_t tick_count() const { return static_cast<uint32_t>(checksums.size()); }
  /// The position after the last tick: first_tick + tick_count().
  Tick end_position() const { return first_tick + static_cast<Tick>(checksums.size()); }
};

/// Writes `bundle` (which must be consistent: sizes as documented above,
/// strings within bounds; kInvalidArgument otherwise, `out` untouched).
Status encode_view_bundle(const ViewBundle& bundle, std::vector<uint8_t>& out);
/// Reads a bundle. kCorrupt names the offset and the field that is wrong
/// (bad magic, a newer version, a length past the end or its bound, an
/// input out of range, bytes left over).
Result<ViewBundle> decode_view_bundle(std::span<const uint8_t> bytes);

}  // namespace rwd::viewer
