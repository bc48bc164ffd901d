// SPDX-License-Identifier: MIT
// Runs fuzz_sim_snapshot_one over real snapshots of a played match, every
// truncation of one, single-byte and stacked mutations, and random bytes.
#include <gtest/gtest.h>

#include <vector>

#include "corpus_mutator.h"
#include "fuzz_entries.h"
#include "rewind/game/simulation.h"

namespace {

std::vector<uint8_t> snapshot_after(int ticks) {
  auto sim = std::move(*rwd::game::Simulation::create("crates", {4, 7}));
  std::vector<rwd::PlayerInput> inputs(4);
  for (int t = 0; t < ticks; ++t) {
    for (int p = 0; p < 4; ++p)
      inputs[static_cast<size_t>(p)] =
          rwd::stick_input(int16_t((t * 37 + p * 500) % 2001 - 1000), 0);
    EXPECT_TRUE(sim->step(inputs).ok());
  }
  std::vector<uint8_t> bytes;
  sim->serialize(bytes);
  return bytes;
}

TEST(FuzzCorpusSimSnapshot, ValidSnapshotsRoundTrip) {
  for (int ticks : {0, 1, 90}) {
    const std::vector<uint8_t> bytes = snapshot_after(ticks);
    EXPECT_EQ(fuzz_sim_snapshot_one(bytes.data(), bytes.size()), 0);
  }
}

TEST(FuzzCorpusSimSnapshot, TruncationsMutationsAndNoise) {
  const std::vector<uint8_t> base = snapshot_after(90);
  for (size_t cut = 0; cut < base.size(); cut += 7) {
    fuzz_sim_snapshot_one(base.data(), cut);
  }
  // Single-byte changes mostly land in float fields (accepted) or counts and
  // indices (refused); stacked mutations and splices reach the rest.
  EXPECT_EQ(
      rwd::fuzz::run_stacked_mutations({base, snapshot_after(3)}, 99, 3000, fuzz_sim_snapshot_one),
      0);
  rwd::fuzz::CorpusRng rng{7};
  for (int i = 0; i < 300; ++i) {
    std::vector<uint8_t> noise(rng.below(4096));
    for (uint8_t& b : noise) b = static_cast<uint8_t>(rng.next());
    fuzz_sim_snapshot_one(noise.data(), noise.size());
  }
}

}  // namespace
