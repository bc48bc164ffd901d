// SPDX-License-Identifier: MIT
#include "d3/manifold_reuse.h"

namespace rwd::sim::d3 {
namespace {

// v in A's frame: A's matrix transposed times v.
Vec3 to_frame(const Mat3& axes, Vec3 v) {
  return {dot(axes.c0, v), dot(axes.c1, v), dot(axes.c2, v)};
}

}  // namespace

RelativePose relative_pose(const BodySim& a, const Mat3& axes_a, const BodySim& b) {
  return {to_frame(axes_a, b.position - a.position), conjugate(a.rotation) * b.rotation};
}

// A turn by angle t moves a point at distance e from B's centre by at most
// t * e, and |turn's vector part| = sin(t / 2) <= t / 2, so 4 |v|^2 e^2 <=
// d^2 bounds it (no square root, no angle).
bool within_reuse(const ContactRecord& rec, const RelativePose& now, Quat turn, float extent_b) {
  const float d_sq = kReuseDistance * kReuseDistance;
  if (length_squared(now.position - rec.frame_position) > d_sq) return false;
  const float v_sq = turn.x * turn.x + turn.y * turn.y + turn.z * turn.z;
  return 4.0f * v_sq * extent_b * extent_b <= d_sq;
}

void carry_manifold(const BodySim& sa, const Mat3& axes_a, const BodySim& sb,
                    const ContactRecord& old, const RelativePose& now, Quat turn, Manifold& m) {
  const Vec3 n = old.frame_normal;
  m.normal = axes_a * n;
  m.point_count = old.point_count;
  for (uint32_t p = 0; p < old.point_count; ++p) {
    const CachedContactPoint& c = old.points[p];
    // B's surface point then, in A's frame, and where B's motion took it.
    const Vec3 b_then = c.local_a + n * c.separation;
    const Vec3 b_now = now.position + rotate(turn, b_then - old.frame_position);
    const float separation = dot(b_now - c.local_a, n);
    ManifoldPoint& mp = m.points[p];
    mp.anchor_a = axes_a * (c.local_a + n * (0.5f * separation));
    mp.point = sa.position + mp.anchor_a;
    mp.anchor_b = mp.point - sb.position;
    mp.separation = separation;
    mp.feature_id = c.feature_id;
  }
}

void record_frame(const Mat3& axes_a, const RelativePose& now, const Manifold& m,
                  ContactRecord& rec) {
  rec.frame_position = now.position;
  rec.frame_rotation = now.rotation;
  rec.frame_normal = to_frame(axes_a, m.normal);
  for (uint32_t p = 0; p < rec.point_count; ++p) {
    const ManifoldPoint& mp = m.points[p];
    // The midpoint less half the separation along the normal: A's surface.
    rec.points[p].local_a = to_frame(axes_a, mp.anchor_a - m.normal * (0.5f * mp.separation));
    rec.points[p].separation = mp.separation;
  }
}

}  // namespace rwd::sim::d3
