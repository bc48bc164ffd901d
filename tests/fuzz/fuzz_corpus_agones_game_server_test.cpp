// SPDX-License-Identifier: MIT
// Runs fuzz_agones_game_server_one over a deterministic corpus: GameServer
// records as the Agones sidecar answers them (with match settings in their
// annotations and labels) and documents exercising the JSON grammar and its
// bounds, all their truncations and mutations, and random bytes. A broken
// invariant aborts, failing the test.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "corpus_mutator.h"
#include "fuzz_entries.h"

namespace {

std::vector<std::vector<uint8_t>> seeds() {
  const std::vector<std::string> texts = {
      R"({"object_meta":{"name":"rewind-x7k2p","namespace":"default","uid":"1234",)"
      R"("resource_version":"v1","generation":"1","creation_timestamp":"1531795395",)"
      R"("annotations":{"rewind.dev/players":"4","rewind.dev/ticks":"3600"},)"
      R"("labels":{"agones.dev/fleet":"rewind"}},"status":{"state":"Allocated",)"
      R"("address":"203.0.113.7","ports":[{"name":"default","port":7193}]}})",
      R"({"object_meta":{"annotations":{"rewind.dev/game":"arena","rewind.dev/seed":"77",)"
      R"("rewind.dev/join-timeout":"2.5","rewind.dev/match-id":"duel-7",)"
      R"("rewind.dev/window":"12"},"labels":{"rewind.dev/players":"3",)"
      R"("rewind.dev/tick-rate":"30","rewind.dev/spectators":"2"}}})",
      R"({"status":{"state":"Ready","ports":[{"name":"a","port":"7777"},{"port":7.5e3}]},)"
      R"("object_meta":null})",
      R"({"x":[1,-0,0.5,-12.5e-3,1E+300,1e-400,true,false,null,"",[],{},[[[[[[[1]]]]]]]]})",
      R"({"object_meta":{"name":"\"\\\/\b\f\n\r\t\u0041\u00e9\ud83d\ude00","labels":)"
      R"({"u":"é😀","k":"\u0000"}}})",
      R"({"a":{"a":1},"a":2})",
      "{\"d\":" + std::string(31, '[') + std::string(31, ']') + "}",
      "{\"d\":" + std::string(32, '[') + std::string(32, ']') + "}",
      " \t\r\n{} ",
  };
  std::vector<std::vector<uint8_t>> out;
  for (const std::string& text : texts) out.emplace_back(text.begin(), text.end());
  return out;
}

TEST(FuzzCorpusAgonesGameServer, SeedsAndTruncations) {
  EXPECT_EQ(rwd::fuzz::run_truncations(seeds(), fuzz_agones_game_server_one), 0);
}

TEST(FuzzCorpusAgonesGameServer, StackedMutations) {
  EXPECT_EQ(rwd::fuzz::run_stacked_mutations(seeds(), 0x4A53'4F4E'5245'4144ull, 30'000,
                                             fuzz_agones_game_server_one),
            0);
}

TEST(FuzzCorpusAgonesGameServer, RandomBytes) {
  rwd::fuzz::CorpusRng rng{7};
  const std::string alphabet = "{}[],:\"\\ntrufalse0123456789.eE+-u \xC3\xA9\xED\xF0";
  std::vector<uint8_t> bytes;
  for (int i = 0; i < 10'000; ++i) {
    bytes.resize(rng.below(200));
    // Half from the grammar's own characters, so structure is reached.
    const bool grammar = i % 2 == 0;
    for (uint8_t& b : bytes) {
      b = grammar ? static_cast<uint8_t>(alphabet[rng.below(alphabet.size())])
                  : static_cast<uint8_t>(rng.next());
    }
    ASSERT_EQ(fuzz_agones_game_server_one(bytes.data(), bytes.size()), 0);
  }
  EXPECT_EQ(fuzz_agones_game_server_one(nullptr, 0), 0);
}

}  // namespace
