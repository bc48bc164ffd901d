// SPDX-License-Identifier: MIT
#pragma once
// Small linear algebra the joint rows share: soft constraint coefficients,
// symmetric 3x3 and 2x2 solves, cross-product matrices and rotation
// vectors. Written operation by operation like math.h, so every build
// rounds alike.
#include "rewind/core/det_math.h"
#include "rewind/sim/math.h"

namespace rwd::sim::d3 {

/// A soft constraint's coefficients for one substep h (Erin Catto's soft
/// step): the velocity bias per metre (or radian) of error, the share of
/// the rigid impulse applied, and the share of the accumulated impulse
/// taken back (what makes it a spring rather than a stiff rod).
struct JointSoftness {
  float bias_rate = 0.0f;      ///< 1/s
  float mass_scale = 1.0f;     ///< (0, 1]
  float impulse_scale = 0.0f;  ///< [0, 1)
};

/// The coefficients of a spring-damper of `hertz` and damping ratio
/// `zeta`; hertz 0 is rigid (no bias, full mass, nothing taken back).
inline JointSoftness joint_softness(float hertz, float zeta, float h) {
  if (hertz == 0.0f) return {0.0f, 1.0f, 0.0f};
  const float omega = 2.0f * kPi * hertz;
  const float a1 = 2.0f * zeta + h * omega;
  const float a2 = h * omega * a1;
  const float a3 = 1.0f / (1.0f + a2);
  return {omega / a1, a2 * a3, a3};
}

inline Mat3 operator+(const Mat3& a, const Mat3& b) {
  return {a.c0 + b.c0, a.c1 + b.c1, a.c2 + b.c2};
}
inline Mat3 operator*(const Mat3& a, const Mat3& b) {
  return {a * b.c0, a * b.c1, a * b.c2};
}
inline Mat3 transpose(const Mat3& m) {
  return {{m.c0.x, m.c1.x, m.c2.x}, {m.c0.y, m.c1.y, m.c2.y}, {m.c0.z, m.c1.z, m.c2.z}};
}
/// The matrix of v x (.): skew(v) * u = cross(v, u).
inline Mat3 skew(Vec3 v) {
  return {{0.0f, v.z, -v.y}, {-v.z, 0.0f, v.x}, {v.y, -v.x, 0.0f}};
}
inline Mat3 diagonal(float d) {
  return {{d, 0.0f, 0.0f}, {0.0f, d, 0.0f}, {0.0f, 0.0f, d}};
}

/// The solution x of K x = b for a symmetric positive semi-definite K;
/// zero when K is singular (both bodies immovable along the rows).
inline Vec3 solve_symmetric(const Mat3& k, Vec3 b) {
  const Vec3 r0 = cross(k.c1, k.c2);
  const float det = dot(k.c0, r0);
  if (!(det > 1e-30f) && !(det < -1e-30f)) return {};
  const float inv = 1.0f / det;
  const Vec3 r1 = cross(k.c2, k.c0);
  const Vec3 r2 = cross(k.c0, k.c1);
  // Rows of the inverse are r0, r1, r2 over det (K symmetric).
  return {dot(r0, b) * inv, dot(r1, b) * inv, dot(r2, b) * inv};
}

/// The inverse of a symmetric positive semi-definite K. Rows and columns
/// that are exactly zero (a world axis both bodies are locked about) stay
/// zero and do not make the rest singular; a singular remainder gives zero.
inline Mat3 inverse_symmetric(const Mat3& k_in) {
  Mat3 k = k_in;
  const bool zx = k.c0.x == 0.0f;
  const bool zy = k.c1.y == 0.0f;
  const bool zz = k.c2.z == 0.0f;
  if (zx) k.c0 = {1.0f, 0.0f, 0.0f};
  if (zy) k.c1 = {0.0f, 1.0f, 0.0f};
  if (zz) k.c2 = {0.0f, 0.0f, 1.0f};
  if (zx) k.c1.x = k.c2.x = 0.0f;
  if (zy) k.c0.y = k.c2.y = 0.0f;
  if (zz) k.c0.z = k.c1.z = 0.0f;
  const Vec3 r0 = cross(k.c1, k.c2);
  const float det = dot(k.c0, r0);
  if (!(det > 1e-30f) && !(det < -1e-30f)) return mat3_zero();
  const float inv = 1.0f / det;
  // The inverse's rows are r0, r1, r2 over det; K is symmetric, so its
  // columns are the same.
  Mat3 m{r0 * inv, cross(k.c2, k.c0) * inv, cross(k.c0, k.c1) * inv};
  if (zx) {
    m.c0 = {};
    m.c1.x = m.c2.x = 0.0f;
  }
  if (zy) {
    m.c1 = {};
    m.c0.y = m.c2.y = 0.0f;
  }
  if (zz) {
    m.c2 = {};
    m.c0.z = m.c1.z = 0.0f;
  }
  return m;
}

/// The same for a 2x2 symmetric system [[a, b], [b, d]] x = (u, v).
inline void solve_symmetric2(float a, float b, float d, float u, float v, float& x, float& y) {
  const float det = a * d - b * b;
  if (!(det > 1e-30f) && !(det < -1e-30f)) {
    x = 0.0f;
    y = 0.0f;
    return;
  }
  const float inv = 1.0f / det;
  x = (d * u - b * v) * inv;
  y = (a * v - b * u) * inv;
}

/// The effective mass matrix of a point constraint: the velocity change
/// of the anchors apart per unit impulse between them.
inline Mat3 point_mass_matrix(float inv_mass_a, const Mat3& inv_inertia_a, Vec3 ra,
                              float inv_mass_b, const Mat3& inv_inertia_b, Vec3 rb) {
  const Mat3 sa = skew(ra);
  const Mat3 sb = skew(rb);
  // m I - [r] I^-1 [r]  (as [r]^T = -[r])
  Mat3 k = diagonal(inv_mass_a + inv_mass_b);
  const Mat3 ta = sa * inv_inertia_a * sa;
  const Mat3 tb = sb * inv_inertia_b * sb;
  k.c0 = k.c0 - ta.c0 - tb.c0;
  k.c1 = k.c1 - ta.c1 - tb.c1;
  k.c2 = k.c2 - ta.c2 - tb.c2;
  return k;
}

/// The rotation vector (axis times angle, rad) of a unit quaternion, the
/// short way round (angle in [0, pi]).
inline Vec3 rotation_vector(Quat q) {
  Vec3 v{q.x, q.y, q.z};
  float w = q.w;
  if (w < 0.0f) {
    v = -v;
    w = -w;
  }
  const float s = length(v);
  if (s < 1e-9f) return v * 2.0f;  // small angle: 2 sin(a/2) ~ a
  const float angle = 2.0f * det_atan2(s, w);
  return v * (angle / s);
}

/// The angle (rad, in [-pi, pi]) of the twist of q about its frame's x
/// axis, after the swing that takes x to where q takes it.
inline float twist_angle(Quat q) {
  if (q.x == 0.0f && q.w == 0.0f) return 0.0f;
  float angle = 2.0f * det_atan2(q.x, q.w);
  if (angle > kPi) angle -= 2.0f * kPi;
  if (angle < -kPi) angle += 2.0f * kPi;
  return angle;
}

/// The joint frame's axes (a hinge turns about x; a cone opens about x).
inline constexpr Vec3 kAxisX{1.0f, 0.0f, 0.0f};
inline constexpr Vec3 kAxisY{0.0f, 1.0f, 0.0f};
inline constexpr Vec3 kAxisZ{0.0f, 0.0f, 1.0f};

/// An angle difference in [-2 pi, 2 pi] brought into [-pi, pi].
inline float wrap_angle(float angle) {
  if (angle > kPi) return angle - 2.0f * kPi;
  if (angle < -kPi) return angle + 2.0f * kPi;
  return angle;
}

/// The shortest-arc rotation taking unit vector `from` onto unit `to`.
inline Quat arc_between(Vec3 from, Vec3 to) {
  const float c = dot(from, to);
  if (c < -0.999999f) {
    // Half a turn about any axis perpendicular to `from`.
    Vec3 t1;
    Vec3 t2;
    tangent_basis(from, t1, t2);
    return {t1.x, t1.y, t1.z, 0.0f};
  }
  const Vec3 axis = cross(from, to);
  return normalize(Quat{axis.x, axis.y, axis.z, 1.0f + c});
}

}  // namespace rwd::sim::d3
