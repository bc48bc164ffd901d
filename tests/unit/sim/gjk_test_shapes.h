// SPDX-License-Identifier: MIT
#pragma once
// Helpers shared by the test_gjk* tests.
#include <gtest/gtest.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>
#include "d3/gjk.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3::gjk_test {

constexpr float kTol = 1e-5f;

struct BoxCorners {
  Vec3 p[8];
};

inline BoxCorners corners(Vec3 h) {
  BoxCorners c;
  for (int i = 0; i < 8; ++i) {
    c.p[i] = {(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z};
  }
  return c;
}

inline ConvexProxy proxy(const Vec3* points, uint32_t count, Vec3 position, Quat rotation = {},
                         float radius = 0.0f) {
  ConvexProxy p;
  p.points = points;
  p.count = count;
  p.radius = radius;
  p.position = position;
  p.axes = mat3_from_quat(rotation);
  return p;
}

inline Quat about_z(float cos_half, float sin_half) {
  return Quat{0.0f, 0.0f, sin_half, cos_half};
}
// 45 degrees about z: cos 22.5, sin 22.5.
const Quat kZ45 = about_z(0.92387953f, 0.38268343f);

inline void expect_vec(Vec3 a, Vec3 b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

}  // namespace rwd::sim::d3::gjk_test
