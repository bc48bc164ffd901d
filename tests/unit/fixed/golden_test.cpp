// SPDX-License-Identifier: MIT
// Golden values: a fixed stream of inputs runs through every operation of
// the library and the raw results are hashed with XXH3-64 (the project's
// checksum). The expected hash was recorded once; any compiler, flag or
// architecture that produces a different bit anywhere changes it. If a
// deliberate change to the library's results is made, the new hash must be
// recorded together with the reason.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdint>
#include <cstdio>

#include "golden_digest.h"

namespace rwd::fixed {
namespace {

TEST(FixedGolden, LibraryResultsHashToTheRecordedValue) {
  const uint64_t digest = golden_digest();
  std::printf("fixed golden digest %016" PRIx64 "\n", digest);
  EXPECT_EQ(digest, 0x79a78593baefdf6eull);
}

}  // namespace
}  // namespace rwd::fixed
