// SPDX-License-Identifier: MIT
#include "rewind/replay/replay_format.h"

#include <limits>

// Inline XXH3 like the state hasher does, so no libxxhash link is needed.
#define XXH_INLINE_ALL
#include <xxhash.h>

namespace rwd::replay {

uint64_t payload_hash(std::span<const uint8_t> payload) {
  return XXH3_64bits(payload.data(), payload.size());
}

Status append_frame(const v1::ReplayRecord& record, std::vector<uint8_t>& out) {
  const size_t size = record.ByteSizeLong();
  if (size > kMaxRecordBytes) {
    return Status::Error(ErrorCode::kCapacity, "replay record of " + std::to_string(size) +
                                                   " bytes exceeds the limit of " +
                                                   std::to_string(kMaxRecordBytes));
  }
  const size_t start = out.size();
  out.resize(start + kFrameHeaderBytes + size);
  uint8_t* payload = out.data() + start + kFrameHeaderBytes;
  if (!record.SerializeToArray(payload, static_cast<int>(size))) {
    out.resize(start);
    return Status::Error(ErrorCode::kInvalidArgument, "replay record does not serialize");
  }
  const uint64_t hash = payload_hash({payload, size});
  uint8_t* head = out.data() + start;
  for (int i = 0; i < 4; ++i) head[i] = static_cast<uint8_t>(size >> (8 * i));
  for (int i = 0; i < 8; ++i) head[4 + i] = static_cast<uint8_t>(hash >> (8 * i));
  return Status::Ok();
}

Status validate_header(const v1::ReplayHeader& header) {
  if (header.format_version() != kFormatVersion) {
    return Status::Error(ErrorCode::kUnsupported,
                         "replay format version " + std::to_string(header.format_version()) +
                             " is not supported (this build reads version " +
                             std::to_string(kFormatVersion) + ")");
  }
  if (header.game().empty()) {
    return Status::Error(ErrorCode::kInvalidArgument, "replay header names no game");
  }
  if (header.player_count() < 1 || header.player_count() > kMaxReplayPlayers) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "replay header player_count " + std::to_string(header.player_count()) +
                             " is outside [1, " + std::to_string(kMaxReplayPlayers) + "]");
  }
  return Status::Ok();
}

std::string describe_last_tick(Tick last_tick) {
  if (last_tick == kNoTick) return "before the first tick";
  return "after tick " + std::to_string(last_tick);
}

}  // namespace rwd::replay
