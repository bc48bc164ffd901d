// SPDX-License-Identifier: MIT
// wdiv's fast path (the processor's 128-by-64-bit division where the
// quotient fits) against the plain 128-bit division it stands in for.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>

#include "rewind/sim2d/detail/wmath.h"

namespace rwd::sim2d::test {
namespace {

using detail::I128;
using detail::kWFrac;
using detail::W;
using detail::wdiv;

W reference_divide(W a, W b) {
  return b == 0 ? 0 : static_cast<W>((static_cast<I128>(a) << kWFrac) / b);
}

TEST(WDivide, MatchesThe128BitDivisionOnEdges) {
  constexpr W kMin = std::numeric_limits<W>::min();
  constexpr W kMax = std::numeric_limits<W>::max();
  const W values[] = {0,
                      1,
                      -1,
                      2,
                      -2,
                      kMin,
                      kMax,
                      kMin + 1,
                      W{1} << 31,
                      -(W{1} << 31),
                      W{1} << 32,
                      -(W{1} << 32),
                      (W{1} << 32) + 1,
                      -(W{1} << 32) - 1,
                      W{3} << 40,
                      12345678901LL,
                      -987654321012LL};
  for (const W a : values) {
    for (const W b : values) {
      EXPECT_EQ(wdiv(a, b), reference_divide(a, b)) << a << " / " << b;
    }
  }
  // Where the fast path hands over: |a| just under and at |b| 2^31.
  for (const W b : {W{1}, W{3}, W{1} << 20, W{1} << 31, -(W{7} << 25)}) {
    const W edge = (b < 0 ? -b : b) << 31;
    for (const W a : {edge - 1, edge, edge + 1, -edge + 1, -edge, -edge - 1}) {
      EXPECT_EQ(wdiv(a, b), reference_divide(a, b)) << a << " / " << b;
    }
  }
}

TEST(WDivide, MatchesThe128BitDivisionOnRandomValues) {
  std::mt19937_64 rng(20261129);
  for (int i = 0; i < 200000; ++i) {
    // Mixed magnitudes: shift random words down by random amounts so
    // small, large and fast-path-refused quotients all come up.
    const W a = static_cast<W>(rng()) >> (rng() % 64);
    const W b = static_cast<W>(rng()) >> (rng() % 64);
    ASSERT_EQ(wdiv(a, b), reference_divide(a, b)) << a << " / " << b;
  }
}

}  // namespace
}  // namespace rwd::sim2d::test
