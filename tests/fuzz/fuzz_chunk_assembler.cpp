// SPDX-License-Identifier: MIT
// The chunk assembler fed arbitrary chunk sequences. The input is read as
// a series of chunks, each a 10-byte header
//   transfer id u8 | index u16 | count u16 | total size u24 | context u8 |
//   data length u8
// followed by that many data bytes (fewer when the input runs out), under
// small limits (16-byte chunks, at most 8) so whole transfers are common.
// A plain model of the documented rules follows along; any difference
// between the two, a blob that is not exactly the chunks given, or more
// memory than the limits allow is a broken invariant.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <span>
#include <vector>

#include "fuzz_entries.h"
#include "rewind/net/chunked_transfer.h"

namespace {

using rwd::net::ChunkAssembler;
using rwd::net::ChunkHeader;
using rwd::net::ChunkLimits;
using rwd::net::ChunkResult;

constexpr ChunkLimits kLimits{16, 8};
constexpr size_t kHeaderBytes = 10;

[[noreturn]] void invariant_broken(const char* what) {
  std::fprintf(stderr, "fuzz_chunk_assembler: invariant broken: %s\n", what);
  std::abort();
}

// The rules of chunked_transfer.h, written out the slow way.
struct Model {
  bool active = false;
  ChunkHeader transfer;
  std::map<uint32_t, std::vector<uint8_t>> chunks;

  static bool well_formed(const ChunkHeader& h, size_t size) {
    if (h.total_size == 0 || h.total_size > kLimits.max_blob_bytes()) return false;
    const uint64_t count = (uint64_t{h.total_size} + kLimits.chunk_bytes - 1) / kLimits.chunk_bytes;
    if (h.count != count || h.index >= h.count) return false;
    const uint64_t last = h.total_size - uint64_t{h.count - 1} * kLimits.chunk_bytes;
    return size == (h.index + 1 == h.count ? last : kLimits.chunk_bytes);
  }

  ChunkResult add(const ChunkHeader& h, std::span<const uint8_t> data) {
    if (!well_formed(h, data.size())) return ChunkResult::kRejected;
    if (active && h.transfer_id == transfer.transfer_id) {
      if (h.count != transfer.count || h.total_size != transfer.total_size ||
          h.context != transfer.context) {
        return ChunkResult::kRejected;
      }
      if (chunks.count(h.index) != 0) return ChunkResult::kDuplicate;
    } else {
      active = true;
      transfer = h;
      chunks.clear();
    }
    chunks[h.index].assign(data.begin(), data.end());
    return chunks.size() == transfer.count ? ChunkResult::kComplete : ChunkResult::kAccepted;
  }

  std::vector<uint8_t> blob() const {
    std::vector<uint8_t> out;
    for (const auto& [index, bytes] : chunks) out.insert(out.end(), bytes.begin(), bytes.end());
    return out;
  }
};

}  // namespace

int fuzz_chunk_assembler_one(const uint8_t* data, size_t size) {
  ChunkAssembler assembler(kLimits);
  Model model;
  size_t at = 0;
  while (size - at >= kHeaderBytes) {
    const uint8_t* p = data + at;
    ChunkHeader header;
    header.transfer_id = p[0] % 4;
    header.index = p[1] | (p[2] << 8);
    header.count = p[3] | (p[4] << 8);
    header.total_size = p[5] | (p[6] << 8) | (static_cast<uint32_t>(p[7]) << 16);
    header.context = {uint64_t{p[8]} % 2, 7, 0};
    const size_t wanted = p[9];
    at += kHeaderBytes;
    const size_t length = std::min(wanted, size - at);
    const std::span<const uint8_t> chunk(data + at, length);
    at += length;

    const uint32_t received_before = assembler.chunks_received();
    const ChunkResult got = assembler.add(header, chunk);
    const ChunkResult expected = model.add(header, chunk);
    if (got != expected) invariant_broken("the assembler and the model disagree");
    if ((got == ChunkResult::kRejected || got == ChunkResult::kDuplicate) &&
        assembler.chunks_received() != received_before) {
      invariant_broken("a refused or repeated chunk changed the transfer");
    }
    if (assembler.active() != model.active) invariant_broken("active differs");
    if (!model.active) continue;
    if (assembler.header().transfer_id != model.transfer.transfer_id ||
        assembler.chunks_received() != model.chunks.size()) {
      invariant_broken("the transfer in progress differs");
    }
    if (assembler.header().total_size > kLimits.max_blob_bytes()) {
      invariant_broken("a transfer larger than the limits was started");
    }
    if (assembler.complete() != (model.chunks.size() == model.transfer.count)) {
      invariant_broken("completion differs");
    }
    const std::span<const uint8_t> blob = assembler.blob();
    if (assembler.complete()) {
      const std::vector<uint8_t> expected_blob = model.blob();
      if (blob.size() != model.transfer.total_size ||
          !std::equal(blob.begin(), blob.end(), expected_blob.begin(), expected_blob.end())) {
        invariant_broken("the blob is not the chunks given");
      }
    } else if (!blob.empty()) {
      invariant_broken("an incomplete transfer shows a blob");
    }
  }
  assembler.reset();
  if (assembler.active() || !assembler.blob().empty()) invariant_broken("reset kept something");
  return 0;
}
