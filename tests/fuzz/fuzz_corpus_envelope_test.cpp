// SPDX-License-Identifier: MIT
// Runs fuzz_envelope_one over a deterministic corpus so CI exercises the fuzz
// target without libFuzzer: every sample envelope, all its truncations,
// mutations (bit flips, byte sets, insertions, deletions, splices) and random
// bytes. A broken invariant aborts, which fails the test.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "corpus_mutator.h"
#include "envelope_samples.h"
#include "fuzz_entries.h"

namespace {

using Rng = rwd::fuzz::CorpusRng;

std::vector<std::vector<uint8_t>> seeds() {
  std::vector<std::vector<uint8_t>> out;
  for (const rwd::v1::Envelope& e : rwd::net::testing::sample_envelopes()) {
    out.push_back(rwd::net::testing::raw_bytes(e));
  }
  return out;
}

TEST(FuzzCorpusEnvelope, SeedsAndTruncations) {
  EXPECT_EQ(rwd::fuzz::run_truncations(seeds(), fuzz_envelope_one), 0);
}

TEST(FuzzCorpusEnvelope, StackedMutations) {
  EXPECT_EQ(rwd::fuzz::run_stacked_mutations(seeds(), 0xF0E1'D2C3'B4A5'9687ull, 20'000,
                                             fuzz_envelope_one),
            0);
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
