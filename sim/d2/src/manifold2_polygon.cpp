// SPDX-License-Identifier: MIT
// Rounded convex polygons against each other, after Box2D v3's
// b2CollidePolygons: the separating axis test picks a reference face (A's
// unless B's is clearly deeper), the most anti-parallel face of the other
// polygon is the incident face, and the incident face clipped to the
// reference face's side planes gives up to two points. Separated cores
// whose nearest features are two vertices get one vertex-vertex point
// instead, whose normal is the direction between those vertices.
#include "manifold2_internal.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::sim2d::detail {

namespace {

int next_index(const WPoly& p, int i) {
  return i + 1 < p.count ? i + 1 : 0;
}

struct EdgeSeparation {
  int edge = 0;
  W separation = INT64_MIN;
};

// n . d for a unit normal n. A normal along an axis (every face of a box
// in the box's own frame, which the first shape of a pair is in) gives the
// component of d or its negative: vdot's product by 2^32 plus the half
// rounds back to exactly that, so the shortcut changes no bit and spares
// the polygon test most of its 128-bit products.
W normal_dot(V2 n, V2 d) {
  if (n.y == 0 && (n.x == kWOne || n.x == -kWOne)) return n.x > 0 ? d.x : -d.x;
  if (n.x == 0 && (n.y == kWOne || n.y == -kWOne)) return n.y > 0 ? d.y : -d.y;
  return vdot(n, d);
}

// The face of p1 with the largest separation from p2 (the deepest vertex of
// p2 measured against each face of p1); ties keep the lowest index.
EdgeSeparation find_max_separation(const WPoly& p1, const WPoly& p2) {
  EdgeSeparation best;
  for (int i = 0; i < p1.count; ++i) {
    W si = INT64_MAX;
    for (int j = 0; j < p2.count; ++j) {
      si = wmin(si, normal_dot(p1.normals[i], p2.vertices[j] - p1.vertices[i]));
    }
    if (si > best.separation) best = {i, si};
  }
  return best;
}

// The face of p whose normal is most anti-parallel to `direction`.
int incident_edge(const WPoly& p, V2 direction) {
  int edge = 0;
  W min_dot = INT64_MAX;
  for (int i = 0; i < p.count; ++i) {
    const W d = normal_dot(direction, p.normals[i]);
    if (d < min_dot) {
      min_dot = d;
      edge = i;
    }
  }
  return edge;
}

U128 length_sq_exact(V2 v) {
  return static_cast<U128>(static_cast<I128>(v.x) * v.x + static_cast<I128>(v.y) * v.y);
}

struct Candidate {
  U128 distance_sq = 0;
  bool clamped = false;  // the nearest point is an end of the other segment
  int vertex1 = 0;       // 0: p1, 1: q1
  int vertex2 = 0;       // 0: p2, 1: q2
};

// The point `pt` against segment a..b: which end it is nearest to, if an
// end, and the exact squared distance.
Candidate point_segment(V2 pt, V2 a, V2 b) {
  const V2 d = b - a;
  const W num = vdot(pt - a, d);
  const W den = vdot(d, d);
  Candidate c;
  V2 nearest;
  if (num <= 0) {
    nearest = a;
    c.clamped = true;
  } else if (num >= den) {
    nearest = b;
    c.clamped = true;
    c.vertex2 = 1;
  } else {
    nearest = lerp_ratio(a, b, num, den);
  }
  c.distance_sq = length_sq_exact(pt - nearest);
  return c;
}

// Whether the nearest points of two disjoint segments are one end of each
// (Box2D's "fraction 0 or 1 on both"), and which ends. The minimum is at an
// end of one of them, so four end-to-segment tests find it. A tie between
// different end pairs, or with an interior point, means parallel edges
// that overlap: they are clipped, not treated as a vertex pair.
bool nearest_vertex_pair(V2 p1, V2 q1, V2 p2, V2 q2, int& vertex1, int& vertex2) {
  Candidate c[4] = {point_segment(p1, p2, q2), point_segment(q1, p2, q2), point_segment(p2, p1, q1),
                    point_segment(q2, p1, q1)};
  // Express every candidate as (end of segment 1, end of segment 2): for
  // c[2] and c[3] the end of segment 1 came out in vertex2.
  c[1].vertex1 = 1;
  c[2] = {c[2].distance_sq, c[2].clamped, c[2].vertex2, 0};
  c[3] = {c[3].distance_sq, c[3].clamped, c[3].vertex2, 1};
  U128 best = c[0].distance_sq;
  for (int i = 1; i < 4; ++i) best = c[i].distance_sq < best ? c[i].distance_sq : best;
  bool found = false;
  for (const Candidate& k : c) {
    if (k.distance_sq != best) continue;
    if (!k.clamped) return false;
    if (found && (k.vertex1 != vertex1 || k.vertex2 != vertex2)) return false;
    vertex1 = k.vertex1;
    vertex2 = k.vertex2;
    found = true;
  }
  return found;
}

}  // namespace

