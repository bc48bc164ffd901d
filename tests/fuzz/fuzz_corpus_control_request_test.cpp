// SPDX-License-Identifier: MIT
// Runs fuzz_control_request_one over a deterministic corpus: real control
// calls and queries, all their truncations and mutations, and random bytes.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "corpus_mutator.h"
#include "fuzz_entries.h"

namespace {

std::vector<std::vector<uint8_t>> seeds() {
  const std::string texts[] = {
      "POST /matches?id=duel-7&players=2&ticks=3600 HTTP/1.1\r\nHost: x\r\n"
      "Authorization: Bearer 0123456789abcdef0123456789abcdef\r\n\r\n",
      "GET /matches HTTP/1.1\r\nAuthorization: bearer fedcba9876543210fedcba9876543210\r\n\r\n",
      "DELETE /matches/bob-match HTTP/1.1\r\nContent-Length: 0\r\n"
      "Authorization: Bearer 0123456789abcdef0123456789abcdef\r\n\r\n",
      "DELETE /matches/alice-match HTTP/1.1\r\n"
      "Authorization: Bearer 00000000000000000000000000000000ffff\r\n\r\n",
      "POST /matches?id=..&join_timeout=86400 HTTP/1.1\r\n"
      "Authorization: Bearer 0123456789abcdef0123456789abcdef\r\nContent-Length: 3\r\n\r\nabc",
      "GET /metrics HTTP/1.0\r\n\r\n",
      "id=a&game=crates&players=4&spectators=2&tick_rate=30&window=8&seed=9&port=7000",
      "join_timeout=1.5&peer_timeout=0.25&ticks=0",
  };
  std::vector<std::vector<uint8_t>> out;
  for (const std::string& text : texts) out.emplace_back(text.begin(), text.end());
  return out;
}

TEST(FuzzCorpusControlRequest, SeedsAndTruncations) {
  EXPECT_EQ(rwd::fuzz::run_truncations(seeds(), fuzz_control_request_one), 0);
}

TEST(FuzzCorpusControlRequest, StackedMutations) {
  EXPECT_EQ(rwd::fuzz::run_stacked_mutations(seeds(), 0xC0'7781'0000'0001ull, 5'000,
                                             fuzz_control_request_one),
            0);
}

TEST(FuzzCorpusControlRequest, RandomBytes) {
  rwd::fuzz::CorpusRng rng{11};
  std::vector<uint8_t> bytes;
  for (int i = 0; i < 2'000; ++i) {
    bytes.resize(rng.below(1200));
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng.next());
    ASSERT_EQ(fuzz_control_request_one(bytes.data(), bytes.size()), 0);
  }
  EXPECT_EQ(fuzz_control_request_one(nullptr, 0), 0);
}

}  // namespace
