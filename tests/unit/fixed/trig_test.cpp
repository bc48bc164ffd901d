// SPDX-License-Identifier: MIT
#include "rewind/fixed/trig.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "rewind/fixed/fx_literal.h"
#include "splitmix.h"

namespace rwd::fixed {
namespace {

long double value(Fx f) {
  return static_cast<long double>(f.raw()) / 65536.0L;
}
// The error of `got` against the true value, in ulps (2^-16).
long double ulps(Fx got, long double truth) {
  return std::fabs(static_cast<long double>(got.raw()) - truth * 65536.0L);
}

void expect_sin_cos_within_one_ulp(Fx angle) {
  const SinCos sc = sin_cos(angle);
  const long double a = value(angle);
  ASSERT_LE(ulps(sc.sin, std::sin(a)), 1.0L) << "sin raw angle " << angle.raw();
  ASSERT_LE(ulps(sc.cos, std::cos(a)), 1.0L) << "cos raw angle " << angle.raw();
}

TEST(FixedSinCos, WithinOneUlpOverTheFullCircle) {
  // Every 3rd raw angle over two full turns: about 275000 angles.
  for (int32_t raw = -2 * 411775; raw <= 2 * 411775; raw += 3) {
    expect_sin_cos_within_one_ulp(Fx::from_raw(raw));
  }
}

TEST(FixedSinCos, WithinOneUlpAcrossTheWholeRange) {
  expect_sin_cos_within_one_ulp(Fx::max());
  expect_sin_cos_within_one_ulp(Fx::min());
  SplitMix64 rng{31};
  for (int i = 0; i < 100000; ++i) expect_sin_cos_within_one_ulp(Fx::from_raw(rng.raw_i32()));
}

TEST(FixedSinCos, KnownAngles) {
  EXPECT_EQ(sin(Fx::zero()), Fx::zero());
  EXPECT_EQ(cos(Fx::zero()), Fx::one());
  EXPECT_EQ(sin(Fx::half_pi()), Fx::one());
  EXPECT_LE(std::abs(cos(Fx::pi()).raw() + 65536), 1);
  EXPECT_LE(std::abs(sin(Fx::ratio(1, 6) * Fx::pi()).raw() - 32768), 1);  // sin 30 deg
  // Odd and even symmetry hold exactly.
  for (int32_t raw = 1; raw < 411775; raw += 977) {
    EXPECT_EQ(sin(Fx::from_raw(-raw)), -sin(Fx::from_raw(raw)));
    EXPECT_EQ(cos(Fx::from_raw(-raw)), cos(Fx::from_raw(raw)));
  }
}

TEST(FixedAtan2, WithinOneUlpAndQuadrantCorrect) {
  SplitMix64 rng{32};
  for (int i = 0; i < 200000; ++i) {
    const Fx y = Fx::from_raw(rng.raw_i32() >> rng.below(31));
    const Fx x = Fx::from_raw(rng.raw_i32() >> rng.below(31));
    const Fx got = atan2(y, x);
    if (y.raw() == 0 && x.raw() == 0) continue;
    const long double truth = std::atan2(value(y), value(x));
    ASSERT_LE(ulps(got, truth), 1.0L) << y.raw() << ", " << x.raw();
    // Quadrant: the result lies in the half-planes of y and x (an angle
    // below half an ulp, e.g. atan2(2^-16, 2^14), rounds to zero).
    if (y.raw() > 0) {
      ASSERT_GE(got.raw(), 0);
    }
    if (y.raw() < 0) {
      ASSERT_LE(got.raw(), 0);
    }
    if (x.raw() > 0) {
      ASSERT_LE(abs(got), Fx::half_pi());
    }
    if (x.raw() < 0) {
      ASSERT_GE(abs(got), Fx::half_pi());
    }
  }
}

TEST(FixedAtan2, ExactOnTheAxesAndAtTheRangeEdge) {
  EXPECT_EQ(atan2(Fx::zero(), Fx::zero()), Fx::zero());
  EXPECT_EQ(atan2(Fx::zero(), Fx(5)), Fx::zero());
  EXPECT_EQ(atan2(Fx::zero(), Fx(-5)), Fx::pi());
  EXPECT_EQ(atan2(Fx(3), Fx::zero()), Fx::half_pi());
  EXPECT_EQ(atan2(Fx(-3), Fx::zero()), -Fx::half_pi());
  EXPECT_EQ(atan2(Fx::min(), Fx::min()).raw(), -154416);  // -3pi/4
  EXPECT_EQ(atan2(Fx::max(), Fx::max()).raw(), 51472);    // pi/4
  EXPECT_EQ(atan2(Fx::epsilon(), Fx::epsilon()).raw(), 51472);
  EXPECT_EQ(atan2(Fx::from_raw(-1), Fx::min()).raw(), -205887);
}

TEST(FixedNormalizeAngle, MapsIntoMinusPiToPi) {
  SplitMix64 rng{33};
  for (int i = 0; i < 100000; ++i) {
    const Fx a = Fx::from_raw(rng.raw_i32());
    const Fx n = normalize_angle(a);
    ASSERT_GE(n, -Fx::pi());
    ASSERT_LE(n, Fx::pi());
    // Same angle: n - a is a whole number of turns, to within 1 ulp.
    const long double turns =
        (value(a) - value(n)) / (2.0L * 3.14159265358979323846264338327950288L);
    ASSERT_LE(std::fabs(turns - std::round(turns)) * 2.0L * 3.14159265358979323846L * 65536.0L,
              1.0L)
        << a.raw();
  }
  EXPECT_EQ(normalize_angle(1.5_fx), 1.5_fx);
  EXPECT_EQ(normalize_angle(Fx::pi()), Fx::pi());
  EXPECT_EQ(normalize_angle(-Fx::pi()), -Fx::pi());
  EXPECT_EQ(normalize_angle(Fx::two_pi()), Fx::zero());
}

}  // namespace
}  // namespace rwd::fixed