// Clips the incident face of `inc` to the side planes of the reference face
// `ref_edge` of `ref`; points in A's frame. `flip`: B holds the reference.
void clip(const WPoly& ref, const WPoly& inc, int ref_edge, int inc_edge, bool flip, const Xf& xa,
          const Xf& xb, W speculative, Manifold2& out) {
  const int i11 = ref_edge;
  const int i12 = next_index(ref, i11);
  const int i21 = inc_edge;
  const int i22 = next_index(inc, i21);
  const V2 normal = ref.normals[i11];
  const V2 v11 = ref.vertices[i11];
  const V2 v12 = ref.vertices[i12];
  const V2 v21 = inc.vertices[i21];
  const V2 v22 = inc.vertices[i22];
  const V2 tangent = vperp(normal);

  const W lower1 = 0;
  const W upper1 = normal_dot(tangent, v12 - v11);
  // Both outlines run counter-clockwise, so the incident face runs against
  // the tangent: v21 is its upper end.
  const W upper2 = normal_dot(tangent, v21 - v11);
  const W lower2 = normal_dot(tangent, v22 - v11);
  const W span = upper2 - lower2;

  V2 v_lower = v22;
  if (lower2 < lower1 && span > 0) v_lower = lerp_ratio(v22, v21, lower1 - lower2, span);
  V2 v_upper = v21;
  if (upper2 > upper1 && span > 0) v_upper = lerp_ratio(v22, v21, upper1 - lower2, span);

  const W sep_lower = normal_dot(normal, v_lower - v11);
  const W sep_upper = normal_dot(normal, v_upper - v11);
  // Midway between the surfaces: the reference surface lies ref.radius out
  // along the normal, the incident one inc.radius back.
  v_lower = vmul_add(v_lower, (ref.radius - inc.radius - sep_lower) / 2, normal);
  v_upper = vmul_add(v_upper, (ref.radius - inc.radius - sep_upper) / 2, normal);
  const W radius = ref.radius + inc.radius;

  struct Clipped {
    V2 point;
    W separation;
    uint16_t id;
  };
  Clipped pts[2];
  if (!flip) {
    pts[0] = {v_lower, sep_lower - radius, make_id(i11, i22)};
    pts[1] = {v_upper, sep_upper - radius, make_id(i12, i21)};
  } else {
    // The reference belongs to B: ids stay (A's vertex, B's vertex), and the
    // point at the start of A's edge comes first, as in the unflipped case.
    pts[0] = {v_upper, sep_upper - radius, make_id(i21, i12)};
    pts[1] = {v_lower, sep_lower - radius, make_id(i22, i11)};
  }
  int count = 0;
  for (const Clipped& c : pts) {
    if (c.separation > speculative) continue;
    set_point(out.points[count], xa, xb, c.point, c.separation, c.id);
    ++count;
  }
  finish(out, xa, flip ? -normal : normal, count);
  if (count == 0) out.normal = {};
}

void collide_wpolys(const WPoly& a, const Xf& xa, const WPoly& b_body, const Xf& xb, W speculative,
                    Manifold2& out) {
  out = {};
  const WPoly b = transform_wpoly(inv_mul_xf(xa, xb), b_body);
  EdgeSeparation sa = find_max_separation(a, b);
  EdgeSeparation sb = find_max_separation(b, a);
  const W radius = a.radius + b.radius;
  if (sa.separation > speculative + radius || sb.separation > speculative + radius) return;

  // A's face is the reference unless B's is deeper by more than the
  // tolerance, so near-ties always resolve the same way.
  const bool flip = sb.separation > sa.separation + kReferenceTolerance;
  if (flip) {
    sa.edge = incident_edge(a, b.normals[sb.edge]);
  } else {
    sb.edge = incident_edge(b, a.normals[sa.edge]);
  }

  if (wmax(sa.separation, sb.separation) > kVertexGap) {
    const int i11 = sa.edge;
    const int i12 = next_index(a, i11);
    const int i21 = sb.edge;
    const int i22 = next_index(b, i21);
    int va = 0;
    int vb = 0;
    if (nearest_vertex_pair(a.vertices[i11], a.vertices[i12], b.vertices[i21], b.vertices[i22], va,
                            vb)) {
      const int ia = va == 0 ? i11 : i12;
      const int ib = vb == 0 ? i21 : i22;
      const V2 pa = a.vertices[ia];
      const V2 pb = b.vertices[ib];
      const UnitLength d = vnormalize(pb - pa);
      const W separation = d.length - radius;
      if (separation > speculative) return;
      const V2 ca = vmul_add(pa, a.radius, d.unit);
      const V2 cb = vmul_sub(pb, b.radius, d.unit);
      set_point(out.points[0], xa, xb, vmid(ca, cb), separation, make_id(ia, ib));
      finish(out, xa, d.unit, 1);
      return;
    }
  }
  if (flip) {
    clip(b, a, sb.edge, sa.edge, true, xa, xb, speculative, out);
  } else {
    clip(a, b, sa.edge, sb.edge, false, xa, xb, speculative, out);
  }
}

void collide_polygons(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb, W speculative,
                      Manifold2& out) {
  collide_wpolys(to_wpoly(a), xa, to_wpoly(b), xb, speculative, out);
}

}  // namespace rwd::sim2d::detail
