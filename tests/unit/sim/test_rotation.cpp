// SPDX-License-Identifier: MIT
#include "rewind/sim/rotation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rewind/core/det_math.h"

namespace rwd::sim {
namespace {

constexpr float kTol = 2e-6f;

void expect_near(Vec3 a, Vec3 b, float tol = kTol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Rotation, AxisAngleTurnsCounterClockwiseAboutTheAxis) {
  // A quarter turn about +Y takes +X to -Z (right-handed).
  expect_near(rotate(axis_angle({0, 1, 0}, 0.5f * kPi), {1, 0, 0}), {0, 0, -1});
  // The axis need not be unit length.
  expect_near(rotate(axis_angle({0, 0, 5}, 0.5f * kPi), {1, 0, 0}), {0, 1, 0});
  // A half turn about +X flips Y and Z.
  expect_near(rotate(axis_angle({1, 0, 0}, kPi), {0, 1, 2}), {0, -1, -2});
  const Quat q = axis_angle({0.3f, -1.0f, 0.2f}, 2.2f);
  EXPECT_NEAR(length_squared(q), 1.0f, 1e-6f);
}

TEST(Rotation, AxisAngleOfNothingIsTheIdentity) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(axis_angle({0, 0, 0}, 1.0f), Quat{});
  EXPECT_EQ(axis_angle({nan, 0, 0}, 1.0f), Quat{});
  EXPECT_EQ(axis_angle({0, 1, 0}, nan), Quat{});
}

TEST(Rotation, LookAtTurnsPlusZOntoForwardWithUpKeptUp) {
  const Vec3 forwards[] = {{1, 0, 0}, {0, 0, -1}, {1, 2, 3}, {-0.2f, -0.1f, 0.9f}, {0, 0, 1}};
  for (const Vec3 f : forwards) {
    const Quat q = look_at(f, {0, 1, 0});
    expect_near(rotate(q, {0, 0, 1}), normalize_or_zero(f), 4e-6f);
    const Vec3 up = rotate(q, {0, 1, 0});
    EXPECT_GT(up.y, 0.0f) << "the body's up stays on the side of +Y";
    EXPECT_NEAR(dot(up, rotate(q, {0, 0, 1})), 0.0f, 4e-6f);
    EXPECT_NEAR(length_squared(q), 1.0f, 1e-6f);
  }
}

TEST(Rotation, LookAtIsDefinedWhenUpIsAlongForwardOrForwardIsZero) {
  // Straight up with +Y as up: another perpendicular is picked.
  const Quat up = look_at({0, 3, 0});
  expect_near(rotate(up, {0, 0, 1}), {0, 1, 0});
  EXPECT_TRUE(is_finite(up));
  EXPECT_EQ(look_at({0, 0, 0}), Quat{});
  // A zero up behaves like +Y.
  expect_near(rotate(look_at({1, 0, 0}, {0, 0, 0}), {0, 1, 0}), {0, 1, 0});
}

TEST(Rotation, SameBitsFromTheSameArguments) {
  // Built from det_sin/det_cos: no dependence on the C library.
  const Quat a = axis_angle({0.1f, 0.7f, -0.3f}, 1.234f);
  const Quat b = axis_angle({0.1f, 0.7f, -0.3f}, 1.234f);
  EXPECT_EQ(a, b);
  EXPECT_FLOAT_EQ(a.w, det_cos(0.617f));
}

}  // namespace
}  // namespace rwd::sim
