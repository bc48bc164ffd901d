// SPDX-License-Identifier: MIT
// Runs fuzz_http_response_one over a deterministic corpus: responses framed
// by Content-Length, by chunks (with extensions and trailers) and by the
// connection's end, with conflicting framings, all their truncations and
// mutations, and random bytes.
// A broken invariant aborts, failing the test.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "corpus_mutator.h"
#include "fuzz_entries.h"

namespace {

std::vector<std::vector<uint8_t>> seeds() {
  const std::vector<std::string> texts = {
      "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: 2\r\n\r\n{}",
      "HTTP/1.1 200 OK\r\nTransfer-Encoding: chunked\r\n\r\n"
      "4\r\n{\"a\"\r\na;x=1\r\n:123456789\r\n0\r\nX-T: 1\r\n\r\n",
      "HTTP/1.0 404 Not Found\r\nServer: x\r\n\r\nnot found",
      "HTTP/1.1 204 No Content\r\n\r\n",
      "HTTP/1.1 500\r\nContent-Length: 0\r\n\r\n",
      "HTTP/1.1 200 OK\r\nContent-Length: 3, 3\r\nTransfer-Encoding: gzip\r\n\r\nabc",
      "HTTP/1.1 100 Continue\r\n\r\nHTTP/1.1 200 OK\r\n\r\n{}",
  };
  std::vector<std::vector<uint8_t>> out;
  for (const std::string& text : texts) out.emplace_back(text.begin(), text.end());
  return out;
}

TEST(FuzzCorpusHttpResponse, SeedsAndTruncations) {
  EXPECT_EQ(rwd::fuzz::run_truncations(seeds(), fuzz_http_response_one), 0);
}

TEST(FuzzCorpusHttpResponse, StackedMutations) {
  EXPECT_EQ(rwd::fuzz::run_stacked_mutations(seeds(), 0x4854'5450'2F31'2E31ull, 30'000,
                                             fuzz_http_response_one),
            0);
}

TEST(FuzzCorpusHttpResponse, RandomBytes) {
  rwd::fuzz::CorpusRng rng{11};
  std::vector<uint8_t> bytes;
  for (int i = 0; i < 10'000; ++i) {
    bytes.resize(rng.below(300));
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng.next());
    ASSERT_EQ(fuzz_http_response_one(bytes.data(), bytes.size()), 0);
  }
  EXPECT_EQ(fuzz_http_response_one(nullptr, 0), 0);
}

}  // namespace
