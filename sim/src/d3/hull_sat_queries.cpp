// SPDX-License-Identifier: MIT
// The separating-axis queries of a hull pair (hull_sat_queries.h), after
// D. Gregorius, "The Separating Axis Test between Convex Polyhedra" (GDC
// 2013): face queries take the other hull's deepest vertex along each
// face's inward normal; edge queries test only the edge pairs whose arcs
// cross on the Gauss map (the pairs that build a face of the Minkowski
// difference), along cross(edge_a, edge_b) turned away from A's centre.
#include "d3/hull_sat_queries.h"

#include <cmath>
#include <limits>

namespace rwd::sim::d3 {
namespace {

// Edge pairs whose cross product is shorter than this (sin^2 of the angle
// between them) are parallel; the face axes cover their direction.
constexpr float kParallelSinSquared = 1e-6f;

// An upper bound of dot(l, d) over the unit vectors l on the arc from n0
// to n1 (unit face normals of one edge, less than half a turn apart): every
// such l is (s n0 + t n1) / |s n0 + t n1| with s, t >= 0, and |s n0 + t n1|
// >= (s + t) cos(half the arc). Infinite for an arc of nearly half a turn.
float arc_bound(Vec3 n0, Vec3 n1, Vec3 d) {
  const float m = std::fmax(dot(n0, d), dot(n1, d));
  if (m <= 0.0f) return m;
  const float cos_half_sq = 0.5f * (1.0f + dot(n0, n1));
  if (cos_half_sq < 1e-6f) return std::numeric_limits<float>::infinity();
  return m / std::sqrt(cos_half_sq);
}

// Rounding allowance of the bounds below against a pair's computed
// separation (both are a few products of quantities of about a metre).
constexpr float kBoundMargin = 1e-4f;

// The radius of the largest ball about the hull's origin (its centre of
// mass) inside it: its nearest face plane's distance. Negative only for a
// degenerate hull whose origin is not inside.
float inner_radius(const HullView& h) {
  float r = h.faces[0].offset;
  for (uint32_t f = 1; f < h.face_count; ++f) r = std::fmin(r, h.faces[f].offset);
  return r;
}

}  // namespace

FaceQuery query_faces(const HullView& hull, const Vec3* other, uint32_t other_count,
                      float speculative_m) {
  FaceQuery best;
  for (uint32_t f = 0; f < hull.face_count; ++f) {
    const float sep = face_separation(hull, f, other, other_count);
    if (sep > best.separation) {
      best.separation = sep;
      best.face = f;
      if (sep > speculative_m) break;
    }
  }
  return best;
}

// Edge pairs of A and B (B's vertices and face normals in A's frame, B's
// origin at b_origin) that build a face of the Minkowski difference A - B,
// each tested along the normal of that face. Ties to the lower (edge_a,
// edge_b). Stops at a pair that separates by more than speculative_m.
//
// Only a pair that separates by more than `floor` is reported (the caller
// treats every pair at or below it alike); without one, separation is
// `floor`. That lets whole edges go untested: along an axis l of A's edge
// at vertex pa (l on the arc of its face normals, where A's support is pa),
// B reaches no lower than l.(b_origin) - (B's inner radius), so the pair
// separates by at most arc_bound(na, nb, b_origin - pa) - rB; the same
// from B's side. An edge whose bound is at or below the best so far cannot
// beat it (the test is strict), so skipping it changes no result.
EdgeQuery query_edges(const HullView& a, const HullView& b, const Vec3* b_vertices,
                      const Vec3* b_normals, Vec3 b_origin, float floor, float speculative_m) {
  EdgeQuery best;
  best.separation = floor;
  const float ra = inner_radius(a);
  const float rb = inner_radius(b);
  const bool bounded = ra >= 0.0f && rb >= 0.0f;
  // B's edges that can beat the floor, and the planes of their arcs: the
  // arc of B's edge on the Gauss map of -B runs between -c and -d (its
  // faces' normals negated); the plane through that arc has normal
  // (-d) x (-c) = d x c.
  uint32_t kept[kMaxEdges];
  Vec3 dxc[kMaxEdges];
  uint32_t kept_count = 0;
  for (uint32_t j = 0; j < b.edge_count; ++j) {
    const HullEdge& e = b.edges[j];
    if (bounded && arc_bound(b_normals[e.face_left], b_normals[e.face_right], -b_vertices[e.v0]) -
                           ra + kBoundMargin <=
                       floor) {
      continue;
    }
    kept[kept_count] = j;
    dxc[kept_count] = cross(b_normals[e.face_right], b_normals[e.face_left]);
    ++kept_count;
  }
  if (kept_count == 0) return best;
  // Per edge of A, the side of each of B's normals relative to the plane of
  // A's arc, once per face instead of twice per edge pair: most pairs fail
  // the first test below, which then costs two lookups and a product.
  float side[kMaxFaces];
  for (uint32_t i = 0; i < a.edge_count; ++i) {
    const HullEdge& ea = a.edges[i];
    const Vec3 na = a.faces[ea.face_left].normal;
    const Vec3 nb = a.faces[ea.face_right].normal;
    const Vec3 pa = a.vertices[ea.v0];
    if (bounded && arc_bound(na, nb, b_origin - pa) - rb + kBoundMargin <= best.separation) {
      continue;
    }
    const Vec3 bxa = cross(nb, na);
    for (uint32_t f = 0; f < b.face_count; ++f) side[f] = dot(b_normals[f], bxa);
    const Vec3 ua = a.vertices[ea.v1] - pa;
    const float ua_sq = length_squared(ua);
    for (uint32_t k = 0; k < kept_count; ++k) {
      const uint32_t j = kept[k];
      const HullEdge& eb = b.edges[j];
      // Arcs (na, nb) and (-nc, -nd) cross: -nc and -nd lie on opposite
      // sides of the plane of na nb, na and nb on opposite sides of the
      // plane of -nc -nd, and both arcs lie in the same hemisphere (not on
      // the antipodal crossing of the two great circles).
      const float cba = -side[eb.face_left];
      const float dba = -side[eb.face_right];
      if (!(cba * dba < 0.0f)) continue;
      const float adc = dot(na, dxc[k]);
      const float bdc = dot(nb, dxc[k]);
      if (!(adc * bdc < 0.0f && cba * bdc > 0.0f)) continue;
      const Vec3 pb = b_vertices[eb.v0];
      const Vec3 ub = b_vertices[eb.v1] - pb;
      Vec3 l = cross(ua, ub);
      const float l_sq = length_squared(l);
      if (l_sq <= kParallelSinSquared * ua_sq * length_squared(ub)) continue;
      l = l * (1.0f / std::sqrt(l_sq));
      // A's frame origin is its centre of mass, inside A; the axis points
      // out of A through its edge.
      if (dot(l, pa) < 0.0f) l = -l;
      const float sep = dot(l, pb - pa);
      if (sep > best.separation) {
        best.separation = sep;
        best.edge_a = i;
        best.edge_b = j;
        best.axis = l;
        if (sep > speculative_m) return best;
      }
    }
  }
  return best;
}

}  // namespace rwd::sim::d3
