// SPDX-License-Identifier: MIT
#pragma once
// The replay file format, shared by the writer, the reader and the tools:
//   "RWRPLY01" | frame* where frame = u32 LE length | u64 LE XXH3-64(payload) | payload
// and each payload is one rwd.v1.ReplayRecord (the first one the header).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/game/player_input.h"
#include "rewind/sim/status.h"
#include "rewind/sim/tick.h"
#include "rewind/v1/replay.pb.h"

namespace rwd::replay {

/// The eight bytes every replay file starts with.
inline constexpr std::string_view kMagic = "RWRPLY01";
/// Bytes in front of every payload: u32 length + u64 hash.
inline constexpr size_t kFrameHeaderBytes = 12;
/// Largest payload a reader accepts; keyframes of big scenes stay far below.
inline constexpr uint32_t kMaxRecordBytes = 8u * 1024u * 1024u;
/// The ReplayHeader.format_version this build writes and reads.
inline constexpr uint32_t kFormatVersion = 1;
/// Most players a replay can hold. Equal to game::kMaxPlayers (checked where
/// both are visible); repeated here so the framing layer does not need the
/// engine's headers.
inline constexpr uint32_t kMaxReplayPlayers = 32;

/// XXH3-64 of a frame payload.
uint64_t payload_hash(std::span<const uint8_t> payload);

/// Serializes `record` and appends it to `out` as one frame. kCapacity if the
/// payload would exceed kMaxRecordBytes; `out` is untouched on error.
Status append_frame(const v1::ReplayRecord& record, std::vector<uint8_t>& out);

/// Checks the fields a reader and a verifier rely on (format version, game
/// name, player count).
Status validate_header(const v1::ReplayHeader& header);

/// "after tick 41" or "before the first tick": where a file stops making sense.
std::string describe_last_tick(Tick last_tick);

}  // namespace rwd::replay
