// SPDX-License-Identifier: MIT
#pragma once
// A batch of a live match's final ticks as a spectating viewer polls them
// (a server's GET /live/<match>/ticks?from=T): the ticks from T on, with
// the players' names and how far the match is, in one flat little-endian
// message a browser reads with no protobuf. A viewer starts from a view
// bundle (rewind/viewer/view_bundle.h, whose first_tick and start_state
// let it join midway) and appends batches to its ReplayPlayer.
//
// Layout (version 2), integers little-endian, strings as u32 length + bytes:
//   "RWDLIVE1"  u32 version
//   u32 player_count  u32 name_count  str name...   (0 or player_count names)
//   i32 newest_final  u8 ended
//   i32 first_tick  u32 tick_count
//   per tick: u64 checksum  u64 substituted_mask
//             player_count x (u8 n  n bytes: the input without its
//                             trailing zeros)
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/core/tick.h"

namespace rwd::viewer {

inline constexpr uint32_t kLiveTicksVersion = 2;
/// Most ticks one batch carries (a reader refuses more).
inline constexpr uint32_t kLiveMaxBatchTicks = 1u << 16;

struct LiveTicks {
  uint32_t player_count = 0;
  std::vector<std::string> player_names;  ///< empty, or one per player
  /// The newest tick the match has made final (kNoTick: none yet). Ahead
  /// of the batch's last tick when the server holds spectators back by a
  /// delay, or when the batch was cut at kLiveMaxBatchTicks.
  Tick newest_final = kNoTick;
  bool ended = false;  ///< the match is over: no tick will follow the newest
  Tick first_tick = 0;
  std::vector<uint64_t> checksums;  ///< after each tick, from first_tick on
  std::vector<uint64_t> substituted_masks;
  std::vector<rwd::PlayerInput> inputs;  ///< tick i's: [i * player_count, + player_count)

  uint32_t tick_count() const { return static_cast<uint32_t>(checksums.size()); }
};

/// Writes `batch`; kInvalidArgument (out untouched) when it is not
/// consistent: players in [1, kMaxPlayers], names none or one each within
/// kViewMaxString, sizes matching, inputs in range, first_tick >= 0.
Status encode_live_ticks(const LiveTicks& batch, std::vector<uint8_t>& out);
/// Reads a batch; kCorrupt names the offset and the field that is wrong.
Result<LiveTicks> decode_live_ticks(std::span<const uint8_t> bytes);

}  // namespace rwd::viewer
