// SPDX-License-Identifier: MIT
#include "rewind/replay/replay_format.h"

#include <limits>
#include <memory>

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
  if (header.format_version() == 0) {
    return Status::Error(ErrorCode::kCorrupt, "replay header names no format version");
  }
  if (header.game().empty()) {
    return Status::Error(ErrorCode::kInvalidArgument, "replay header names no game");
  }
  if (header.player_count() < 1 || header.player_count() > kMaxReplayPlayers) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "replay header player_count " + std::to_string(header.player_count()) +
                             " is outside [1, " + std::to_string(kMaxReplayPlayers) + "]");
  }
  if (header.format_version() > kFormatVersion) {
    return Status::Error(ErrorCode::kUnsupported,
                         "replay format version " + std::to_string(header.format_version()) +
                             " is newer than this build reads (" + readable_formats() + ")");
  }
  if (header.format_version() >= 2) {
    // A format 2 file without its identity could not be told apart from one
    // recorded by any other engine, which is what the format exists to do.
    if (header.engine().empty() || header.sim_revision() == 0 || header.world_config().empty()) {
      return Status::Error(ErrorCode::kInvalidArgument,
                           "replay format " + std::to_string(header.format_version()) +
                               " header lacks the engine name, sim revision or world config");
    }
  }
  return Status::Ok();
}

std::string readable_formats() {
  return "formats " + std::to_string(kOldestFormatVersion) + " to " +
         std::to_string(kFormatVersion);
}

std::optional<size_t> prefix_with_hash(std::span<const uint8_t> bytes, uint64_t hash) {
  // One streaming state, digested after every byte: linear in the tail,
  // where hashing every prefix from scratch would be quadratic.
  std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state(XXH3_createState(),
                                                                 &XXH3_freeState);
  if (!state || XXH3_64bits_reset(state.get()) != XXH_OK) return std::nullopt;
  if (XXH3_64bits_digest(state.get()) == hash) return size_t{0};
  for (size_t i = 0; i < bytes.size(); ++i) {
    if (XXH3_64bits_update(state.get(), bytes.data() + i, 1) != XXH_OK) return std::nullopt;
    if (XXH3_64bits_digest(state.get()) == hash) return i + 1;
  }
  return std::nullopt;
}

std::string describe_last_tick(Tick last_tick) {
  if (last_tick == kNoTick) return "before the first tick";
  return "after tick " + std::to_string(last_tick);
}

}  // namespace rwd::replay
