// SPDX-License-Identifier: MIT
#pragma once
// What every fuzz corpus test does to its seeds, so that CI exercises each
// fuzz entry without libFuzzer: a seeded RNG, libFuzzer-style byte
// mutations, and a loop of stacked mutations over a seed pool.
#include <cstddef>
#include <cstdint>
#include <vector>
#include "rewind/core/splitmix64.h"

namespace rwd::fuzz {

/// splitmix64: deterministic, so a failing input can be reproduced.
struct CorpusRng : SplitMix64 {
  size_t below(size_t n) { return static_cast<size_t>(SplitMix64::below(n)); }
};

/// One mutation: flip a bit, replace, insert or erase a byte, or splice in
/// the tail of another pool entry.
inline void mutate(std::vector<uint8_t>& bytes, const std::vector<std::vector<uint8_t>>& pool,
                   CorpusRng& rng) {
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
      if (!bytes.empty()) {
        bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(rng.below(bytes.size())));
      }
      break;
    default: {
      const std::vector<uint8_t>& other = pool[rng.below(pool.size())];
      bytes.resize(rng.below(bytes.size() + 1));
      const size_t from = rng.below(other.size() + 1);
      bytes.insert(bytes.end(), other.begin() + static_cast<std::ptrdiff_t>(from), other.end());
      break;
    }
  }
}

/// Feeds `entry` `iterations` inputs, each a pool entry with 1-8 stacked
/// mutations. Returns the first non-zero result (the entries abort on a
/// broken invariant, which fails the test anyway).
template <class Entry>
int run_stacked_mutations(const std::vector<std::vector<uint8_t>>& pool, uint64_t seed,
                          int iterations, Entry entry) {
  CorpusRng rng{seed};
  for (int i = 0; i < iterations; ++i) {
    std::vector<uint8_t> bytes = pool[rng.below(pool.size())];
    const size_t rounds = 1 + rng.below(8);
    for (size_t r = 0; r < rounds; ++r) mutate(bytes, pool, rng);
    if (int result = entry(bytes.data(), bytes.size()); result != 0) return result;
  }
  return 0;
}

/// Feeds `entry` every prefix of every seed (the empty one included).
template <class Entry>
int run_truncations(const std::vector<std::vector<uint8_t>>& seeds, Entry entry) {
  for (const std::vector<uint8_t>& seed : seeds) {
    for (size_t cut = 0; cut <= seed.size(); ++cut) {
      if (int result = entry(seed.data(), cut); result != 0) return result;
    }
  }
  return 0;
}

}  // namespace rwd::fuzz
