// SPDX-License-Identifier: MIT
#include "rewind/fixed/fx_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "rewind/fixed/fx_literal.h"
#include "rewind/fixed/wide_int.h"
#include "splitmix.h"

namespace rwd::fixed {
namespace {

TEST(FixedIntegerSqrt, IsExactFloorForEveryWidth) {
  EXPECT_EQ(isqrt64(0), 0u);
  EXPECT_EQ(isqrt64(UINT64_MAX), 4294967295u);
  EXPECT_EQ(isqrt128(~U128{0}), static_cast<U128>(UINT64_MAX));
  // Each side of a power of four, and where isqrt128 hands over to isqrt64.
  for (uint64_t n : {1u, 2u, 3u, 4u, 5u, 15u, 16u, 17u}) {
    EXPECT_EQ(isqrt64(n), n < 4 ? 1u : (n < 9 ? 2u : (n < 16 ? 3u : 4u))) << n;
  }
  EXPECT_EQ(isqrt128(U128{1} << 64), U128{1} << 32);
  EXPECT_EQ(isqrt128((U128{1} << 64) - 1), (U128{1} << 32) - 1);
  EXPECT_EQ(isqrt128((U128{1} << 64) + 1), U128{1} << 32);
  EXPECT_EQ(isqrt128(U128{1} << 126), U128{1} << 63);
  EXPECT_EQ(isqrt128((U128{1} << 126) - 1), (U128{1} << 63) - 1);
  SplitMix64 rng{21};
  for (int i = 0; i < 100000; ++i) {
    const uint64_t n = rng.next() >> rng.below(64);
    const uint64_t s = isqrt64(n);
    ASSERT_LE(static_cast<U128>(s) * s, n);
    ASSERT_GT(static_cast<U128>(s + 1) * (s + 1), n);
    const U128 wide = (static_cast<U128>(rng.next()) << 64 | rng.next()) >> rng.below(128);
    const U128 w = isqrt128(wide);
    ASSERT_LE(w * w, wide);
    ASSERT_GT((w + 1) * (w + 1), wide);  // w < 2^64, so this cannot wrap
  }
}

TEST(FixedFxSqrt, IsExactForPerfectSquares) {
  for (int32_t k = 0; k <= 181; ++k) EXPECT_EQ(sqrt(Fx(k * k)), Fx(k)) << k;
  EXPECT_EQ(sqrt(0.25_fx), 0.5_fx);
  EXPECT_EQ(sqrt(Fx::ratio(1, 16)), 0.25_fx);
}

TEST(FixedFxSqrt, IsTheNearestFxToTheTrueRoot) {
  SplitMix64 rng{22};
  for (int i = 0; i < 200000; ++i) {
    const int32_t raw =
        static_cast<int32_t>(static_cast<uint32_t>(rng.next()) >> 1 >> rng.below(31));
    const int64_t r = sqrt(Fx::from_raw(raw)).raw();
    // r is nearest to sqrt(n) for n = raw * 2^16  <=>  (2r-1)^2 <= 4n <= (2r+1)^2.
    const I128 four_n = static_cast<I128>(raw) * 65536 * 4;
    if (r > 0) {
      ASSERT_LE(static_cast<I128>(2 * r - 1) * (2 * r - 1), four_n) << raw;
    }
    ASSERT_GE(static_cast<I128>(2 * r + 1) * (2 * r + 1), four_n) << raw;
    // And within half an ulp of the analytic value.
    const long double truth = std::sqrt(static_cast<long double>(raw) / 65536.0L) * 65536.0L;
    ASSERT_LE(std::fabs(static_cast<long double>(r) - truth), 0.5L) << raw;
  }
  EXPECT_EQ(sqrt(Fx::max()).raw(), 11863283);  // sqrt(32768 - 2^-16) * 65536 = 11863283.2
  EXPECT_EQ(sqrt(Fx::epsilon()).raw(), 256);
}

TEST(FixedFxSqrt, NegativeInputIsZeroOrRefused) {
  EXPECT_EQ(sqrt(Fx(-4)), Fx::zero());
  EXPECT_EQ(sqrt(Fx::min()), Fx::zero());
  const Result<Fx> refused = checked_sqrt(Fx(-4));
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_NE(refused.status().message().find("negative"), std::string::npos);
  EXPECT_EQ(*checked_sqrt(Fx(9)), Fx(3));
}

TEST(FixedFxSqrt, WideArgumentKeepsSmallValues) {
  // sqrt(2^-32) = 2^-16: an Fx argument could not even represent 2^-32.
  EXPECT_EQ(sqrt(FxWide::from_raw(1)), Fx::epsilon());
  EXPECT_EQ(sqrt(FxWide(Fx(4))), Fx(2));
  EXPECT_EQ(sqrt(FxWide::from_raw(INT64_MAX)), Fx::max());  // 2^31.5 > range
}

TEST(FixedFxRsqrt, IsWithinOneUlpAndRefusesNonPositive) {
  SplitMix64 rng{23};
  for (int i = 0; i < 50000; ++i) {
    const int32_t raw =
        1 + static_cast<int32_t>(static_cast<uint32_t>(rng.next()) >> 1 >> rng.below(31));
    const Result<Fx> r = checked_rsqrt(Fx::from_raw(raw));
    ASSERT_TRUE(r.ok());
    long double truth = 65536.0L / std::sqrt(static_cast<long double>(raw) / 65536.0L);
    if (truth > INT32_MAX) truth = INT32_MAX;
    ASSERT_LE(std::fabs(static_cast<long double>(r->raw()) - truth), 1.0L) << raw;
  }
  EXPECT_EQ(*checked_rsqrt(Fx(4)), 0.5_fx);
  EXPECT_FALSE(checked_rsqrt(Fx::zero()).ok());
  EXPECT_FALSE(checked_rsqrt(Fx(-1)).ok());
}

TEST(FixedFxDiv, CheckedDivisionRefusesZero) {
  const Result<Fx> refused = checked_div(Fx(1), Fx::zero());
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(*checked_div(Fx(1), Fx(4)), 0.25_fx);
}

}  // namespace
}  // namespace rwd::fixed
