// SPDX-License-Identifier: MIT
#include "d3/cast_exact.h"

#include <cmath>

#include "d3/slab_interval.h"

namespace rwd::sim::d3 {
namespace {

using gjk_detail::mul_transpose;

float sign_of(float v) {
  return v < 0.0f ? -1.0f : 1.0f;
}

float clamp(float v, float lo, float hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

Vec3 clamp_to_box(Vec3 p, Vec3 h) {
  return {clamp(p.x, -h.x, h.x), clamp(p.y, -h.y, h.y), clamp(p.z, -h.z, h.z)};
}

void set_component(Vec3& v, int i, float value) {
  (i == 0 ? v.x : i == 1 ? v.y : v.z) = value;
}

// The first t in [0, t_max] at which o + t d is within r of q (the ray
// starts farther than r from it). From the point of closest approach, not
// as the roots of |o + t d - q|^2 = r^2: with the ray starting far away
// that difference of large squares loses the centimetres a long cast needs.
bool ray_ball(Vec3 o, Vec3 d, Vec3 q, float r, float t_max, float& t) {
  const Vec3 m = o - q;
  const float dd = dot(d, d);
  if (!(dd > 0.0f)) return false;
  const float closest_t = -dot(m, d) / dd;
  if (closest_t < 0.0f) return false;  // moving away
  const Vec3 closest = m + d * closest_t;
  const float miss_sq = r * r - dot(closest, closest);
  if (miss_sq < 0.0f) return false;
  t = closest_t - std::sqrt(miss_sq / dd);
  if (t < 0.0f) t = 0.0f;
  return t <= t_max;
}

// The first t in [0, t_max] at which o + t d is within r of the box edge
// through `corner` along axis k (its other two coordinates are corner's;
// along k it runs from -h_k to h_k): the edge's cylinder, else the ball of
// the end the ray meets the cylinder beyond. The ray starts near the box
// (callers start it where it enters the box's slabs grown by r), outside
// the rounded box or on it.
bool ray_edge(Vec3 o, Vec3 d, Vec3 corner, int k, Vec3 h, float r, float t_max, float& t) {
  const int i = (k + 1) % 3;
  const int j = (k + 2) % 3;
  const float ux = component(o, i) - component(corner, i);
  const float uy = component(o, j) - component(corner, j);
  const float vx = component(d, i);
  const float vy = component(d, j);
  const bool within = ux * ux + uy * uy <= r * r;
  float s = component(o, k);  // where along the edge the cylinder is met
  if (within) {
    // Already within the cylinder: touching now if within the edge's
    // length (an entry point on the rounded edge, up to rounding), else
    // beyond one end of it.
    t = 0.0f;
  } else {
    // The closest approach to the edge's line, as in ray_ball.
    const float vv = vx * vx + vy * vy;
    if (!(vv > 0.0f)) return false;
    const float closest_t = -(ux * vx + uy * vy) / vv;
    if (closest_t < 0.0f) return false;  // moving away from the line
    const float cx = ux + vx * closest_t;
    const float cy = uy + vy * closest_t;
    const float miss_sq = r * r - (cx * cx + cy * cy);
    if (miss_sq < 0.0f) return false;
    t = closest_t - std::sqrt(miss_sq / vv);
    if (t < 0.0f) t = 0.0f;
    if (t > t_max) return false;
    s += t * component(d, k);
  }
  const float hk = component(h, k);
  if (s >= -hk && s <= hk) return true;
  Vec3 end = corner;
  set_component(end, k, s < 0.0f ? -hk : hk);
  return ray_ball(o, d, end, r, t_max, t);
}

enum class Cast { kMiss, kHit, kOverlap };

// A ball of radius r whose centre moves along o + t d, t in [0, t_max],
// against the box of half extents h at the origin: the first touch, the
// normal out of the box there and the box's point nearest the ball.
Cast ball_at_box(Vec3 o, Vec3 d, Vec3 h, float r, float t_max, float& t, Vec3& normal,
                 Vec3& point) {
  // The slabs of the box grown by r.
  float t_lo = 0.0f;
  float t_hi = t_max;
  int entered = -1;  // the slab entered last, if the ray starts outside one
  for (int i = 0; i < 3; ++i) {
    const float oi = component(o, i);
    const float di = component(d, i);
    const float e = component(h, i) + r;
    if (di == 0.0f) {
      if (oi < -e || oi > e) return Cast::kMiss;
      continue;
    }
    float t0 = 0.0f;
    float t1 = 0.0f;
    slab_interval(oi, di, e, t0, t1);
    if (t0 > t_lo) {
      t_lo = t0;
      entered = i;
    }
    if (t1 < t_hi) t_hi = t1;
    if (t_lo > t_hi) return Cast::kMiss;
  }
  const Vec3 p = o + d * t_lo;
  // Which of the box's slabs the entry point lies outside: one (or none) is
  // a face of the rounded box; two an edge's cylinder, three a corner's.
  int outside = 0;
  int inside_axis = 0;
  Vec3 corner;
  for (int i = 0; i < 3; ++i) {
    const float pi = component(p, i);
    const float hi = component(h, i);
    if (i == entered || pi > hi || pi < -hi) {
      ++outside;
      set_component(corner, i, sign_of(pi) * hi);
    } else {
      inside_axis = i;
    }
  }
  if (entered < 0 && length_squared(o - clamp_to_box(o, h)) <= r * r) return Cast::kOverlap;
  if (outside <= 1) {
    if (entered < 0) return Cast::kOverlap;  // inside a face's slab: rounding only
    t = t_lo;
    normal = Vec3{};
    set_component(normal, entered, sign_of(component(p, entered)));
    point = clamp_to_box(p - normal * r, h);
    return Cast::kHit;
  }
  // The edges' cylinders and the corners' balls, from the entry point (near
  // the box, so their quadratics keep their precision on a long cast).
  bool found = false;
  float after = t_max - t_lo;
  for (int k = 0; k < 3; ++k) {
    if (outside == 2 && k != inside_axis) continue;
    float tk = 0.0f;
    if (ray_edge(p, d, corner, k, h, r, after, tk) && (!found || tk < after)) {
      after = tk;
      found = true;
    }
  }
  if (!found) return Cast::kMiss;
  t = t_lo + after;
  const Vec3 at = p + d * after;
  point = clamp_to_box(at, h);
  normal = normalize_or_zero(at - point);
  return Cast::kHit;
}

// A ball (centre `ball`, radius r) and a box (half extents h, centre at
// `box_position`, `box_axes`), one of them swept by `translation`. With
// `box_swept` the box moves and the ball stands still (the target): the
// ball moves by -translation relative to the box, and the normal runs from
// the ball to the box.
bool ball_box(Vec3 ball, float r, Vec3 box_position, const Mat3& box_axes, Vec3 h, Vec3 translation,
              float max_fraction, bool box_swept, ShapeCastOutput& out) {
  const Vec3 o = mul_transpose(box_axes, ball - box_position);
  const Vec3 d = mul_transpose(box_axes, box_swept ? -translation : translation);
  float t = 0.0f;
  Vec3 normal;
  Vec3 point;
  const Cast cast = ball_at_box(o, d, h, r, max_fraction, t, normal, point);
  if (cast == Cast::kOverlap) return false;
  out = ShapeCastOutput{};
  if (cast == Cast::kMiss) return true;
  out.hit = true;
  out.fraction = t;
  const Vec3 n = box_axes * normal;
  if (box_swept) {
    out.normal = -n;
    out.point = ball + out.normal * r;
  } else {
    out.normal = n;
    out.point = box_position + box_axes * point;
  }
  return true;
}

bool ball_ball(Vec3 target, float target_radius, Vec3 c, float r, Vec3 translation,
               float max_fraction, ShapeCastOutput& out) {
  const float reach = target_radius + r;
  if (length_squared(c - target) <= reach * reach) return false;
  out = ShapeCastOutput{};
  float t = 0.0f;
  if (!ray_ball(c, translation, target, reach, max_fraction, t)) return true;
  out.hit = true;
  out.fraction = t;
  out.normal = normalize_or_zero((c + translation * t) - target);
  out.point = target + out.normal * target_radius;
  return true;
}

// The offset from a box's centre to its support feature's centre along
// `dir`: each axis (a column of `axes`) nearly across dir (|dir . axis| <=
// tie) contributes nothing, so a face gives its centre and an edge its
// middle. Returns how many axes were across.
int support_centre(const Mat3& axes, Vec3 h, Vec3 dir, float tie, Vec3& offset) {
  const Vec3 cols[3] = {axes.c0, axes.c1, axes.c2};
  int across = 0;
  offset = Vec3{};
  for (int j = 0; j < 3; ++j) {
    const float a = dot(dir, cols[j]);
    if (a <= tie && a >= -tie) {
      ++across;
      continue;
    }
    offset += cols[j] * (sign_of(a) * component(h, j));
  }
  return across;
}

constexpr float kFeatureTie = 1e-4f;  // |cos| below which an axis lies across a normal

// The segments p + s u (|s| <= hu) and q + w v (|w| <= hv), u and v unit:
// the first one's point nearest the second.
Vec3 segment_nearest(Vec3 p, Vec3 u, float hu, Vec3 q, Vec3 v, float hv) {
  const Vec3 r = p - q;
  const float b = dot(u, v);
  const float du = dot(u, r);
  const float dv = dot(v, r);
  const float denom = 1.0f - b * b;
  float s = denom > 1e-8f ? (b * dv - du) / denom : 0.0f;
  s = clamp(s, -hu, hu);
  const float w = clamp(dv + s * b, -hv, hv);
  s = clamp(w * b - du, -hu, hu);
  return p + u * s;
}

// Box B (centre c, axes R, half extents hb; all in A's frame) touching box
// A (half extents ha, at the origin, axes the frame's) across `n` (unit,
// from A to B), found on axis `kind` (0: a face of A, 1: a face of B, 2:
// an edge of each), numbered i (A's axis) and j (B's): a point of the
// touching features, on A's surface.
Vec3 box_touch_point(Vec3 ha, Vec3 c, const Mat3& r, Vec3 hb, Vec3 n, int kind, int i, int j) {
  const Mat3 identity;
  const Vec3 b_cols[3] = {r.c0, r.c1, r.c2};
  if (kind == 0) {
    // B's deepest feature, brought onto A's face and within its bounds.
    Vec3 offset;
    support_centre(r, hb, -n, kFeatureTie, offset);
    Vec3 p = clamp_to_box(c + offset, ha);
    set_component(p, i, sign_of(component(n, i)) * component(ha, i));
    return p;
  }
  if (kind == 1) {
    // A's feature facing B's face: a corner, or an edge clipped to the face.
    Vec3 q;
    const int across = support_centre(identity, ha, n, kFeatureTie, q);
    const Vec3 face = c - n * component(hb, j);
    if (across == 0) return q;
    int k = 0;
    for (int m = 0; m < 3; ++m) {
      const float nm = component(n, m);
      if (nm <= kFeatureTie && nm >= -kFeatureTie) k = m;
    }
    if (across >= 2) {
      // A face parallel to B's: B's face centre on A's face.
      Vec3 p = clamp_to_box(face, ha);
      for (int m = 0; m < 3; ++m) {
        const float nm = component(n, m);
        if (nm > kFeatureTie || nm < -kFeatureTie)
          set_component(p, m, sign_of(nm) * component(ha, m));
      }
      return p;
    }
    float lo = -component(ha, k);
    float hi = component(ha, k);
    for (int m = 0; m < 3; ++m) {
      if (m == j) continue;
      const float alpha = dot(q - face, b_cols[m]);
      const float beta = component(b_cols[m], k);
      const float hm = component(hb, m);
      if (beta > 1e-6f || beta < -1e-6f) {
        float l0 = 0.0f;
        float l1 = 0.0f;
        slab_interval(alpha, beta, hm, l0, l1);
        if (l0 > lo) lo = l0;
        if (l1 < hi) hi = l1;
      }
    }
    const float lambda = lo <= hi ? 0.5f * (lo + hi) : 0.0f;
    Vec3 p = q;
    set_component(p, k, lambda);
    return p;
  }
  // Edge against edge: A's edge along axis i, B's along its axis j.
  Vec3 qa;
  support_centre(identity, ha, n, kFeatureTie, qa);
  set_component(qa, i, 0.0f);
  Vec3 qb;
  support_centre(r, hb, -n, kFeatureTie, qb);
  qb = qb - b_cols[j] * dot(qb, b_cols[j]);
  Vec3 ea;
  set_component(ea, i, 1.0f);
  return segment_nearest(qa, ea, component(ha, i), c + qb, b_cols[j], component(hb, j));
}

// Box B swept against box A by the separating axes (see the header).
bool box_box(Vec3 pa, const Mat3& axes_a, Vec3 ha, Vec3 pb, const Mat3& axes_b, Vec3 hb,
             Vec3 translation, float max_fraction, ShapeCastOutput& out) {
  const Vec3 c = mul_transpose(axes_a, pb - pa);
  const Vec3 d = mul_transpose(axes_a, translation);
  const Mat3 r{mul_transpose(axes_a, axes_b.c0), mul_transpose(axes_a, axes_b.c1),
               mul_transpose(axes_a, axes_b.c2)};
  const Vec3 b_cols[3] = {r.c0, r.c1, r.c2};
  const float speed = length(d);
  // Fractions this close pick the simpler feature for the normal.
  const float tie = speed > 0.0f ? 1e-4f / speed : 0.0f;
  float t_enter = -INFINITY;
  float t_exit = INFINITY;
  float best = -INFINITY;
  Vec3 best_axis;
  int best_kind = 0;
  int best_i = 0;
  int best_j = 0;
  for (int kind = 0; kind < 3; ++kind) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (kind != 2 && j > 0) break;
        Vec3 l;
        if (kind == 0) {
          set_component(l, i, 1.0f);
        } else if (kind == 1) {
          l = b_cols[i];
        } else {
          Vec3 e;
          set_component(e, i, 1.0f);
          l = cross(e, b_cols[j]);
          if (length_squared(l) < 1e-6f) continue;  // parallel edges: the faces decide
        }
        const float extent = ha.x * std::fabs(l.x) + ha.y * std::fabs(l.y) + ha.z * std::fabs(l.z) +
                             hb.x * std::fabs(dot(l, r.c0)) + hb.y * std::fabs(dot(l, r.c1)) +
                             hb.z * std::fabs(dot(l, r.c2));
        const float s0 = dot(l, c);
        const float v = dot(l, d);
        if (v == 0.0f) {
          if (s0 > extent || s0 < -extent) {
            out = ShapeCastOutput{};
            return true;
          }
          continue;
        }
        float t0 = 0.0f;
        float t1 = 0.0f;
        slab_interval(s0, v, extent, t0, t1);
        if (t1 < t_exit) t_exit = t1;
        if (t0 > t_enter) t_enter = t0;
        // Apart on this axis for the whole sweep: most candidates a query's
        // tree gives end here, at one of A's faces.
        if (t_enter > t_exit || t_exit < 0.0f || t_enter > max_fraction) {
          out = ShapeCastOutput{};
          return true;
        }
        if (t0 > best + (kind == 0 ? 0.0f : tie)) {
          best = t0;
          best_axis = v > 0.0f ? -l : l;
          best_kind = kind;
          best_i = kind == 1 ? 0 : i;
          best_j = kind == 1 ? i : j;
        }
      }
    }
  }
  if (!(t_enter > 0.0f)) return false;  // touching at the start: GJK and EPA
  const Vec3 n = normalize_or_zero(best_axis);
  const Vec3 point = box_touch_point(ha, c + d * t_enter, r, hb, n, best_kind, best_i, best_j);
  out = ShapeCastOutput{};
  out.hit = true;
  out.fraction = t_enter;
  out.normal = axes_a * n;
  out.point = pa + axes_a * point;
  return true;
}

}  // namespace

bool cast_exact(const Shape& target, Vec3 position, const Mat3& axes, const Shape& swept_shape,
                const ConvexProxy& swept, Vec3 translation, float max_fraction,
                ShapeCastOutput& out) {
  const bool ball = swept_shape.type == ShapeType::kSphere;
  const bool box = swept_shape.type == ShapeType::kBox;
  if (!ball && !box) return false;
  if (target.type == ShapeType::kSphere) {
    if (ball) {
      return ball_ball(position, target.radius, swept.position + swept.axes * swept.points[0],
                       swept.radius, translation, max_fraction, out);
    }
    return ball_box(position, target.radius, swept.position, swept.axes, swept_shape.half_extents,
                    translation, max_fraction, true, out);
  }
  if (target.type != ShapeType::kBox) return false;
  if (ball) {
    return ball_box(swept.position + swept.axes * swept.points[0], swept.radius, position, axes,
                    target.half_extents, translation, max_fraction, false, out);
  }
  return box_box(position, axes, target.half_extents, swept.position, swept.axes,
                 swept_shape.half_extents, translation, max_fraction, out);
}

}  // namespace rwd::sim::d3
