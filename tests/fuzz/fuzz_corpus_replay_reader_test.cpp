// SPDX-License-Identifier: MIT
// Runs fuzz_replay_reader_one over a deterministic corpus so CI exercises the
// fuzz target without libFuzzer: sample replays in both modes (hashes as
// given, hashes repaired), all their truncations, stacked mutations and
// random bytes. A broken invariant aborts, which fails the test.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "fuzz_entries.h"
#include "rewind/replay/replay_format.h"

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

// A small replay: header, `ticks` ticks with a keyframe after tick 1, and
// an end record when `finished`.
std::vector<uint8_t> sample_replay(int ticks, bool finished) {
  std::vector<uint8_t> out(rwd::replay::kMagic.begin(), rwd::replay::kMagic.end());
  rwd::v1::ReplayRecord r;
  rwd::v1::ReplayHeader* h = r.mutable_header();
  h->set_format_version(rwd::replay::kFormatVersion);
  h->set_game("crates");
  h->set_player_count(2);
  h->set_seed(9);
  EXPECT_TRUE(rwd::replay::append_frame(r, out).ok());
  for (int t = 0; t < ticks; ++t) {
    r.Clear();
    r.mutable_tick()->set_tick(t);
    for (int p = 0; p < 2; ++p) {
      rwd::v1::Input* in = r.mutable_tick()->add_inputs();
      in->set_axis_x(100 * t - p);
      in->set_buttons(static_cast<uint32_t>(t & 3));
    }
    r.mutable_tick()->set_substituted_mask(t == 2 ? 2u : 0u);
    r.mutable_tick()->set_checksum(0x1234'5678ull * static_cast<uint64_t>(t + 1));
    EXPECT_TRUE(rwd::replay::append_frame(r, out).ok());
    if (t == 1) {
      r.Clear();
      r.mutable_keyframe()->set_tick(1);
      r.mutable_keyframe()->set_state(std::string(24, '\x5a'));
      EXPECT_TRUE(rwd::replay::append_frame(r, out).ok());
    }
  }
  if (finished) {
    r.Clear();
    r.mutable_end()->set_last_final_tick(ticks - 1);
    r.mutable_end()->set_reason("done");
    EXPECT_TRUE(rwd::replay::append_frame(r, out).ok());
  }
  return out;
}

// Every sample in both modes: the first byte selects hash repair.
std::vector<std::vector<uint8_t>> seeds() {
  std::vector<std::vector<uint8_t>> out;
  for (const std::vector<uint8_t>& file : {sample_replay(4, true), sample_replay(3, false)}) {
    for (uint8_t mode : {0, 1}) {
      std::vector<uint8_t> input{mode};
      input.insert(input.end(), file.begin(), file.end());
      out.push_back(input);
    }
  }
  return out;
}

void mutate(std::vector<uint8_t>& bytes, const std::vector<std::vector<uint8_t>>& pool, Rng& rng) {
  switch (rng.below(5)) {
    case 0:
      if (!bytes.empty()) {
        bytes[rng.below(bytes.size())] ^= static_cast<uint8_t>(1u << rng.below(8));
      }
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
      // Splice: a prefix of this input with a suffix of another.
      const std::vector<uint8_t>& other = pool[rng.below(pool.size())];
      bytes.resize(rng.below(bytes.size() + 1));
      const size_t from = rng.below(other.size() + 1);
      bytes.insert(bytes.end(), other.begin() + static_cast<std::ptrdiff_t>(from), other.end());
      break;
    }
  }
}

TEST(FuzzCorpusReplayReader, SeedsAndTruncations) {
  for (const std::vector<uint8_t>& seed : seeds()) {
    for (size_t cut = 0; cut <= seed.size(); ++cut) {
      EXPECT_EQ(fuzz_replay_reader_one(seed.data(), cut), 0);
    }
  }
}

TEST(FuzzCorpusReplayReader, StackedMutations) {
  const std::vector<std::vector<uint8_t>> pool = seeds();
  Rng rng{0x5EED'0F'BADC'0FFEull};
  for (int i = 0; i < 20'000; ++i) {
    std::vector<uint8_t> bytes = pool[rng.below(pool.size())];
    const size_t rounds = 1 + rng.below(8);
    for (size_t r = 0; r < rounds; ++r) mutate(bytes, pool, rng);
    ASSERT_EQ(fuzz_replay_reader_one(bytes.data(), bytes.size()), 0);
  }
}

TEST(FuzzCorpusReplayReader, RandomBytes) {
  Rng rng{7};
  std::vector<uint8_t> bytes;
  for (int i = 0; i < 10'000; ++i) {
    bytes.resize(rng.below(600));
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng.next());
    // Half of the inputs start with the magic so the frame parser is reached.
    if (i % 2 == 0 && bytes.size() > 9) {
      std::copy(rwd::replay::kMagic.begin(), rwd::replay::kMagic.end(), bytes.begin() + 1);
    }
    ASSERT_EQ(fuzz_replay_reader_one(bytes.data(), bytes.size()), 0);
  }
  EXPECT_EQ(fuzz_replay_reader_one(nullptr, 0), 0);
}

}  // namespace
