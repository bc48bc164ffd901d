// SPDX-License-Identifier: MIT
#pragma once
// Small builders shared by the 2D lane's shape and manifold tests.
#include <gtest/gtest.h>

#include "manifold2.h"
#include "rewind/fixed/fx_literal.h"
#include "rewind/fixed/trig.h"
#include "rewind/sim2d/shape2d.h"
#include "wmath.h"

namespace rwd::sim2d::test {

using namespace rwd::fixed::literals;  // NOLINT: test brevity
using detail::Manifold2;
using detail::Rot;
using detail::V2;
using detail::W;
using detail::Xf;

/// One Fx ulp (2^-16 m) in W units.
inline constexpr W kFxUlp = W{1} << 16;
/// The speculative distance the tests use: 0.02 m.
inline constexpr W kSpeculative = detail::w_ratio(2, 100);

inline V2 wv(Fx x, Fx y) {
  return {detail::w_from(x), detail::w_from(y)};
}

/// A body transform at (x, y) turned by `angle` radians.
inline Xf body(Fx x, Fx y, Fx angle = Fx()) {
  Rot q;
  if (angle != Fx()) {
    const fixed::SinCos sc = fixed::sin_cos(angle);
    q = detail::renormalize({detail::w_from(sc.cos), detail::w_from(sc.sin)});
  }
  return {wv(x, y), q};
}

inline Shape2D ok(Result<Shape2D> r) {
  EXPECT_TRUE(r.ok()) << r.status().message();
  return r.ok() ? *r : Shape2D{};
}

inline Manifold2 collide(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                         W speculative = kSpeculative) {
  Manifold2 m;
  detail::collide(a, xa, b, xb, speculative, m);
  return m;
}

/// |a - b| <= tol for each component.
inline ::testing::AssertionResult near_v(V2 a, V2 b, W tol) {
  if (detail::wabs(a.x - b.x) <= tol && detail::wabs(a.y - b.y) <= tol) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ") vs (" << b.x << ", "
                                       << b.y << "), tolerance " << tol << " raw";
}

inline ::testing::AssertionResult near_w(W a, W b, W tol) {
  if (detail::wabs(a - b) <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << ", tolerance " << tol << " raw";
}

/// collide(b, a) must be collide(a, b) with the normal flipped and the
/// anchors swapped, point for point.
inline void expect_reversed(const Manifold2& ab, const Manifold2& ba) {
  ASSERT_EQ(ab.count, ba.count);
  EXPECT_EQ(ab.normal, -ba.normal);
  for (int i = 0; i < ab.count; ++i) {
    EXPECT_EQ(ab.points[i].anchor_a, ba.points[i].anchor_b);
    EXPECT_EQ(ab.points[i].anchor_b, ba.points[i].anchor_a);
    EXPECT_EQ(ab.points[i].separation, ba.points[i].separation);
    EXPECT_EQ(ab.points[i].id, ba.points[i].id);
  }
}

}  // namespace rwd::sim2d::test
