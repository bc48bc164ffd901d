// SPDX-License-Identifier: MIT
// Runs fuzz_world3d_snapshot_one over snapshots of a jointed 3D world
// (every joint kind, a joint tree, a break), every truncation of one,
// single-byte and stacked mutations, and random bytes.
#include <gtest/gtest.h>

#include <vector>

#include "corpus_mutator.h"
#include "fuzz_entries.h"
#include "jointed_world.h"

namespace {

std::vector<uint8_t> snapshot_after(int ticks) {
  rwd::sim::World3D world;
  rwd::fuzz::build_jointed_world(world, ticks);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  return bytes;
}

TEST(FuzzCorpusWorld3DSnapshot, ValidSnapshotsRoundTrip) {
  for (int ticks : {0, 1, 60}) {
    const std::vector<uint8_t> bytes = snapshot_after(ticks);
    EXPECT_EQ(fuzz_world3d_snapshot_one(bytes.data(), bytes.size()), 0);
  }
}

TEST(FuzzCorpusWorld3DSnapshot, TruncationsMutationsAndNoise) {
  const std::vector<uint8_t> base = snapshot_after(60);
  for (size_t cut = 0; cut < base.size(); cut += 5) fuzz_world3d_snapshot_one(base.data(), cut);
  EXPECT_EQ(rwd::fuzz::run_stacked_mutations({base, snapshot_after(2)}, 41, 2000,
                                             fuzz_world3d_snapshot_one),
            0);
  rwd::fuzz::CorpusRng rng{11};
  for (int i = 0; i < 200; ++i) {
    std::vector<uint8_t> noise(rng.below(2048));
    for (uint8_t& b : noise) b = static_cast<uint8_t>(rng.next());
    fuzz_world3d_snapshot_one(noise.data(), noise.size());
  }
}

}  // namespace
