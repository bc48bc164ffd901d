// SPDX-License-Identifier: MIT
#pragma once
// The replay file format, shared by the writer, the reader and the tools:
//   "RWRPLY01" | frame* where frame = u32 LE length | u64 LE XXH3-64(payload) | payload
// and each payload is one rwd.v1.ReplayRecord (the first one the header).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/core/tick.h"
#include "rewind/v1/replay.pb.h"

namespace rwd::replay {

/// The eight bytes every replay file starts with.
inline constexpr std::string_view kMagic = "RWRPLY01";
/// Bytes in front of every payload: u32 length + u64 hash.
inline constexpr size_t kFrameHeaderBytes = 12;
/// Largest payload a reader accepts; keyframes of big scenes stay far below.
inline constexpr uint32_t kMaxRecordBytes = 8u * 1024u * 1024u;
/// The ReplayHeader.format_version this build writes.
///   1  no engine identity in the header
///   2  the header records engine, sim revision, game rules version and
///      world config (what re-simulation must match)
///   3  inputs are the game's bytes (Input.data) instead of the stick
///      fields (formats 1 and 2 are read as the stick input)
/// Frames and records are the same in all.
inline constexpr uint32_t kFormatVersion = 3;
/// The oldest format_version this build reads.
inline constexpr uint32_t kOldestFormatVersion = 1;
/// Most players a replay can hold. Equal to game::kMaxPlayers (checked where
/// both are visible); repeated here so the framing layer does not need the
/// engine's headers.
inline constexpr uint32_t kMaxReplayPlayers = 32;

/// XXH3-64 of a frame payload.
uint64_t payload_hash(std::span<const uint8_t> payload);

/// Serializes `record` and appends it to `out` as one frame. kCapacity if the
/// payload would exceed kMaxRecordBytes; `out` is untouched on error.
Status append_frame(const v1::ReplayRecord& record, std::vector<uint8_t>& out);

/// Checks the fields a reader and a verifier rely on: a format version (0
/// is kCorrupt), the game name, the player count and, from format 2 on, the
/// engine identity. A format newer than kFormatVersion whose other common
/// fields are valid is kUnsupported: its records are not this build's to
/// read.
Status validate_header(const v1::ReplayHeader& header);

/// "formats 1 to 3": the format versions this build reads.
std::string readable_formats();

/// Length of the shortest prefix of `bytes` whose payload_hash() is `hash`,
/// if any. A frame whose payload seems to run past the end of the file but
/// whose stored hash matches a prefix of what is there had its length field
/// damaged; a write cut short cannot produce that (but for a 2^-64 chance).
std::optional<size_t> prefix_with_hash(std::span<const uint8_t> bytes, uint64_t hash);

/// "after tick 41" or "before the first tick": where a file stops making sense.
std::string describe_last_tick(Tick last_tick);

}  // namespace rwd::replay
