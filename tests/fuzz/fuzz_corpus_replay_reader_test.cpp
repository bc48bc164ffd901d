// SPDX-License-Identifier: MIT
// Runs fuzz_replay_reader_one over a deterministic corpus so CI exercises the
// fuzz target without libFuzzer: sample replays in both modes (hashes as
// given, hashes repaired), all their truncations, stacked mutations and
// random bytes. A broken invariant aborts, which fails the test.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "corpus_mutator.h"
#include "fuzz_entries.h"
#include "rewind/replay/replay_format.h"

namespace {

using Rng = rwd::fuzz::CorpusRng;

// A small replay: header (of format `format`), `ticks` ticks with a
// keyframe after tick 1, and an end record when `finished`.
std::vector<uint8_t> sample_replay(int ticks, bool finished,
                                   uint32_t format = rwd::replay::kFormatVersion) {
  std::vector<uint8_t> out(rwd::replay::kMagic.begin(), rwd::replay::kMagic.end());
  rwd::v1::ReplayRecord r;
  rwd::v1::ReplayHeader* h = r.mutable_header();
  h->set_format_version(format);
  h->set_game("crates");
  h->set_player_count(2);
  h->set_seed(9);
  if (format >= 2) {
    h->set_engine("rewind-sim");
    h->set_sim_revision(2);
    h->set_rules_version(2);
    h->set_world_config(std::string(61, '\x02'));
  }
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
  // Current format, finished and not; the oldest format; a newer one.
  for (const std::vector<uint8_t>& file :
       {sample_replay(4, true), sample_replay(3, false),
        sample_replay(3, true, rwd::replay::kOldestFormatVersion),
        sample_replay(2, true, rwd::replay::kFormatVersion + 1)}) {
    for (uint8_t mode : {0, 1}) {
      std::vector<uint8_t> input{mode};
      input.insert(input.end(), file.begin(), file.end());
      out.push_back(input);
    }
  }
  return out;
}

TEST(FuzzCorpusReplayReader, SeedsAndTruncations) {
  EXPECT_EQ(rwd::fuzz::run_truncations(seeds(), fuzz_replay_reader_one), 0);
}

TEST(FuzzCorpusReplayReader, StackedMutations) {
  EXPECT_EQ(rwd::fuzz::run_stacked_mutations(seeds(), 0x5EED'0F'BADC'0FFEull, 20'000,
                                             fuzz_replay_reader_one),
            0);
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
