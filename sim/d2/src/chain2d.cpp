// SPDX-License-Identifier: MIT
// The chain segment factory and make_chain. Validation is exact, on raw
// Q16.16 values in int64, like the other shape factories.
#include "rewind/sim2d/chain2d.h"

#include <cstdint>
#include <string>
#include <utility>

namespace rwd::sim2d {

namespace {

Status invalid(std::string message) {
  return Status::Error(ErrorCode::kInvalidArgument, std::move(message));
}

bool fits_fx(int64_t raw) {
  return raw >= INT32_MIN && raw <= INT32_MAX;
}

// Whether b - a fits the Fx range on both axes (the manifold routines take
// that difference in Q16.16 before widening).
bool span_fits(Vec2 a, Vec2 b) {
  return fits_fx(int64_t{b.x.raw()} - a.x.raw()) && fits_fx(int64_t{b.y.raw()} - a.y.raw());
}

// The midpoint, rounded toward minus infinity, as the segment's centroid.
Vec2 midpoint(Vec2 a, Vec2 b) {
  return {Fx::from_raw(static_cast<int32_t>((int64_t{a.x.raw()} + b.x.raw()) >> 1)),
          Fx::from_raw(static_cast<int32_t>((int64_t{a.y.raw()} + b.y.raw()) >> 1))};
}

// The ghost of an open end: `end` moved by -n * |p2 - p1|, n the edge's
// right normal, so the missing neighbour is a wall at a right angle behind
// the end. In raw units -n * |d| is (-d.y, d.x) exactly; it is halved until
// the ghost fits the Fx range, which keeps its direction (up to the
// rounding of odd values) and so the square corner.
Result<Vec2> square_ghost(Vec2 p1, Vec2 p2, Vec2 end) {
  int64_t ox = -(int64_t{p2.y.raw()} - p1.y.raw());
  int64_t oy = int64_t{p2.x.raw()} - p1.x.raw();
  while (ox != 0 || oy != 0) {
    const int64_t gx = end.x.raw() + ox;
    const int64_t gy = end.y.raw() + oy;
    if (fits_fx(gx) && fits_fx(gy) && fits_fx(ox) && fits_fx(oy)) {
      return Vec2{Fx::from_raw(static_cast<int32_t>(gx)), Fx::from_raw(static_cast<int32_t>(gy))};
    }
    ox /= 2;
    oy /= 2;
  }
  return invalid("chain end ghost does not fit the coordinate range");
}

}  // namespace

Result<Shape2D> make_chain_segment(Vec2 ghost1, Vec2 p1, Vec2 p2, Vec2 ghost2) {
  if (p1 == p2) return invalid("chain segment points 0 and 1 are the same");
  if (ghost1 == p1) return invalid("chain segment ghost1 equals point 0");
  if (ghost2 == p2) return invalid("chain segment ghost2 equals point 1");
  if (!span_fits(p1, p2)) return invalid("chain segment spans more than the coordinate range");
  if (!span_fits(ghost1, p1)) {
    return invalid("chain segment ghost1 edge spans more than the coordinate range");
  }
  if (!span_fits(p2, ghost2)) {
    return invalid("chain segment ghost2 edge spans more than the coordinate range");
  }
  Shape2D s;
  s.type = ShapeType2D::kChainSegment;
  s.count = 2;
  s.vertices[0] = p1;
  s.vertices[1] = p2;
  s.vertices[2] = ghost1;
  s.vertices[3] = ghost2;
  s.centroid = midpoint(p1, p2);
  return s;
}

Result<std::vector<Shape2D>> make_chain(std::span<const Vec2> points, bool loop) {
  const int n = static_cast<int>(points.size());
  const int min_points = loop ? 3 : 2;
  if (n < min_points) {
    return invalid(std::string(loop ? "chain loop" : "chain") + " needs at least " +
                   std::to_string(min_points) + " points, got " + std::to_string(n));
  }
  const int edges = loop ? n : n - 1;
  for (int i = 0; i < edges; ++i) {
    const int j = (i + 1) % n;
    if (points[i] == points[j]) {
      return invalid("chain points " + std::to_string(i) + " and " + std::to_string(j) + " repeat");
    }
    if (!span_fits(points[i], points[j])) {
      return invalid("chain edge " + std::to_string(i) + " spans more than the coordinate range");
    }
  }
  std::vector<Shape2D> out;
  out.reserve(static_cast<size_t>(edges));
  for (int i = 0; i < edges; ++i) {
    const Vec2 p1 = points[i];
    const Vec2 p2 = points[(i + 1) % n];
    Vec2 ghost1;
    Vec2 ghost2;
    if (loop || i > 0) {
      ghost1 = points[(i + n - 1) % n];
    } else {
      const Result<Vec2> g = square_ghost(p1, p2, p1);
      if (!g.ok()) return g.status();
      ghost1 = *g;
    }
    if (loop || i + 2 < n) {
      ghost2 = points[(i + 2) % n];
    } else {
      const Result<Vec2> g = square_ghost(p1, p2, p2);
      if (!g.ok()) return g.status();
      ghost2 = *g;
    }
    Result<Shape2D> s = make_chain_segment(ghost1, p1, p2, ghost2);
    if (!s.ok()) {
      return invalid("chain edge " + std::to_string(i) + ": " + std::string(s.status().message()));
    }
    out.push_back(*s);
  }
  return out;
}

}  // namespace rwd::sim2d
