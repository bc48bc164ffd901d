// SPDX-License-Identifier: MIT
#include "rewind/fixed/fx.h"

#include <gtest/gtest.h>

#include <cstdint>

#include "rewind/fixed/fx_literal.h"
#include "rewind/fixed/fx_wide.h"
#include "rewind/fixed/wide_int.h"
#include "splitmix.h"

namespace rwd::fixed {
namespace {

// Reference rounding written independently of the library: floor division
// on the doubled value, i.e. round(n / d) with ties away from zero.
int64_t ref_round_div(I128 n, I128 d) {
  if (d < 0) {
    n = -n;
    d = -d;
  }
  const I128 twice = 2 * n;
  I128 q = twice >= 0 ? (twice + d) / (2 * d) : -((-twice + d) / (2 * d));
  if (q > INT32_MAX) q = INT32_MAX;
  if (q < INT32_MIN) q = INT32_MIN;
  return static_cast<int64_t>(q);
}

TEST(FixedFx, ConstructsFromIntegersAndRawBits) {
  EXPECT_EQ(Fx(3).raw(), 3 * 65536);
  EXPECT_EQ(Fx(-1).raw(), -65536);
  EXPECT_EQ(Fx(32767).raw(), 32767 * 65536);
  EXPECT_EQ(Fx(-32768).raw(), INT32_MIN);
  EXPECT_EQ(Fx(40000), Fx::max());  // saturates
  EXPECT_EQ(Fx(-40000), Fx::min());
  EXPECT_EQ(Fx::from_raw(INT32_MIN).raw(), INT32_MIN);
  EXPECT_EQ(Fx::ratio(1, 3).raw(), 21845);
  EXPECT_EQ(Fx::ratio(-1, 3).raw(), -21845);
  EXPECT_EQ(Fx::ratio(1, 0), Fx::max());
  EXPECT_EQ(Fx::ratio(-5, 0), Fx::min());
  EXPECT_EQ(Fx::ratio(0, 0), Fx::zero());
}

TEST(FixedFx, DecimalLiteralsAreRoundedExactlyAtCompileTime) {
  static_assert((0.1_fx).raw() == 6554);  // 6553.6 rounds up
  static_assert((1.5_fx).raw() == 98304);
  static_assert((0.00000762939453125_fx).raw() == 1);  // exactly half an ulp: away from zero
  static_assert((0.0000076293945312_fx).raw() == 0);   // just below half an ulp
  static_assert((32767_fx).raw() == 32767 * 65536);
  static_assert((1'000.25_fx).raw() == 1000 * 65536 + 16384);
  EXPECT_EQ((-2.5_fx).raw(), -163840);
}

TEST(FixedFx, RoundsIntegerParts) {
  EXPECT_EQ((2.5_fx).round_int(), 3);
  EXPECT_EQ((-2.5_fx).round_int(), -3);
  EXPECT_EQ((-2.5_fx).floor_int(), -3);
  EXPECT_EQ((2.49_fx).round_int(), 2);
}

TEST(FixedFx, MultiplyRoundsToNearestTiesAwayFromZero) {
  // Half an ulp exactly: 1 raw * 0.5.
  EXPECT_EQ((Fx::epsilon() * Fx::half()).raw(), 1);
  EXPECT_EQ((-Fx::epsilon() * Fx::half()).raw(), -1);
  EXPECT_EQ((Fx::epsilon() * Fx::from_raw(32767)).raw(), 0);
  SplitMix64 rng{11};
  for (int i = 0; i < 200000; ++i) {
    const int32_t a = rng.raw_i32();
    const int32_t b = rng.raw_i32() >> rng.below(31);
    const int64_t want = ref_round_div(static_cast<I128>(a) * b, 65536);
    ASSERT_EQ((Fx::from_raw(a) * Fx::from_raw(b)).raw(), want) << a << " * " << b;
    // Symmetry that the rounding rule promises.
    ASSERT_EQ((Fx::from_raw(a) * Fx::from_raw(b)).raw(), (Fx::from_raw(b) * Fx::from_raw(a)).raw());
  }
}

TEST(FixedFx, DivideRoundsToNearestAndSaturates) {
  SplitMix64 rng{12};
  for (int i = 0; i < 200000; ++i) {
    const int32_t a = rng.raw_i32() >> rng.below(31);
    int32_t b = rng.raw_i32() >> rng.below(31);
    if (b == 0) b = 1;
    const int64_t want = ref_round_div(static_cast<I128>(a) * 65536, b);
    ASSERT_EQ((Fx::from_raw(a) / Fx::from_raw(b)).raw(), want) << a << " / " << b;
  }
  EXPECT_EQ(Fx(1) / Fx(0), Fx::max());
  EXPECT_EQ(Fx(-1) / Fx(0), Fx::min());
  EXPECT_EQ(Fx(0) / Fx(0), Fx::zero());
  EXPECT_EQ(Fx(7) / 2, 3.5_fx);
  EXPECT_EQ(Fx::from_raw(-3) / 2, Fx::from_raw(-2));  // -1.5 -> -2
}

TEST(FixedFx, SaturatesAtTheRangeEdgesIncludingIntMin) {
  const Fx lo = Fx::min();
  EXPECT_EQ(-lo, Fx::max());
  EXPECT_EQ(abs(lo), Fx::max());
  EXPECT_EQ(lo * Fx(-1), Fx::max());
  EXPECT_EQ(lo / Fx(-1), Fx::max());
  EXPECT_EQ(lo - Fx::epsilon(), lo);
  EXPECT_EQ(Fx::max() + Fx::epsilon(), Fx::max());
  EXPECT_EQ(lo * lo, Fx::max());
  EXPECT_EQ(lo * Fx::max(), Fx::min());
  EXPECT_EQ(Fx::max() * 3, Fx::max());
  EXPECT_EQ(lo + Fx::max(), Fx::from_raw(-1));
}

TEST(FixedFx, ComparesAndClamps) {
  EXPECT_LT(Fx(-1), Fx::zero());
  EXPECT_GT(Fx::epsilon(), Fx::zero());
  EXPECT_EQ(min(Fx(2), Fx(-3)), Fx(-3));
  EXPECT_EQ(max(Fx(2), Fx(-3)), Fx(2));
  EXPECT_EQ(clamp(Fx(5), Fx(-1), Fx(1)), Fx(1));
  EXPECT_EQ(clamp(Fx(-5), Fx(-1), Fx(1)), Fx(-1));
  EXPECT_EQ(clamp(0.5_fx, Fx(-1), Fx(1)), 0.5_fx);
  EXPECT_EQ(sign(Fx::min()), -1);
  EXPECT_EQ(sign(Fx::zero()), 0);
}

TEST(FixedFxWide, HoldsProductsExactlyAndNarrowsWithRounding) {
  const FxWide p = FxWide::product(Fx::epsilon(), Fx::epsilon());
  EXPECT_EQ(p.raw(), 1);  // 2^-32: lost by Fx, kept here
  EXPECT_EQ(p.to_fx(), Fx::zero());
  FxWide sum;
  for (int i = 0; i < 1 << 16; ++i) sum += p;  // 65536 * 2^-32 = 2^-16
  EXPECT_EQ(sum.to_fx(), Fx::epsilon());
  EXPECT_EQ(FxWide(Fx::min()).to_fx(), Fx::min());
  EXPECT_EQ(FxWide::product(Fx::min(), Fx::min()).to_fx(), Fx::max());
  EXPECT_EQ((FxWide(Fx(3)) * FxWide(Fx(-2))).to_fx(), Fx(-6));
  EXPECT_EQ(-FxWide::from_raw(INT64_MIN), FxWide::from_raw(INT64_MAX));
}

}  // namespace
}  // namespace rwd::fixed
