// SPDX-License-Identifier: MIT
// Runs fuzz_envelope_one over a deterministic corpus so CI exercises the fuzz
// target without libFuzzer: every sample envelope, all its truncations,
// mutations (bit flips, byte sets, insertions, deletions, splices) and random
// bytes. A broken invariant aborts, which fails the test.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "envelope_samples.h"
#include "fuzz_entries.h"

namespace {

struct Rng {
  uint64_t state;
  uint64_t next() {
    state += 0x9E37'79B9'7F4A'7C15ull;
    uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58'476D'1CE4'E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D0'49BB'1331'11EBull;
    return z ^ (z >> 31);
  }
  size_t below(size_t n) { return n == 0 ? 0 : static_cast<size_t>(next() % n); }
};

std::vector<std::vector<uint8_t>> seeds() {
  std::vector<std::vector<uint8_t>> out;
  for (const rwd::v1::Envelope& e : rwd::net::testing::sample_envelopes()) {
    out.push_back(rwd::net::testing::raw_bytes(e));
  }
  return out;
}

void mutate(std::vector<uint8_t>& bytes, const std::vector<std::vector<uint8_t>>& pool, Rng& rng) {
  switch (rng.below(5)) {
    case 0:
      if (!bytes.empty())
        bytes[rng.below(bytes.size())] ^= static_cast<uint8_t>(1u << rng.below(8));
      break;
    case 1:
      if (!bytes.empty()) bytes[rng.below(bytes.size())] = static_cast<uint8_t>(rng.next());
      break;
    case 2:
      bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(rng.below(bytes.size() + 1)),
                   static_cast<uint8_t>(rng.next()));
      break;
    case 3:
      if (!bytes.empty())
        bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(rng.below(bytes.size())));
      break;
    default: {
      // Splice: a prefix of this input with a suffix of another.
      const std::vector<uint8_t>& other = pool[rng.below(pool.size())];
      bytes.resize(rng.below(bytes.size() + 1));
      const size_t from = rng.below(other.size() + 1);
      bytes.insert(bytes.end(), other.begin() + static_cast<std::ptrdiff_t>(from), other.end());
      break;
    }
  }
}

TEST(FuzzCorpusEnvelope, SeedsAndTruncations) {
  for (const std::vector<uint8_t>& seed : seeds()) {
    for (size_t cut = 0; cut <= seed.size(); ++cut) {
      EXPECT_EQ(fuzz_envelope_one(seed.data(), cut), 0);
    }
  }
}

TEST(FuzzCorpusEnvelope, StackedMutations) {
  const std::vector<std::vector<uint8_t>> pool = seeds();
  Rng rng{0xF0E1'D2C3'B4A5'9687ull};
  for (int i = 0; i < 20'000; ++i) {
    std::vector<uint8_t> bytes = pool[rng.below(pool.size())];
    const size_t rounds = 1 + rng.below(8);
    for (size_t r = 0; r < rounds; ++r) mutate(bytes, pool, rng);
    ASSERT_EQ(fuzz_envelope_one(bytes.data(), bytes.size()), 0);
  }
}

TEST(FuzzCorpusEnvelope, RandomBytes) {
  Rng rng{42};
  std::vector<uint8_t> bytes;
  for (int i = 0; i < 10'000; ++i) {
    bytes.resize(rng.below(1300));
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng.next());
    ASSERT_EQ(fuzz_envelope_one(bytes.data(), bytes.size()), 0);
  }
  // Zero-length input with a null pointer, as libFuzzer may pass.
  EXPECT_EQ(fuzz_envelope_one(nullptr, 0), 0);
}

}  // namespace