namespace rwd::fixed {
namespace {

// vector_angle is atan2's CORDIC kept to 2^-30: rounded to an Fx it gives
// atan2's bits, and it resolves angles atan2 cannot (below 2^-16).
TEST(VectorAngle, AgreesWithAtan2AndKeepsItsPrecision) {
  for (int32_t y = -70000; y <= 70000; y += 7001) {
    for (int32_t x = -70000; x <= 70000; x += 6007) {
      const FxWide wide = vector_angle(y, x);
      EXPECT_EQ(wide.to_fx(), atan2(Fx::from_raw(y), Fx::from_raw(x))) << y << ", " << x;
    }
  }
  // pi / 4 in Q32.32 is 3373259426.3; within 2^-29 (8 units of 2^-32).
  EXPECT_NEAR(static_cast<double>(vector_angle(1, 1).raw()), 3373259426.3, 8.0);
  // An angle of 2^-20 rad, far below an Fx ulp: (2^52, 2^32) is 2^-20 to 1e-13.
  const int64_t one = int64_t{1} << 52;
  EXPECT_NEAR(static_cast<double>(vector_angle(one >> 20, one).raw()), 4096.0, 8.0);
  EXPECT_EQ(atan2(Fx::from_raw(1), Fx::from_raw(1 << 20)), Fx());
  // Axes exact, and the extreme inputs are taken.
  EXPECT_EQ(vector_angle(0, -5).raw(), 13493037705);  // pi, Q32.32
  EXPECT_EQ(vector_angle(7, 0).raw(), 6746518852);    // pi / 2
  EXPECT_EQ(vector_angle(INT64_MIN, INT64_MIN).to_fx(), atan2(-1_fx, -1_fx));
}

}  // namespace
}  // namespace rwd::fixed
