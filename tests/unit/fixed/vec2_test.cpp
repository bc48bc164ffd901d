// SPDX-License-Identifier: MIT
#include "rewind/fixed/vec2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "rewind/fixed/fx_literal.h"
#include "rewind/fixed/rot2.h"
#include "rewind/fixed/transform2.h"
#include "rewind/fixed/wide_int.h"
#include "splitmix.h"

namespace rwd::fixed {
namespace {

Vec2 v(int32_t x, int32_t y) {
  return {Fx(x), Fx(y)};
}
Vec2 raw_vec(SplitMix64& rng) {
  return {Fx::from_raw(rng.raw_i32() >> rng.below(31)),
          Fx::from_raw(rng.raw_i32() >> rng.below(31))};
}
long double value(Fx f) {
  return static_cast<long double>(f.raw()) / 65536.0L;
}

TEST(FixedVec2, AddsSubtractsScalesAndSaturates) {
  EXPECT_EQ(v(1, 2) + v(3, -4), v(4, -2));
  EXPECT_EQ(v(1, 2) - v(3, -4), v(-2, 6));
  EXPECT_EQ(-v(1, -2), v(-1, 2));
  EXPECT_EQ(v(3, -4) * 0.5_fx, Vec2(1.5_fx, Fx(-2)));
  EXPECT_EQ(Vec2(Fx::max(), Fx::min()) + v(1, -1), Vec2(Fx::max(), Fx::min()));
  EXPECT_EQ(perp(v(1, 0)), v(0, 1));
}

TEST(FixedVec2, DotAndCrossAreSummedExactlyThenRoundedOnce) {
  SplitMix64 rng{41};
  for (int i = 0; i < 100000; ++i) {
    const Vec2 a = raw_vec(rng);
    const Vec2 b = raw_vec(rng);
    const I128 d =
        static_cast<I128>(a.x.raw()) * b.x.raw() + static_cast<I128>(a.y.raw()) * b.y.raw();
    const I128 c =
        static_cast<I128>(a.x.raw()) * b.y.raw() - static_cast<I128>(a.y.raw()) * b.x.raw();
    ASSERT_EQ(dot(a, b).raw(), saturate_i32(shift_round(d, 16)));
    ASSERT_EQ(cross(a, b).raw(), saturate_i32(shift_round(c, 16)));
    ASSERT_EQ(dot_wide(a, b).raw(), saturate_i64(d));
    if (cross(a, b) != Fx::min() && cross(a, b) != Fx::max()) {
      ASSERT_EQ(cross(a, b), -cross(b, a));  // rounding is symmetric
    }
  }
  // Each product alone rounds to zero, their sum does not.
  const Vec2 tiny(Fx::from_raw(256), Fx::from_raw(256));
  EXPECT_EQ(dot(tiny, tiny).raw(), 2);
  EXPECT_EQ(length_squared_wide(Vec2(Fx::min(), Fx::min())).raw(), INT64_MAX);  // 2^63 saturates
}

TEST(FixedVec2, LengthIsTheRoundedExactRoot) {
  EXPECT_EQ(length(v(3, 4)), Fx(5));
  EXPECT_EQ(length(v(-300, 400)), Fx(500));
  EXPECT_EQ(length(Vec2::zero()), Fx::zero());
  EXPECT_EQ(length(Vec2(Fx::max(), Fx::max())), Fx::max());   // 46341 saturates
  EXPECT_EQ(length(Vec2(Fx::min(), Fx::zero())), Fx::max());  // 32768 saturates
  EXPECT_EQ(distance(Vec2(Fx::min(), Fx::zero()), Vec2(Fx(-32000), Fx::zero())), Fx(768));
  SplitMix64 rng{42};
  for (int i = 0; i < 100000; ++i) {
    const Vec2 a = raw_vec(rng);
    const long double truth =
        std::hypot(static_cast<long double>(a.x.raw()), static_cast<long double>(a.y.raw()));
    if (truth >= INT32_MAX) continue;
    ASSERT_LE(std::fabs(static_cast<long double>(length(a).raw()) - truth), 0.5L)
        << a.x.raw() << " " << a.y.raw();
  }
}

TEST(FixedVec2, NormalizedIsWithinOneUlpAndKeepsZero) {
  EXPECT_EQ(normalized(Vec2::zero()), Vec2::zero());
  EXPECT_EQ(normalized(v(0, -7)), v(0, -1));
  EXPECT_EQ(normalized(Vec2(Fx::min(), Fx::zero())), v(-1, 0));
  EXPECT_EQ(normalized(Vec2(Fx::epsilon(), Fx::zero())), v(1, 0));
  SplitMix64 rng{43};
  for (int i = 0; i < 100000; ++i) {
    const Vec2 a = raw_vec(rng);
    if (a == Vec2::zero()) continue;
    const Vec2 n = normalized(a);
    const long double len = std::hypot(value(a.x), value(a.y));
    ASSERT_LE(std::fabs(n.x.raw() - value(a.x) / len * 65536.0L), 1.0L);
    ASSERT_LE(std::fabs(n.y.raw() - value(a.y) / len * 65536.0L), 1.0L);
  }
}

TEST(FixedRot2, RotatesAndComposes) {
  const Rot2 quarter = Rot2::from_angle(Fx::half_pi());
  EXPECT_EQ(rotate(quarter, v(2, 0)), v(0, 2));
  EXPECT_EQ(inv_rotate(quarter, v(0, 2)), v(2, 0));
  EXPECT_EQ(rotate(Rot2::identity(), v(5, -6)), v(5, -6));
  const Rot2 half = mul(quarter, quarter);
  EXPECT_LE(std::abs(half.c.raw() + 65536), 1);
  EXPECT_LE(std::abs(half.s.raw()), 1);
  const Rot2 q = Rot2::from_angle(0.7_fx);
  EXPECT_LE(std::abs(q.angle().raw() - (0.7_fx).raw()), 1);
  EXPECT_LE(std::abs(length(Vec2(q.c, q.s)).raw() - 65536), 2);
  const Vec2 p(Fx(100), Fx(-37));
  const Vec2 back = inv_rotate(q, rotate(q, p));
  // c^2 + s^2 is 1 to within 2 ulps, so the round trip is off by at most
  // |p| * 2^-15 (in raw units, 2 per unit of |p| < 107) plus the roundings.
  EXPECT_LE(std::abs(back.x.raw() - p.x.raw()), 2 * 107 + 2);
  EXPECT_LE(std::abs(back.y.raw() - p.y.raw()), 2 * 107 + 2);
}

TEST(FixedRot2, FromAngleIsUnitWithinTwoUlps) {
  for (int32_t raw = -411775; raw <= 411775; raw += 37) {
    const Rot2 q = Rot2::from_angle(Fx::from_raw(raw));
    const I128 norm2 =
        static_cast<I128>(q.c.raw()) * q.c.raw() + static_cast<I128>(q.s.raw()) * q.s.raw();
    // |(c, s)| - 1 in ulps is about (norm2 - 2^32) / 2^17.
    const I128 off = norm2 - (I128{1} << 32);
    ASSERT_LE(off < 0 ? -off : off, I128{2} << 17) << raw;
  }
}

TEST(FixedTransform2, AppliesAndInverts) {
  const Transform2 t{v(10, -5), Rot2::from_angle(Fx::half_pi())};
  EXPECT_EQ(apply(t, v(1, 0)), v(10, -4));
  EXPECT_EQ(apply_inverse(t, v(10, -4)), v(1, 0));
  const Transform2 ti = inverse(t);
  EXPECT_EQ(apply(ti, apply(t, v(3, 7))), v(3, 7));
  const Transform2 both = mul(t, t);
  EXPECT_EQ(apply(both, v(1, 0)), apply(t, apply(t, v(1, 0))));
  EXPECT_EQ(apply(Transform2::identity(), v(4, 4)), v(4, 4));
}

}  // namespace
}  // namespace rwd::fixed
