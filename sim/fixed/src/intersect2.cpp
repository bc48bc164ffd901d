// SPDX-License-Identifier: MIT
#include "rewind/fixed/intersect2.h"

#include <string>

#include "exact2.h"

namespace rwd::fixed {

using detail::W2;

namespace {

// |d|^2 <= r^2 with d < 2^33 per axis and r < 2^32: both sides below 2^67.
bool within(W2 d, I128 radius) {
  return detail::dot(d, d) <= radius * radius;
}

int64_t clamp64(int64_t v, int64_t lo, int64_t hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// p on the closed segment [a, b], given that a, b, p are collinear.
bool on_collinear_segment(Vec2 a, Vec2 b, Vec2 p) {
  return min(a.x, b.x) <= p.x && p.x <= max(a.x, b.x) && min(a.y, b.y) <= p.y &&
         p.y <= max(a.y, b.y);
}

// The sign of the turn a -> b -> c: +1 counter-clockwise, -1 clockwise, 0
// collinear. Exact.
int orientation(Vec2 a, Vec2 b, Vec2 c) {
  return detail::sign(detail::cross(detail::diff(b, a), detail::diff(c, a)));
}

bool on_segment(Vec2 a, Vec2 b, Vec2 p) {
  return orientation(a, b, p) == 0 && on_collinear_segment(a, b, p);
}

}  // namespace

bool overlaps(Circle a, Circle b) {
  const I128 reach = static_cast<I128>(a.radius.raw()) + b.radius.raw();
  return within(detail::diff(a.center, b.center), reach);
}

bool overlaps(Circle c, Aabb2 box) {
  // The box point closest to the center, then the disc test against it.
  const int64_t qx = clamp64(c.center.x.raw(), box.lower.x.raw(), box.upper.x.raw());
  const int64_t qy = clamp64(c.center.y.raw(), box.lower.y.raw(), box.upper.y.raw());
  return within({c.center.x.raw() - qx, c.center.y.raw() - qy}, c.radius.raw());
}

bool contains(Circle c, Vec2 p) {
  return within(detail::diff(p, c.center), c.radius.raw());
}

bool intersects(Segment2 s, Segment2 t) {
  const int o1 = orientation(s.a, s.b, t.a);
  const int o2 = orientation(s.a, s.b, t.b);
  const int o3 = orientation(t.a, t.b, s.a);
  const int o4 = orientation(t.a, t.b, s.b);
  // A proper crossing: each segment's ends lie strictly on both sides of
  // the other's line. Otherwise they meet only where an end lies on the
  // other segment.
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  if (o1 == 0 && on_collinear_segment(s.a, s.b, t.a)) return true;
  if (o2 == 0 && on_collinear_segment(s.a, s.b, t.b)) return true;
  if (o3 == 0 && on_collinear_segment(t.a, t.b, s.a)) return true;
  if (o4 == 0 && on_collinear_segment(t.a, t.b, s.b)) return true;
  return false;
}

Result<bool> polygon_contains(std::span<const Vec2> vertices, Vec2 p) {
  if (vertices.size() < 3) {
    return Status::Error(ErrorCode::kInvalidArgument, "a polygon needs at least 3 vertices, got " +
                                                          std::to_string(vertices.size()));
  }
  bool inside = false;
  for (size_t i = 0, j = vertices.size() - 1; i < vertices.size(); j = i++) {
    const Vec2 a = vertices[j];
    const Vec2 b = vertices[i];
    if (on_segment(a, b, p)) return true;
    // Half-open rule on y so a vertex on the horizontal through p is
    // counted once. For an upward edge the crossing lies to the right of p
    // when p is left of a -> b, i.e. the turn a -> b -> p is positive.
    if ((a.y > p.y) != (b.y > p.y)) {
      const int turn = orientation(a, b, p);
      if (b.y > a.y ? turn > 0 : turn < 0) inside = !inside;
    }
  }
  return inside;
}

}  // namespace rwd::fixed
