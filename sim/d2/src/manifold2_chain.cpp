// SPDX-License-Identifier: MIT
// Chain segments (one-sided edges with ghost vertices) against circles,
// capsules and rounded polygons, after the ghost-collision method of Box2D
// (v2.4's one-sided edges, v3's b2CollideChainSegmentAndPolygon): the
// ghosts give the neighbouring edges' directions, and a contact normal is
// judged against the Gauss map of the joint (the cone of normals between
// this edge's face normal and the neighbour's).
//  - At a convex joint the neighbour's cone starts where ours ends: a
//    normal beyond the neighbour's face normal belongs to the neighbour and
//    is skipped here (the neighbour's own manifold supplies it).
//  - At a flat or concave joint there is no vertex cone: a normal that
//    would come from the joint vertex is a ghost, so the edge's face normal
//    is used instead (snapped). This is what lets a box slide over the
//    joints of collinear edges without catching on them.
// Nothing collides from behind (the left of p1 -> p2). Everything is worked
// in the chain body's frame, like the other pair routines.
#include "manifold2_internal.h"

namespace rwd::sim2d::detail {

namespace {

// Joints bent by less than about 0.6 degrees count as flat: a polyline that
// is straight up to the Q16.16 rounding of its points still slides.
constexpr W kConvexTol = w_ratio(1, 100);
// How far (as a sine) a normal may lean past the neighbour's face normal
// before the neighbour owns it.
constexpr W kSinTol = w_ratio(1, 100);

enum class NormalKind { kSkip, kAdmit, kSnap };

struct ChainEdge {
  V2 p1;
  V2 p2;
  V2 e1;  // unit direction p1 -> p2
  V2 n1;  // face normal: the right perpendicular of e1
  V2 n0;  // the previous edge's face normal (ghost1 -> p1)
  V2 n2;  // the next edge's face normal (p2 -> ghost2)
  V2 e0;  // unit direction ghost1 -> p1
  V2 e2;  // unit direction p2 -> ghost2
  bool convex1 = false;
  bool convex2 = false;
};

ChainEdge chain_edge(const Shape2D& s) {
  ChainEdge c;
  c.p1 = v_from(s.vertices[0]);
  c.p2 = v_from(s.vertices[1]);
  const V2 g1 = v_from(s.vertices[2]);
  const V2 g2 = v_from(s.vertices[3]);
  c.e1 = vnormalize(c.p2 - c.p1).unit;
  c.n1 = vperp_cw(c.e1);
  c.e0 = vnormalize(c.p1 - g1).unit;
  c.n0 = vperp_cw(c.e0);
  c.e2 = vnormalize(g2 - c.p2).unit;
  c.n2 = vperp_cw(c.e2);
  // A left turn is convex on the right-hand (colliding) side.
  c.convex1 = vcross(c.e0, c.e1) >= kConvexTol;
  c.convex2 = vcross(c.e1, c.e2) >= kConvexTol;
  return c;
}

// Where a unit normal (from the edge towards B) falls in the joint's
// Gauss map: towards p1 or towards p2, inside our vertex cone, inside the
// neighbour's, or at a joint with no vertex cone at all.
NormalKind classify(const ChainEdge& c, V2 normal) {
  if (vdot(normal, c.e1) <= 0) {
    if (!c.convex1) return NormalKind::kSnap;
    return vcross(normal, c.n0) > kSinTol ? NormalKind::kSkip : NormalKind::kAdmit;
  }
  if (!c.convex2) return NormalKind::kSnap;
  return vcross(c.n2, normal) > kSinTol ? NormalKind::kSkip : NormalKind::kAdmit;
}

// The chain edge as a rounded two-gon of radius 0 (face 0 is the front).
WPoly edge_wpoly(const ChainEdge& c) {
  WPoly p;
  p.count = 2;
  p.vertices[0] = c.p1;
  p.vertices[1] = c.p2;
  p.normals[0] = c.n1;
  p.normals[1] = -c.n1;
  return p;
}

int next_vertex(const WPoly& p, int i) {
  return i + 1 < p.count ? i + 1 : 0;
}

// Whether the incident face inc_edge of `inc` overlaps the reference face
// ref_edge of `ref` along the reference face's tangent. A face wholly past
// one end of the reference face lies over a neighbour's territory; clipping
// it would extrapolate points off the face.
bool faces_overlap(const WPoly& ref, int ref_edge, const WPoly& inc, int inc_edge) {
  const V2 v11 = ref.vertices[ref_edge];
  const V2 tangent = vperp(ref.normals[ref_edge]);
  const W upper1 = vdot(ref.vertices[next_vertex(ref, ref_edge)] - v11, tangent);
  const W a = vdot(inc.vertices[inc_edge] - v11, tangent);
  const W b = vdot(inc.vertices[next_vertex(inc, inc_edge)] - v11, tangent);
  return wmax(a, b) >= 0 && wmin(a, b) <= upper1;
}

// The face of p most anti-parallel to `direction`; ties keep the lowest.
int most_antiparallel(const WPoly& p, V2 direction) {
  int edge = 0;
  W min_dot = INT64_MAX;
  for (int i = 0; i < p.count; ++i) {
    const W d = vdot(direction, p.normals[i]);
    if (d < min_dot) {
      min_dot = d;
      edge = i;
    }
  }
  return edge;
}

// The least signed distance of p's vertices from the line through `origin`
// with unit normal n (and the vertex that has it).
W min_along(const WPoly& p, V2 n, V2 origin, int* deepest = nullptr) {
  W best = INT64_MAX;
  for (int i = 0; i < p.count; ++i) {
    const W s = vdot(n, p.vertices[i] - origin);
    if (s < best) {
      best = s;
      if (deepest != nullptr) *deepest = i;
    }
  }
  return best;
}

struct VertexPair {
  bool found = false;
  int edge_vertex = 0;  // 0: p1, 1: p2
  int poly_vertex = 0;
};

// When the cores are apart, whether their nearest features are an end of
// the edge and a vertex of B: each lies strictly inside the other's normal
// cone (beyond the edge's end; beyond both faces meeting at the vertex).
// For convex cores those conditions single out the nearest pair.
VertexPair nearest_vertices(const ChainEdge& c, const WPoly& b) {
  for (int k = 0; k < 2; ++k) {
    const V2 p = k == 0 ? c.p1 : c.p2;
    for (int j = 0; j < b.count; ++j) {
      const V2 v = b.vertices[j];
      const W along = vdot(v - p, c.e1);
      if (k == 0 ? along >= 0 : along <= 0) continue;
      const V2 prev = b.vertices[j > 0 ? j - 1 : b.count - 1];
      const V2 next = b.vertices[next_vertex(b, j)];
      if (vdot(p - v, v - prev) > 0 && vdot(p - v, next - v) < 0) return {true, k, j};
    }
  }
  return {};
}

// The edge's face is the reference: B's most anti-parallel face is clipped
// to the edge's span, and the normal is exactly the face normal.
void clip_to_edge(const WPoly& edge, const WPoly& b, const Xf& xa, const Xf& xb, W speculative,
                  Manifold2& out) {
  const int inc = most_antiparallel(b, edge.normals[0]);
  if (!faces_overlap(edge, 0, b, inc)) return;
  clip(edge, b, 0, inc, false, xa, xb, speculative, out);
}

}  // namespace

void collide_chain_circle(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                          W speculative, Manifold2& out) {
  out = {};
  const ChainEdge c = chain_edge(a);
  const V2 center = transform_point(inv_mul_xf(xa, xb), v_from(b.vertices[0]));
  const W rb = w_from(b.radius);
  const W offset = vdot(c.n1, center - c.p1);
  if (offset < 0) return;  // behind: one-sided
  const W v = vdot(center - c.p1, c.e1);
  const W u = vdot(c.p2 - center, c.e1);
  // At a convex joint the wedge past both ends is answered by both edges
  // with the same vertex point (as in Box2D); the solver shares the load.
  if (v < 0) {
    // Before p1: if the centre is not also past the previous edge's end,
    // it is in the previous edge's region and that edge answers.
    if (vdot(c.e0, center - c.p1) <= 0) return;
    collide_round_pair(c.p1, 0, center, rb, c.n1, xa, xb, speculative, out);
    return;
  }
  if (u < 0) {
    if (vdot(c.e2, center - c.p2) >= 0) return;
    collide_round_pair(c.p2, 0, center, rb, c.n1, xa, xb, speculative, out);
    return;
  }
  // Over the face: the face normal itself, not the (rounded) direction
  // from the projected point, so a circle on a flat chain is pushed
  // exactly along the normal on every edge.
  const W separation = offset - rb;
  if (separation > speculative) return;
  const V2 ca = vmul_sub(center, offset, c.n1);
  const V2 cb = vmul_sub(center, rb, c.n1);
  set_point(out.points[0], xa, xb, vmid(ca, cb), separation, 0);
  finish(out, xa, c.n1, 1);
}

void collide_chain_polygon(const Shape2D& a, const Xf& xa, const Shape2D& b, const Xf& xb,
                           W speculative, Manifold2& out) {
  out = {};
  const ChainEdge c = chain_edge(a);
  const Xf xf = inv_mul_xf(xa, xb);
  const WPoly poly = transform_wpoly(xf, to_wpoly(b));
  const WPoly edge = edge_wpoly(c);
  const W rb = poly.radius;

  // One-sided: B's centroid behind this edge's face and behind each convex
  // neighbour's face means B is inside the solid (or came from behind).
  const V2 centroid = transform_point(xf, v_from(b.centroid));
  const bool behind1 = vdot(c.n1, centroid - c.p1) < 0;
  const bool behind0 = !c.convex1 || vdot(c.n0, centroid - c.p1) < 0;
  const bool behind2 = !c.convex2 || vdot(c.n2, centroid - c.p2) < 0;
  if (behind1 && behind0 && behind2) return;

  // Separation along the face normal; a convex neighbour's face normal is
  // also a separating axis of this edge, and if it separates more the
  // neighbour owns the contact.
  W edge_sep = min_along(poly, c.n1, c.p1);
  bool neighbour_axis = false;
  if (c.convex1) {
    const W s0 = min_along(poly, c.n0, c.p1);
    if (s0 > edge_sep) {
      edge_sep = s0;
      neighbour_axis = true;
    }
  }
  if (c.convex2) {
    const W s2 = min_along(poly, c.n2, c.p2);
    if (s2 > edge_sep) {
      edge_sep = s2;
      neighbour_axis = true;
    }
  }
  // B's faces, each only if its (reversed) normal is admitted at the joint
  // it would come from: a face normal snapped or owned by a neighbour is a
  // ghost and may not become the contact normal.
  W poly_sep = INT64_MIN;
  int reference = -1;
  for (int i = 0; i < poly.count; ++i) {
    const V2 n = poly.normals[i];
    if (classify(c, -n) != NormalKind::kAdmit) continue;
    const V2 v = poly.vertices[i];
    const W s = wmin(vdot(n, c.p1 - v), vdot(n, c.p2 - v));
    if (s > poly_sep) {
      poly_sep = s;
      reference = i;
    }
  }
  if (wmax(edge_sep, poly_sep) > speculative + rb) return;

  // Apart cores whose nearest features are two vertices: the normal runs
  // between them, if the joint admits it.
  if (wmax(edge_sep, poly_sep) > kVertexGap) {
    const VertexPair vp = nearest_vertices(c, poly);
    if (vp.found) {
      const V2 pa = vp.edge_vertex == 0 ? c.p1 : c.p2;
      const V2 pb = poly.vertices[vp.poly_vertex];
      const UnitLength d = vnormalize(pb - pa);
      switch (classify(c, d.unit)) {
        case NormalKind::kSkip:
          return;
        case NormalKind::kAdmit: {
          const W separation = d.length - rb;
          if (separation > speculative) return;
          const V2 cb = vmul_sub(pb, rb, d.unit);
          set_point(out.points[0], xa, xb, vmid(pa, cb), separation,
                    make_id(vp.edge_vertex, vp.poly_vertex));
          finish(out, xa, d.unit, 1);
          return;
        }
        case NormalKind::kSnap:
          clip_to_edge(edge, poly, xa, xb, speculative, out);
          return;
      }
    }
  }

  if (reference >= 0 && poly_sep > edge_sep + kReferenceTolerance) {
    // B's face is the reference. If the edge's deeper end leads onto a
    // neighbour that faces B's face more squarely, that neighbour is the
    // incident feature and answers for the contact.
    const V2 n = poly.normals[reference];
    const V2 v = poly.vertices[reference];
    const bool p1_deeper = vdot(n, c.p1 - v) < vdot(n, c.p2 - v);
    const V2 neighbour = p1_deeper ? (c.convex1 ? c.n0 : c.n1) : (c.convex2 ? c.n2 : c.n1);
    if (vdot(neighbour, n) < vdot(c.n1, n)) return;
    const int inc = vdot(n, c.n1) <= 0 ? 0 : 1;
    if (!faces_overlap(poly, reference, edge, inc)) return;
    clip(poly, edge, reference, inc, true, xa, xb, speculative, out);
    return;
  }
  if (neighbour_axis) return;
  clip_to_edge(edge, poly, xa, xb, speculative, out);
}

}  // namespace rwd::sim2d::detail
