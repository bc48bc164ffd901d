// SPDX-License-Identifier: MIT
#pragma once
// Vector and quaternion value types for the 3D lane. Only + - * / and sqrt
// reach the hardware here; trigonometry lives in det_math.h. Every function
// is written out operation by operation so the compiler has no freedom to
// reassociate (and -ffp-contract=off forbids fusing).
#include <cmath>

#include "rewind/core/build_checks.h"

namespace rwd::sim {

/// A 3-vector in metres, metres per second or radians per second, by use.
struct Vec3 {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
};

inline Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator-(Vec3 a) {
  return {-a.x, -a.y, -a.z};
}
inline Vec3 operator*(Vec3 a, float s) {
  return {a.x * s, a.y * s, a.z * s};
}
inline Vec3 operator*(float s, Vec3 a) {
  return {a.x * s, a.y * s, a.z * s};
}
inline Vec3& operator+=(Vec3& a, Vec3 b) {
  return a = a + b;
}
inline Vec3& operator-=(Vec3& a, Vec3 b) {
  return a = a - b;
}
inline bool operator==(Vec3 a, Vec3 b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
inline float dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length_squared(Vec3 a) {
  return dot(a, a);
}
inline float length(Vec3 a) {
  return std::sqrt(dot(a, a));
}
/// Unit vector along a, or zero when a is (nearly) zero.
inline Vec3 normalize_or_zero(Vec3 a) {
  float len = length(a);
  return len > 1e-12f ? a * (1.0f / len) : Vec3{};
}

/// A rotation as a unit quaternion (x, y, z vector part; w scalar part).
struct Quat {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
  float w = 1.0f;
};

inline bool operator==(Quat a, Quat b) {
  return a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w;
}
inline Quat operator*(Quat a, Quat b) {
  return {
      a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
      a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}
inline Quat conjugate(Quat q) {
  return {-q.x, -q.y, -q.z, q.w};
}
inline Quat normalize(Quat q) {
  float len = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (len < 1e-12f) return Quat{};
  float inv = 1.0f / len;
  return {q.x * inv, q.y * inv, q.z * inv, q.w * inv};
}
/// Rotates v by the unit quaternion q.
inline Vec3 rotate(Quat q, Vec3 v) {
  Vec3 u{q.x, q.y, q.z};
  Vec3 t = 2.0f * cross(u, v);
  return v + q.w * t + cross(u, t);
}
/// Rotates v by the inverse of the unit quaternion q.
inline Vec3 inv_rotate(Quat q, Vec3 v) {
  return rotate(conjugate(q), v);
}

/// Component-wise product.
inline Vec3 mul_elements(Vec3 a, Vec3 b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
inline Vec3 abs(Vec3 a) {
  return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)};
}
inline Vec3 min(Vec3 a, Vec3 b) {
  return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
inline Vec3 max(Vec3 a, Vec3 b) {
  return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}
/// Component i (0 = x, 1 = y, 2 = z) of v.
inline float component(Vec3 v, int i) {
  return i == 0 ? v.x : (i == 1 ? v.y : v.z);
}
inline bool is_finite(float v) {
  return std::isfinite(v);
}
inline bool is_finite(Vec3 v) {
  return is_finite(v.x) && is_finite(v.y) && is_finite(v.z);
}
inline bool is_finite(Quat q) {
  return is_finite(q.x) && is_finite(q.y) && is_finite(q.z) && is_finite(q.w);
}
inline float length_squared(Quat q) {
  return q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
}

/// Two unit vectors that complete the unit vector n to a right-handed
/// orthonormal basis (n, t1, t2). Branch on the larger component so the
/// basis is well conditioned; the result is a pure function of n's bits.
inline void tangent_basis(Vec3 n, Vec3& t1, Vec3& t2) {
  if (std::fabs(n.x) >= 0.57735f) {
    t1 = normalize_or_zero(Vec3{n.y, -n.x, 0.0f});
  } else {
    t1 = normalize_or_zero(Vec3{0.0f, n.z, -n.y});
  }
  t2 = cross(n, t1);
}

/// Integrates a unit quaternion by angular velocity w (rad/s, world frame)
/// over h seconds: q += h/2 * (w, 0) * q, then renormalizes. First order,
/// like every real-time engine; substeps keep the error small.
inline Quat integrate_rotation(Quat q, Vec3 w, float h) {
  float hh = 0.5f * h;
  Quat dq{w.x * hh, w.y * hh, w.z * hh, 0.0f};
  Quat r = dq * q;
  return normalize(Quat{q.x + r.x, q.y + r.y, q.z + r.z, q.w + r.w});
}

/// A 3x3 matrix stored as three columns.
struct Mat3 {
  Vec3 c0{1.0f, 0.0f, 0.0f};
  Vec3 c1{0.0f, 1.0f, 0.0f};
  Vec3 c2{0.0f, 0.0f, 1.0f};
};

inline Mat3 mat3_zero() {
  return {Vec3{}, Vec3{}, Vec3{}};
}
inline Vec3 operator*(const Mat3& m, Vec3 v) {
  return m.c0 * v.x + m.c1 * v.y + m.c2 * v.z;
}
/// Rotation matrix of the unit quaternion q (columns are the rotated axes).
inline Mat3 mat3_from_quat(Quat q) {
  return {rotate(q, Vec3{1.0f, 0.0f, 0.0f}), rotate(q, Vec3{0.0f, 1.0f, 0.0f}),
          rotate(q, Vec3{0.0f, 0.0f, 1.0f})};
}
/// R * diag(d) * R^T: a body-frame diagonal tensor (e.g. inverse inertia)
/// expressed in the world frame.
inline Mat3 rotate_diagonal(const Mat3& r, Vec3 d) {
  Vec3 a = r.c0 * d.x;
  Vec3 b = r.c1 * d.y;
  Vec3 c = r.c2 * d.z;
  // column j of R D R^T = sum_k (R col k * d_k) * R[j][k]
  auto col = [&](float r0, float r1, float r2) { return a * r0 + b * r1 + c * r2; };
  return {col(r.c0.x, r.c1.x, r.c2.x), col(r.c0.y, r.c1.y, r.c2.y), col(r.c0.z, r.c1.z, r.c2.z)};
}

}  // namespace rwd::sim
