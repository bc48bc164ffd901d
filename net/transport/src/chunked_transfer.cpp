// SPDX-License-Identifier: MIT
#include "rewind/net/chunked_transfer.h"

#include <algorithm>
#include <string>

#include "rewind/net/envelope_codec.h"

namespace rwd::net {

// The messages that carry chunks are checked by the envelope codec against
// its own limits; a transfer these limits allow must pass them.
static_assert(kResyncChunkLimits.max_chunks == kMaxResyncChunks);
static_assert(kDesyncChunkLimits.max_chunks == kMaxDesyncChunks);
static_assert(kTransferChunkBytes <= kMaxChunkBytes);
static_assert(kResyncChunkLimits.max_blob_bytes() <= kMaxResyncStateBytes);
static_assert(kDesyncChunkLimits.max_blob_bytes() <= kMaxDesyncDumpBytes);

Result<uint32_t> plan_chunks(size_t size, const ChunkLimits& limits) {
  if (size == 0) return Status::Error(ErrorCode::kInvalidArgument, "an empty blob has no chunks");
  const size_t count = (size + limits.chunk_bytes - 1) / limits.chunk_bytes;
  if (count > limits.max_chunks) {
    return Status::Error(ErrorCode::kCapacity,
                         std::to_string(size) + " bytes is too large: at most " +
                             std::to_string(limits.max_blob_bytes()) + " in " +
                             std::to_string(limits.max_chunks) + " chunks");
  }
  return static_cast<uint32_t>(count);
}

std::span<const uint8_t> chunk_at(std::span<const uint8_t> blob, uint32_t index,
                                  const ChunkLimits& limits) {
  const size_t begin = std::min(blob.size(), size_t{index} * limits.chunk_bytes);
  const size_t end = std::min(blob.size(), begin + limits.chunk_bytes);
  return blob.subspan(begin, end - begin);
}

ChunkAssembler::ChunkAssembler(const ChunkLimits& limits) : limits_(limits) {
  limits_.chunk_bytes = std::max<size_t>(limits_.chunk_bytes, 1);
  limits_.max_chunks = std::max<uint32_t>(limits_.max_chunks, 1);
}

bool ChunkAssembler::well_formed(const ChunkHeader& header, size_t data_size) const {
  const Result<uint32_t> count = plan_chunks(header.total_size, limits_);
  if (!count.ok() || *count != header.count || header.index >= header.count) return false;
  // Every chunk but the last is full; the last holds the remainder.
  const size_t begin = size_t{header.index} * limits_.chunk_bytes;
  const size_t expected = std::min<size_t>(limits_.chunk_bytes, header.total_size - begin);
  return data_size == expected;
}

ChunkResult ChunkAssembler::add(const ChunkHeader& header, std::span<const uint8_t> data) {
  if (!well_formed(header, data.size())) return ChunkResult::kRejected;
  if (active_ && header.transfer_id == header_.transfer_id) {
    // The same transfer must keep its shape: a contradiction under one id
    // is damage or a forgery, and must not undo the chunks already held.
    if (header.count != header_.count || header.total_size != header_.total_size ||
        header.context != header_.context) {
      return ChunkResult::kRejected;
    }
    if (have_[header.index] != 0) return ChunkResult::kDuplicate;
  } else {
    // A new transfer supersedes the old one (the sender has moved on).
    active_ = true;
    header_ = header;
    header_.index = 0;
    received_ = 0;
    bytes_.assign(header.total_size, 0);
    have_.assign(header.count, 0);
  }
  std::copy(
      data.begin(), data.end(),
      bytes_.begin() + static_cast<std::ptrdiff_t>(size_t{header.index} * limits_.chunk_bytes));
  have_[header.index] = 1;
  ++received_;
  return received_ == header_.count ? ChunkResult::kComplete : ChunkResult::kAccepted;
}

void ChunkAssembler::reset() {
  active_ = false;
  header_ = ChunkHeader{};
  received_ = 0;
  // Transfers are rare (a desync, a resync): hold no memory between them.
  std::vector<uint8_t>().swap(bytes_);
  std::vector<uint8_t>().swap(have_);
}

std::span<const uint8_t> ChunkAssembler::blob() const {
  if (!complete()) return {};
  return bytes_;
}

}  // namespace rwd::net
