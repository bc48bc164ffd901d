// SPDX-License-Identifier: MIT
// Runs fuzz_sim_snapshot_one over real snapshots of a played match, every
// truncation of one, single-byte and stacked mutations, and random bytes.
#include <gtest/gtest.h>

#include <vector>

#include "fuzz_entries.h"
#include "rewind/game/simulation.h"

namespace {

uint64_t next(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::vector<uint8_t> snapshot_after(int ticks) {
  auto sim = std::move(*rwd::game::Simulation::create("crates", {4, 7}));
  std::vector<rwd::game::PlayerInput> inputs(4);
  for (int t = 0; t < ticks; ++t) {
    for (int p = 0; p < 4; ++p)
      inputs[static_cast<size_t>(p)] = {int16_t((t * 37 + p * 500) % 2001 - 1000), 0, 0};
    sim->step(inputs);
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
  uint64_t rng = 99;
  for (int i = 0; i < 3000; ++i) {
    std::vector<uint8_t> bytes = base;
    const int flips = 1 + static_cast<int>(next(rng) % 4);
    for (int f = 0; f < flips; ++f)
      bytes[next(rng) % bytes.size()] = static_cast<uint8_t>(next(rng));
    fuzz_sim_snapshot_one(bytes.data(), bytes.size());
  }
  for (int i = 0; i < 300; ++i) {
    std::vector<uint8_t> noise(next(rng) % 4096);
    for (uint8_t& b : noise) b = static_cast<uint8_t>(next(rng));
    fuzz_sim_snapshot_one(noise.data(), noise.size());
  }
}

}  // namespace
