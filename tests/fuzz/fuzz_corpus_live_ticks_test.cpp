// SPDX-License-Identifier: MIT
// Runs fuzz_live_ticks_one over real batches (from tick 0 and later, with
// and without names), every truncation, single-byte and stacked mutations,
// and random bytes.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "corpus_mutator.h"
#include "fuzz_entries.h"
#include "rewind/core/stick_input.h"
#include "rewind/viewer/live_ticks.h"

namespace {

std::vector<uint8_t> batch_of(rwd::Tick first, int ticks, bool names) {
  rwd::viewer::LiveTicks b;
  b.player_count = 2;
  if (names) b.player_names = {"ann", ""};
  b.first_tick = first;
  b.newest_final = first + ticks + 3;
  for (int t = 0; t < ticks; ++t) {
    b.checksums.push_back(0x1234u + static_cast<uint64_t>(t));
    b.substituted_masks.push_back(static_cast<uint64_t>(t % 4));
    for (int p = 0; p < 2; ++p)
      b.inputs.push_back(rwd::stick_input(int16_t(t * 100 - 300), int16_t(p * 50), 3));
  }
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(rwd::viewer::encode_live_ticks(b, bytes).ok());
  return bytes;
}

TEST(FuzzCorpusLiveTicks, ValidBatchesRoundTrip) {
  for (rwd::Tick first : {0, 1, 40}) {
    for (bool names : {false, true}) {
      const std::vector<uint8_t> bytes = batch_of(first, 5, names);
      EXPECT_EQ(fuzz_live_ticks_one(bytes.data(), bytes.size()), 0);
    }
  }
}

TEST(FuzzCorpusLiveTicks, TruncationsMutationsAndNoise) {
  const std::vector<uint8_t> base = batch_of(0, 6, true);
  for (size_t cut = 0; cut < base.size(); ++cut) fuzz_live_ticks_one(base.data(), cut);
  EXPECT_EQ(rwd::fuzz::run_stacked_mutations({base, batch_of(2, 3, false)}, 43, 1500,
                                             fuzz_live_ticks_one),
            0);
  rwd::fuzz::CorpusRng rng{13};
  for (int i = 0; i < 300; ++i) {
    std::vector<uint8_t> noise(rng.below(256));
    for (uint8_t& b : noise) b = static_cast<uint8_t>(rng.next());
    if (noise.size() >= 8 && i % 2 == 0) std::memcpy(noise.data(), "RWDLIVE1", 8);
    fuzz_live_ticks_one(noise.data(), noise.size());
  }
}

}  // namespace
