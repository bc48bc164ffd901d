// SPDX-License-Identifier: MIT
// Runs fuzz_chunk_assembler_one over a deterministic corpus: whole
// transfers in order, reversed, with duplicates, interrupted by another
// transfer, contradicting themselves; their truncations and mutations; and
// random bytes. A broken invariant aborts, failing the test.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "corpus_mutator.h"
#include "fuzz_entries.h"

namespace {

// One chunk in the entry's input format (see fuzz_chunk_assembler.cpp).
void put_chunk(std::vector<uint8_t>& out, uint8_t id, uint16_t index, uint16_t count,
               uint32_t total, uint8_t context, uint8_t length, uint8_t fill) {
  const uint8_t header[] = {id,
                            static_cast<uint8_t>(index),
                            static_cast<uint8_t>(index >> 8),
                            static_cast<uint8_t>(count),
                            static_cast<uint8_t>(count >> 8),
                            static_cast<uint8_t>(total),
                            static_cast<uint8_t>(total >> 8),
                            static_cast<uint8_t>(total >> 16),
                            context,
                            length};
  out.insert(out.end(), std::begin(header), std::end(header));
  for (uint8_t i = 0; i < length; ++i) out.push_back(static_cast<uint8_t>(fill + i));
}

// A whole transfer of `total` bytes (16-byte chunks) in the given order.
std::vector<uint8_t> transfer(uint8_t id, uint32_t total, const std::vector<uint16_t>& order) {
  const auto count = static_cast<uint16_t>((total + 15) / 16);
  std::vector<uint8_t> out;
  for (uint16_t index : order) {
    const uint32_t length = index + 1 == count ? total - 16u * (count - 1u) : 16u;
    put_chunk(out, id, index, count, total, 0, static_cast<uint8_t>(length),
              static_cast<uint8_t>(index * 16));
  }
  return out;
}

std::vector<std::vector<uint8_t>> seeds() {
  std::vector<std::vector<uint8_t>> out;
  out.push_back(transfer(1, 50, {0, 1, 2, 3}));
  out.push_back(transfer(2, 128, {7, 6, 5, 4, 3, 2, 1, 0}));
  out.push_back(transfer(3, 40, {0, 0, 2, 2, 1, 1}));
  out.push_back(transfer(0, 1, {0}));
  std::vector<uint8_t> interrupted = transfer(1, 64, {0, 1});
  const std::vector<uint8_t> other = transfer(2, 20, {1, 0});
  interrupted.insert(interrupted.end(), other.begin(), other.end());
  const std::vector<uint8_t> rest = transfer(1, 64, {2, 3});
  interrupted.insert(interrupted.end(), rest.begin(), rest.end());
  out.push_back(interrupted);
  std::vector<uint8_t> contradicting = transfer(1, 64, {0});
  put_chunk(contradicting, 1, 1, 4, 64, 1, 16, 0);  // another context, same id
  put_chunk(contradicting, 1, 1, 5, 80, 0, 16, 0);  // another shape, same id
  put_chunk(contradicting, 1, 9, 4, 64, 0, 16, 0);  // index past the count
  put_chunk(contradicting, 1, 3, 4, 64, 0, 15, 0);  // a short last chunk
  const std::vector<uint8_t> finish = transfer(1, 64, {1, 2, 3});
  contradicting.insert(contradicting.end(), finish.begin(), finish.end());
  out.push_back(contradicting);
  std::vector<uint8_t> oversized;
  put_chunk(oversized, 1, 0, 9, 129, 0, 16, 0);  // one byte past the limits
  put_chunk(oversized, 1, 0, 0xFFFF, 0xFFFFFF, 0, 16, 0);
  out.push_back(oversized);
  return out;
}

TEST(FuzzCorpusChunkAssembler, SeedsAndTruncations) {
  EXPECT_EQ(rwd::fuzz::run_truncations(seeds(), fuzz_chunk_assembler_one), 0);
}

TEST(FuzzCorpusChunkAssembler, StackedMutations) {
  EXPECT_EQ(rwd::fuzz::run_stacked_mutations(seeds(), 0xC4A0'0000'0000'0001ull, 20'000,
                                             fuzz_chunk_assembler_one),
            0);
}

TEST(FuzzCorpusChunkAssembler, RandomBytes) {
  rwd::fuzz::CorpusRng rng{11};
  std::vector<uint8_t> bytes;
  for (int i = 0; i < 2'000; ++i) {
    bytes.resize(rng.below(600));
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng.next());
    ASSERT_EQ(fuzz_chunk_assembler_one(bytes.data(), bytes.size()), 0);
  }
  EXPECT_EQ(fuzz_chunk_assembler_one(nullptr, 0), 0);
}

}  // namespace
