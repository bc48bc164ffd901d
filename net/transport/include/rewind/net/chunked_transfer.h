// SPDX-License-Identifier: MIT
#pragma once
// Blobs too large for one datagram (resync snapshots, desync state dumps)
// travel as numbered chunks: the sender cuts the blob with
// plan_chunks()/chunk_at(), the receiver puts it back together with a
// ChunkAssembler. Both sides use the same chunk size, so every chunk but
// the last is exactly limits.chunk_bytes long and a chunk's place in the
// blob follows from its index alone. No sockets, clocks or protobuf: the
// messages that carry the chunks are the caller's.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rewind/core/status.h"

namespace rwd::net {

/// Bytes per chunk on the wire: a chunk plus its message and envelope
/// headers stays below kMaxDatagramBytes (1200).
inline constexpr size_t kTransferChunkBytes = 1000;

/// The shape every transfer of one kind must fit.
struct ChunkLimits {
  size_t chunk_bytes = kTransferChunkBytes;  ///< bytes per chunk, >= 1
  uint32_t max_chunks = 1;                   ///< chunks per blob, >= 1
  /// The largest blob: also the most memory an assembler holds.
  constexpr size_t max_blob_bytes() const { return chunk_bytes * max_chunks; }
};

/// Resync snapshots (server -> client): up to 1024 chunks.
inline constexpr ChunkLimits kResyncChunkLimits{kTransferChunkBytes, 1024};
/// Desync state dumps (client -> server): up to 256 chunks.
inline constexpr ChunkLimits kDesyncChunkLimits{kTransferChunkBytes, 256};

/// How many chunks a blob of `size` bytes takes. kInvalidArgument for an
/// empty blob, kCapacity when it needs more than limits.max_chunks.
Result<uint32_t> plan_chunks(size_t size, const ChunkLimits& limits);

/// Chunk `index` of `blob`: a view into it, limits.chunk_bytes long except
/// for the last. `index` must be below plan_chunks(blob.size()).
std::span<const uint8_t> chunk_at(std::span<const uint8_t> blob, uint32_t index,
                                  const ChunkLimits& limits);

/// What one chunk says about itself. Every chunk of a transfer repeats the
/// same transfer_id, count, total_size and context.
struct ChunkHeader {
  uint32_t transfer_id = 0;  ///< names the transfer; a new id replaces the old one
  uint32_t index = 0;        ///< [0, count)
  uint32_t count = 0;        ///< plan_chunks(total_size)
  uint32_t total_size = 0;   ///< bytes of the whole blob
  /// Whatever else the sender states once per transfer and repeats in every
  /// chunk (a tick, checksums): a chunk that disagrees with its transfer's
  /// first chunk is refused.
  std::array<uint64_t, 3> context{};
};

/// How ChunkAssembler::add() took a chunk.
enum class ChunkResult : uint8_t {
  kAccepted,   ///< stored; more chunks are missing
  kComplete,   ///< stored, and the blob is whole: blob() holds it
  kDuplicate,  ///< this transfer already has that chunk; nothing changed
  /// Refused, nothing changed: a header that contradicts itself or the
  /// limits (index >= count, count != plan_chunks(total_size), a chunk of
  /// the wrong length), or one that disagrees with the transfer in progress
  /// under the same id (count, size or context).
  kRejected,
};

/// Reassembles one transfer at a time. A valid chunk with a new id drops
/// whatever was in progress and starts over. Memory is bounded by
/// limits.max_blob_bytes() plus one flag per chunk (a transfer allocates its
/// stated size when its first chunk arrives) and freed by reset(). Not
/// thread-safe.
class ChunkAssembler {
 public:
  /// limits.chunk_bytes and limits.max_chunks must be >= 1.
  explicit ChunkAssembler(const ChunkLimits& limits);

  ChunkResult add(const ChunkHeader& header, std::span<const uint8_t> data);

  /// Forgets the transfer in progress (or the completed one) and frees its
  /// memory.
  void reset();

  /// True while a transfer has started (complete or not).
  bool active() const { return active_; }
  bool complete() const { return active_ && received_ == header_.count; }
  /// The transfer's first chunk's header (index aside); meaningful while active().
  const ChunkHeader& header() const { return header_; }
  uint32_t chunks_received() const { return received_; }
  /// The whole blob once complete(); empty before. Valid until the next
  /// add() or reset().
  std::span<const uint8_t> blob() const;
  const ChunkLimits& limits() const { return limits_; }

 private:
  /// Checks a header against itself and the limits (not the transfer).
  bool well_formed(const ChunkHeader& header, size_t data_size) const;

  ChunkLimits limits_;
  bool active_ = false;
  ChunkHeader header_;
  uint32_t received_ = 0;
  std::vector<uint8_t> bytes_;  // total_size long while active
  std::vector<uint8_t> have_;   // one flag per chunk
};

}  // namespace rwd::net
