// SPDX-License-Identifier: MIT
// Runs fuzz_view_bundle_one over real bundles (each built-in game, one with
// a desync report), every truncation, single-byte and stacked mutations,
// and random bytes.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "corpus_mutator.h"
#include "fuzz_entries.h"
#include "rewind/game/simulation.h"
#include "rewind/viewer/view_bundle.h"

namespace {

std::vector<uint8_t> bundle_of(const char* game, int ticks, bool desync) {
  rwd::viewer::ViewBundle b;
  b.game = game;
  b.setup = {2, 3};
  b.player_names = {"a", "b"};
  auto sim = std::move(*rwd::game::Simulation::create(game, b.setup));
  std::vector<rwd::PlayerInput> inputs(2);
  for (int t = 0; t < ticks; ++t) {
    for (int p = 0; p < 2; ++p) {
      inputs[static_cast<size_t>(p)] =
          rwd::stick_input(int16_t((t * 37 + p * 500) % 2001 - 1000), 300, 1);
    }
    EXPECT_TRUE(sim->step(inputs).ok());
    b.inputs.insert(b.inputs.end(), inputs.begin(), inputs.end());
    b.checksums.push_back(sim->checksum());
    b.substituted_masks.push_back(static_cast<uint64_t>(t % 3));
  }
  if (desync) {
    rwd::viewer::ViewDesync d;
    d.tick = 1;
    d.headline = "desync";
    auto client = std::move(*rwd::game::Simulation::create(game, b.setup));
    EXPECT_TRUE(client->step(std::span<const rwd::PlayerInput>(b.inputs).first(2)).ok());
    EXPECT_TRUE(client->step(std::span<const rwd::PlayerInput>(b.inputs).subspan(2, 2)).ok());
    client->serialize(d.client_state);
    b.desync = d;
    b.keyframes.push_back({2, d.client_state});  // the state after tick 1, to seek by
  }
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(rwd::viewer::encode_view_bundle(b, bytes).ok());
  return bytes;
}

TEST(FuzzCorpusViewBundle, ValidBundlesRoundTrip) {
  for (const char* game : {"crates", "arena", "joust"}) {
    for (bool desync : {false, true}) {
      const std::vector<uint8_t> bytes = bundle_of(game, 4, desync);
      EXPECT_EQ(fuzz_view_bundle_one(bytes.data(), bytes.size()), 0);
    }
  }
}

TEST(FuzzCorpusViewBundle, TruncationsMutationsAndNoise) {
  const std::vector<uint8_t> base = bundle_of("arena", 4, true);
  for (size_t cut = 0; cut < base.size(); cut += 5) fuzz_view_bundle_one(base.data(), cut);
  EXPECT_EQ(rwd::fuzz::run_stacked_mutations({base, bundle_of("crates", 3, false)}, 41, 1500,
                                             fuzz_view_bundle_one),
            0);
  rwd::fuzz::CorpusRng rng{11};
  for (int i = 0; i < 300; ++i) {
    std::vector<uint8_t> noise(rng.below(512));
    for (uint8_t& b : noise) b = static_cast<uint8_t>(rng.next());
    if (noise.size() >= 8 && i % 2 == 0) std::memcpy(noise.data(), "RWDVIEW1", 8);
    fuzz_view_bundle_one(noise.data(), noise.size());
  }
}

}  // namespace
