// SPDX-License-Identifier: MIT
#include "rewind/net/chunked_transfer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace rwd::net {
namespace {

std::vector<uint8_t> blob_of(size_t size, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint8_t> out(size);
  for (uint8_t& b : out) b = static_cast<uint8_t>(rng());
  return out;
}

ChunkHeader header_for(uint32_t id, uint32_t index, size_t total, const ChunkLimits& limits) {
  return {id, index, *plan_chunks(total, limits), static_cast<uint32_t>(total), {42, 7, 0}};
}

TEST(ChunkedTransfer, PlansChunksWithinTheLimits) {
  const ChunkLimits limits{1000, 4};
  EXPECT_EQ(plan_chunks(0, limits).status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(*plan_chunks(1, limits), 1u);
  EXPECT_EQ(*plan_chunks(1000, limits), 1u);
  EXPECT_EQ(*plan_chunks(1001, limits), 2u);
  EXPECT_EQ(*plan_chunks(4000, limits), 4u);
  EXPECT_EQ(plan_chunks(4001, limits).status().code(), ErrorCode::kCapacity);
  EXPECT_EQ(kResyncChunkLimits.max_chunks, 1024u);
  EXPECT_EQ(kDesyncChunkLimits.max_chunks, 256u);
}

TEST(ChunkedTransfer, ChunksCoverTheBlobExactly) {
  const ChunkLimits limits{100, 16};
  const std::vector<uint8_t> blob = blob_of(350, 1);
  const uint32_t count = *plan_chunks(blob.size(), limits);
  ASSERT_EQ(count, 4u);
  std::vector<uint8_t> joined;
  for (uint32_t i = 0; i < count; ++i) {
    const auto part = chunk_at(blob, i, limits);
    EXPECT_EQ(part.size(), i + 1 < count ? 100u : 50u);
    joined.insert(joined.end(), part.begin(), part.end());
  }
  EXPECT_EQ(joined, blob);
}

TEST(ChunkedTransfer, AssemblesShuffledChunksAndIgnoresDuplicates) {
  const ChunkLimits limits = kResyncChunkLimits;
  const std::vector<uint8_t> blob = blob_of(5321, 2);
  const uint32_t count = *plan_chunks(blob.size(), limits);
  std::vector<uint32_t> order(count);
  for (uint32_t i = 0; i < count; ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937(3));

  ChunkAssembler assembler(limits);
  EXPECT_FALSE(assembler.active());
  for (size_t n = 0; n < order.size(); ++n) {
    const uint32_t i = order[n];
    const ChunkResult result =
        assembler.add(header_for(9, i, blob.size(), limits), chunk_at(blob, i, limits));
    EXPECT_EQ(result, n + 1 == order.size() ? ChunkResult::kComplete : ChunkResult::kAccepted);
    EXPECT_TRUE(assembler.blob().empty() || n + 1 == order.size());
    if (n + 1 < order.size()) {
      EXPECT_EQ(assembler.add(header_for(9, i, blob.size(), limits), chunk_at(blob, i, limits)),
                ChunkResult::kDuplicate);
    }
  }
  ASSERT_TRUE(assembler.complete());
  EXPECT_EQ(std::vector<uint8_t>(assembler.blob().begin(), assembler.blob().end()), blob);
  EXPECT_EQ(assembler.header().context[0], 42u);
  // More copies of a finished transfer change nothing.
  EXPECT_EQ(assembler.add(header_for(9, 0, blob.size(), limits), chunk_at(blob, 0, limits)),
            ChunkResult::kDuplicate);
  assembler.reset();
  EXPECT_FALSE(assembler.active());
  EXPECT_TRUE(assembler.blob().empty());
}

TEST(ChunkedTransfer, RefusesMalformedAndContradictingChunksLeavingTheTransferIntact) {
  const ChunkLimits limits{100, 4};
  const std::vector<uint8_t> blob = blob_of(250, 4);
  ChunkAssembler assembler(limits);
  ASSERT_EQ(assembler.add(header_for(1, 0, blob.size(), limits), chunk_at(blob, 0, limits)),
            ChunkResult::kAccepted);

  ChunkHeader h = header_for(1, 1, blob.size(), limits);
  const auto part = chunk_at(blob, 1, limits);
  auto refused = [&](ChunkHeader header, std::span<const uint8_t> data) {
    EXPECT_EQ(assembler.add(header, data), ChunkResult::kRejected);
    EXPECT_EQ(assembler.chunks_received(), 1u);
    EXPECT_EQ(assembler.header().transfer_id, 1u);
  };
  ChunkHeader bad = h;
  bad.index = 3;  // past the count
  refused(bad, part);
  bad = h;
  bad.count = 4;  // not what 250 bytes take
  refused(bad, part);
  refused(h, part.first(99));  // a middle chunk must be full
  bad = header_for(1, 2, blob.size(), limits);
  refused(bad, chunk_at(blob, 2, limits).first(10));  // the last holds exactly the rest
  bad = h;
  bad.total_size = 0;
  bad.count = 0;
  refused(bad, {});
  bad = h;
  bad.total_size = 401;  // over 4 x 100 bytes: never allocated
  bad.count = 5;
  refused(bad, part);
  bad = h;
  bad.total_size = 0xFFFF'FFFFu;
  bad.count = 0xFFFF'FFFFu / 100 + 1;
  refused(bad, part);
  // Same id, another shape or context: a contradiction, not a new transfer.
  const std::vector<uint8_t> longer = blob_of(300, 5);
  refused(header_for(1, 1, longer.size(), limits), chunk_at(longer, 1, limits));
  bad = h;
  bad.context[1] = 8;
  refused(bad, part);

  // The transfer still completes from its own chunks.
  EXPECT_EQ(assembler.add(h, part), ChunkResult::kAccepted);
  EXPECT_EQ(assembler.add(header_for(1, 2, blob.size(), limits), chunk_at(blob, 2, limits)),
            ChunkResult::kComplete);
  EXPECT_EQ(std::vector<uint8_t>(assembler.blob().begin(), assembler.blob().end()), blob);
}

TEST(ChunkedTransfer, ANewTransferReplacesTheOneInProgress) {
  const ChunkLimits limits{100, 4};
  const std::vector<uint8_t> first = blob_of(300, 6);
  const std::vector<uint8_t> second = blob_of(120, 7);
  ChunkAssembler assembler(limits);
  ASSERT_EQ(assembler.add(header_for(1, 0, first.size(), limits), chunk_at(first, 0, limits)),
            ChunkResult::kAccepted);
  ASSERT_EQ(assembler.add(header_for(2, 1, second.size(), limits), chunk_at(second, 1, limits)),
            ChunkResult::kAccepted);
  EXPECT_EQ(assembler.header().transfer_id, 2u);
  EXPECT_EQ(assembler.chunks_received(), 1u);
  // The old transfer's chunks no longer count; its late chunk starts it over.
  EXPECT_EQ(assembler.add(header_for(2, 0, second.size(), limits), chunk_at(second, 0, limits)),
            ChunkResult::kComplete);
  EXPECT_EQ(std::vector<uint8_t>(assembler.blob().begin(), assembler.blob().end()), second);
  EXPECT_EQ(assembler.add(header_for(1, 1, first.size(), limits), chunk_at(first, 1, limits)),
            ChunkResult::kAccepted);
  EXPECT_EQ(assembler.chunks_received(), 1u);
  EXPECT_TRUE(assembler.blob().empty());
}

}  // namespace
}  // namespace rwd::net
