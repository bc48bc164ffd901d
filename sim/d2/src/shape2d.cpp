// SPDX-License-Identifier: MIT
// The shape factories. Validation is exact: every predicate (equal points,
// turn direction, side of an edge, area) is an integer cross product of raw
// Q16.16 values summed in 128 bits, so a shape is accepted or refused the
// same way on every machine and no rounding can make a bad outline pass.
#include <cstdint>
#include <string>

#include "rewind/fixed/rot2.h"
#include "rewind/fixed/wide_int.h"
#include "rewind/sim2d/shape2d.h"

namespace rwd::sim2d {

namespace {

using fixed::I128;

// Twice the smallest polygon area accepted, in raw Q32.32 units (products of
// two raw Q16.16 values): area >= 2^-16 m^2, about a 4 mm square. Below it
// the mass and rotational inertia lose most of their bits.
constexpr I128 kMinTwiceAreaRaw = I128{1} << 17;

Status invalid(std::string message) {
  return Status::Error(ErrorCode::kInvalidArgument, std::move(message));
}

// Exact raw differences and cross products (no saturation: raw values are
// int32, so a difference fits int64 and a product of differences I128).
struct RawVec {
  int64_t x = 0;
  int64_t y = 0;
};

RawVec raw_sub(Vec2 a, Vec2 b) {
  return {int64_t{a.x.raw()} - b.x.raw(), int64_t{a.y.raw()} - b.y.raw()};
}

I128 raw_cross(RawVec a, RawVec b) {
  return static_cast<I128>(a.x) * b.y - static_cast<I128>(a.y) * b.x;
}

int sign(I128 v) {
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

std::string idx(int i) {
  return std::to_string(i);
}

bool fits_fx(int64_t raw) {
  return raw >= INT32_MIN && raw <= INT32_MAX;
}

// Midpoint, rounded toward minus infinity (the arithmetic shift), exact in
// int64 so it cannot saturate.
Vec2 midpoint(Vec2 a, Vec2 b) {
  return {Fx::from_raw(static_cast<int32_t>((int64_t{a.x.raw()} + b.x.raw()) >> 1)),
          Fx::from_raw(static_cast<int32_t>((int64_t{a.y.raw()} + b.y.raw()) >> 1))};
}

// Checks the outline in the caller's order (so messages name the caller's
// indices) and returns the orientation: +1 counter-clockwise, -1 clockwise.
Result<int> check_outline(std::span<const Vec2> p) {
  const int n = static_cast<int>(p.size());
  if (n < 3) return invalid("polygon needs at least 3 points, got " + idx(n));
  if (n > kMaxPolygonVertices) {
    return invalid("polygon takes at most " + idx(kMaxPolygonVertices) + " points, got " + idx(n));
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (p[i] == p[j]) return invalid("polygon points " + idx(i) + " and " + idx(j) + " repeat");
    }
  }
  for (int i = 0; i < n; ++i) {
    const RawVec e = raw_sub(p[(i + 1) % n], p[i]);
    if (!fits_fx(e.x) || !fits_fx(e.y)) {
      return invalid("polygon edge " + idx(i) + " spans more than the coordinate range");
    }
  }
  // Twice the signed area, about point 0 (exact).
  I128 twice_area = 0;
  for (int i = 1; i + 1 < n; ++i)
    twice_area += raw_cross(raw_sub(p[i], p[0]), raw_sub(p[i + 1], p[0]));
  for (int i = 0; i < n; ++i) {
    const RawVec in = raw_sub(p[i], p[(i + n - 1) % n]);
    const RawVec out = raw_sub(p[(i + 1) % n], p[i]);
    if (raw_cross(in, out) == 0) {
      return invalid("polygon point " + idx(i) + " is collinear with its neighbours");
    }
  }
  const int orientation = sign(twice_area);
  if (orientation == 0) return invalid("polygon outline crosses itself (zero signed area)");
  for (int i = 0; i < n; ++i) {
    const RawVec in = raw_sub(p[i], p[(i + n - 1) % n]);
    const RawVec out = raw_sub(p[(i + 1) % n], p[i]);
    if (sign(raw_cross(in, out)) != orientation) {
      return invalid("polygon is not convex: reflex corner at point " + idx(i));
    }
  }
  // All turns agree, yet an outline may still wind more than once (a
  // pentagram). A convex simple outline has every other point strictly on
  // the inner side of every edge; a multiply wound one does not.
  for (int i = 0; i < n; ++i) {
    const int next = (i + 1) % n;
    const RawVec e = raw_sub(p[next], p[i]);
    for (int j = 0; j < n; ++j) {
      if (j == i || j == next) continue;
      if (sign(raw_cross(e, raw_sub(p[j], p[i]))) != orientation) {
        return invalid("polygon outline crosses itself: point " + idx(j) + " lies outside edge " +
                       idx(i));
      }
    }
  }
  const I128 magnitude = twice_area < 0 ? -twice_area : twice_area;
  if (magnitude < kMinTwiceAreaRaw) return invalid("polygon area is below 2^-16 m^2");
  return orientation;
}

// The area centroid of a counter-clockwise outline, relative to point 0 for
// precision, rounded once from the exact 128-bit sums.
Vec2 area_centroid(const Shape2D& s) {
  const int n = s.count;
  const Vec2 o = s.vertices[0];
  I128 twice_area = 0;
  I128 sx = 0;
  I128 sy = 0;
  for (int i = 1; i + 1 < n; ++i) {
    const RawVec e1 = raw_sub(s.vertices[i], o);
    const RawVec e2 = raw_sub(s.vertices[i + 1], o);
    const I128 c = raw_cross(e1, e2);
    twice_area += c;
    sx += c * (e1.x + e2.x);
    sy += c * (e1.y + e2.y);
  }
  // centroid = o + sum / (3 * twice_area); the raw units cancel to Q16.16.
  const I128 den = 3 * twice_area;
  return {Fx::from_raw(fixed::saturate_i32(o.x.raw() + fixed::div_round(sx, den))),
          Fx::from_raw(fixed::saturate_i32(o.y.raw() + fixed::div_round(sy, den)))};
}

Result<Shape2D> two_point_shape(ShapeType2D type, Vec2 p1, Vec2 p2, Fx radius, const char* what) {
  if (p1 == p2) return invalid(std::string(what) + " points 0 and 1 are the same");
  const RawVec e = raw_sub(p2, p1);
  if (!fits_fx(e.x) || !fits_fx(e.y)) {
    return invalid(std::string(what) + " spans more than the coordinate range");
  }
  Shape2D s;
  s.type = type;
  s.count = 2;
  s.radius = radius;
  s.vertices[0] = p1;
  s.vertices[1] = p2;
  s.centroid = midpoint(p1, p2);
  return s;
}

}  // namespace

Result<Shape2D> make_circle(Fx radius, Vec2 center) {
  if (radius <= Fx()) return invalid("circle radius must be > 0");
  Shape2D s;
  s.type = ShapeType2D::kCircle;
  s.count = 1;
  s.radius = radius;
  s.vertices[0] = center;
  s.centroid = center;
  return s;
}

Result<Shape2D> make_capsule(Vec2 p1, Vec2 p2, Fx radius) {
  if (radius <= Fx()) return invalid("capsule radius must be > 0");
  return two_point_shape(ShapeType2D::kCapsule, p1, p2, radius, "capsule");
}

Result<Shape2D> make_segment(Vec2 p1, Vec2 p2) {
  return two_point_shape(ShapeType2D::kSegment, p1, p2, Fx(), "segment");
}

Result<Shape2D> make_box(Fx half_width, Fx half_height) {
  return make_box(half_width, half_height, Vec2{}, Fx());
}

Result<Shape2D> make_box(Fx half_width, Fx half_height, Vec2 center, Fx angle) {
  if (half_width <= Fx() || half_height <= Fx()) return invalid("box half extents must be > 0");
  // Opposite corners are exact negatives of each other (rotation rounds
  // symmetrically), so the centroid comes out as `center` exactly.
  const fixed::Rot2 q = angle == Fx() ? fixed::Rot2::identity() : fixed::Rot2::from_angle(angle);
  const Vec2 corners[4] = {{-half_width, -half_height},
                           {half_width, -half_height},
                           {half_width, half_height},
                           {-half_width, half_height}};
  Vec2 points[4];
  for (int i = 0; i < 4; ++i) points[i] = center + fixed::rotate(q, corners[i]);
  return make_polygon(points);
}

Result<Shape2D> make_polygon(std::span<const Vec2> points, Fx radius) {
  if (radius < Fx()) return invalid("polygon radius must be >= 0");
  const Result<int> orientation = check_outline(points);
  if (!orientation.ok()) return orientation.status();
  const int n = static_cast<int>(points.size());
  Shape2D s;
  s.type = ShapeType2D::kPolygon;
  s.count = static_cast<uint8_t>(n);
  s.radius = radius;
  // A clockwise outline is walked backwards from point 0, so point 0 stays
  // first either way.
  for (int i = 0; i < n; ++i) s.vertices[i] = points[*orientation > 0 ? i : (n - i) % n];
  for (int i = 0; i < n; ++i) {
    const Vec2 e = s.vertices[(i + 1) % n] - s.vertices[i];
    // Counter-clockwise, so the outward normal is the clockwise perpendicular.
    s.normals[i] = fixed::normalized(Vec2{e.y, -e.x});
  }
  s.centroid = area_centroid(s);
  return s;
}

Status validate_shape(const Shape2D& shape) {
  // Rebuilding with the factory applies the same checks; the rebuilt value
  // must then match field for field (derived fields and zero padding too).
  Result<Shape2D> rebuilt = invalid("unknown shape type");
  switch (shape.type) {
    case ShapeType2D::kCircle:
      if (shape.count != 1) return invalid("circle count must be 1");
      rebuilt = make_circle(shape.radius, shape.vertices[0]);
      break;
    case ShapeType2D::kCapsule:
      if (shape.count != 2) return invalid("capsule count must be 2");
      rebuilt = make_capsule(shape.vertices[0], shape.vertices[1], shape.radius);
      break;
    case ShapeType2D::kSegment:
      if (shape.count != 2) return invalid("segment count must be 2");
      if (shape.radius != Fx()) return invalid("segment radius must be 0");
      rebuilt = make_segment(shape.vertices[0], shape.vertices[1]);
      break;
    case ShapeType2D::kChainSegment:
      if (shape.count != 2) return invalid("chain segment count must be 2");
      if (shape.radius != Fx()) return invalid("chain segment radius must be 0");
      rebuilt = make_chain_segment(shape.vertices[2], shape.vertices[0], shape.vertices[1],
                                   shape.vertices[3]);
      break;
    case ShapeType2D::kPolygon: {
      if (shape.count < 3 || shape.count > kMaxPolygonVertices) {
        return invalid("polygon count must be 3.." + idx(kMaxPolygonVertices));
      }
      const std::span<const Vec2> pts(shape.vertices.data(), shape.count);
      rebuilt = make_polygon(pts, shape.radius);
      if (rebuilt.ok()) {
        for (int i = 0; i < shape.count; ++i) {
          if (rebuilt->vertices[i] != shape.vertices[i]) {
            return invalid("polygon vertices must be counter-clockwise");
          }
        }
      }
      break;
    }
  }
  if (!rebuilt.ok()) return rebuilt.status();
  if (rebuilt->normals != shape.normals) return invalid("shape normals do not match its vertices");
  if (rebuilt->centroid != shape.centroid) {
    return invalid("shape centroid does not match its vertices");
  }
  if (!(*rebuilt == shape)) return invalid("shape has non-zero unused fields");
  return Status::Ok();
}

}  // namespace rwd::sim2d
