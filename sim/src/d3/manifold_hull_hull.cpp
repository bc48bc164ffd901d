// SPDX-License-Identifier: MIT
// Hull-hull manifold by the separating-axis test (D. Gregorius, "The
// Separating Axis Test between Convex Polyhedra", GDC 2013): the face and
// edge queries (hull_sat_queries.cpp) give the best axis, then either
//  - a face contact: the incident face (the other hull's face most
//    anti-parallel to the reference face) is clipped against the reference
//    face's side planes (polygon_clip.h), points within the speculative
//    distance are kept, midway between the surfaces, and reduced to four; or
//  - an edge contact: one point midway between the closest points of the
//    two edges.
// The other hull is brought into each hull's own frame once (at most 64
// vertices each way), so every query reads the hulls' stored planes as they
// are; A's faces are tested in A's frame and B's in B's.
//
// Feature ids:
//   face contact: bit 31 clear; bit 30 = reference face is on hull B;
//     bits 23-29 reference face index, bits 16-22 incident face index;
//     bits 7-13 and 0-6 the two lines the point lies on, the polygon side
//     arriving at it (7-13) and the side leaving it (0-6), in the clipped
//     polygon's order. A line is incident loop edge k (from loop vertex k
//     to k + 1) as k, or reference side plane s (the side through reference
//     loop vertices s and s + 1) as 64 + s. An incident vertex that survives
//     clipping is (k - 1, k); a point where incident edge k leaves through
//     side s is (k, 64 + s) and one where it enters is (64 + s, k); a
//     reference corner inside the incident face is (64 + s', 64 + s). Lines
//     of a convex polygon meet once, so ids are unique within a manifold,
//     and they stay the same while the features touching stay the same.
//   edge contact: bit 31 set; bits 8-15 edge of A, bits 0-7 edge of B.
// Faces (at most 124) and loop sides (at most 64) fit these fields.
#include "d3/manifold_hull_sat.h"

#include <cmath>

#include "d3/hull_sat_queries.h"
#include "d3/polygon_clip.h"

namespace rwd::sim::d3 {
namespace {

// Face contacts win near-ties: they give up to four well-spread points and
// ids that persist, which is what keeps stacks still. B's face is used only
// when it separates more than A's by kFaceTolerance (as collide_boxes does,
// so a box and a box-shaped hull choose alike), and an edge only when it
// separates more than the best face by kEdgeTolerance plus
// kEdgeRelativeTolerance of the face separation's size: deep overlaps
// (fast impacts, large hulls) have larger rounding and more room for the
// edge and face depths to trade places from step to step, so the margin
// grows with them. At the small depths of resting contact the rule is
// collide_boxes' (1 mm); it is never weaker than it.
constexpr float kFaceTolerance = 0.0005f;        // metres
constexpr float kEdgeTolerance = 0.001f;         // metres
constexpr float kEdgeRelativeTolerance = 0.02f;  // of |face separation|
// Side planes are pushed out by this much before clipping, as collide_boxes
// does: equal hulls stacked flush have incident vertices exactly on the
// reference face's sides, and without the margin rounding would decide each
// step whether a vertex survives (keeping its id) or is replaced by clipped
// points with other ids.
constexpr float kClipTolerance = 0.001f;  // metres
// Reduction to four points: candidates within kDepthTie of the deepest
// count as equally deep, and spreads within kSpreadTie (relative) of the
// best as equally good; among equals the lowest feature id wins. Resting
// faces are flat to rounding, so "the deepest" would otherwise be decided by
// the last bit from one step to the next and the kept corners would flicker;
// ids are persistent, so this choice is too (and it does not depend on the
// order clipping produced the candidates in).
constexpr float kDepthTie = 0.0005f;  // metres
constexpr float kSpreadTie = 0.01f;
// Clipping a convex polygon by a plane adds at most one vertex: 64 incident
// vertices clipped by a 64-sided reference face end with at most 128.
// Rounding can make a nearly degenerate polygon gain more; clip_by_plane
// drops vertices past the capacity instead of writing beyond it.
constexpr int kMaxClip = 2 * static_cast<int>(kHullMaxVertices) + 2;
constexpr uint32_t kReferenceSide = 64;  // line label of reference side s: 64 + s

// x -> r x + t.
struct Transform {
  Mat3 r;
  Vec3 t;
};

Vec3 mul_transpose(const Mat3& m, Vec3 v) {
  return {dot(m.c0, v), dot(m.c1, v), dot(m.c2, v)};
}

// From the frame at (p_from, r_from) to the frame at (p_to, r_to), both
// world poses: r_to^T (r_from x + p_from - p_to). The centre offset is taken
// in world space first, so far from the origin only the offset rounds.
Transform relative(Vec3 p_to, const Mat3& r_to, Vec3 p_from, const Mat3& r_from) {
  return {{mul_transpose(r_to, r_from.c0), mul_transpose(r_to, r_from.c1),
           mul_transpose(r_to, r_from.c2)},
          mul_transpose(r_to, p_from - p_to)};
}

// The hull's vertices moved by xf, into out (vertex_count of them).
void move_vertices(const HullView& hull, const Transform& xf, Vec3* out) {
  for (uint32_t v = 0; v < hull.vertex_count; ++v) out[v] = xf.r * hull.vertices[v] + xf.t;
}

bool view_fits(const HullView& h) {
  return h.vertex_count > 0 && h.vertex_count <= kHullMaxVertices && h.face_count > 0 &&
         h.face_count <= kMaxFaces && h.edge_count <= kMaxEdges;
}

// A loop's length as the scratch can hold it (a valid hull's loops never
// exceed its vertex count).
uint32_t loop_count(const HullFace& f) {
  return f.count < kHullMaxVertices ? f.count : kHullMaxVertices;
}

// A vertex of the clipped polygon: position (reference hull's frame) and the
// labels of the polygon sides arriving at it and leaving it (see the
// feature-id notes at the top).
struct ClipVertex {
  Vec3 p;
  uint8_t in;
  uint8_t out;
};

// Keeps the part of `in` where dot(plane, x) <= offset; the plane is line
// `label`.
int clip_side(const ClipVertex* in, int count, Vec3 plane, float offset, uint8_t label,
              ClipVertex* out) {
  float dist[kMaxClip];
  for (int m = 0; m < count; ++m) dist[m] = dot(plane, in[m].p) - offset;
  return clip_polygon<kMaxClip>(
      in, dist, count, out,
      [label](const ClipVertex& p, const ClipVertex& q, float t, bool leaving) {
        ClipVertex x;
        x.p = p.p + (q.p - p.p) * t;
        // The side p -> q is p.out; leaving, the polygon continues along the
        // plane, entering it comes off the plane onto that side.
        x.in = leaving ? p.out : label;
        x.out = leaving ? label : p.out;
        return x;
      });
}

struct Candidate {
  Vec3 point;  // reference hull's frame, midway between the surfaces
  float separation;
  uint32_t id;
};

// Among candidates not yet kept, the one with the highest score; scores
// within `tie` of the highest count as equal and the lowest id among them
// wins (then the lower index). -1 when every candidate is kept.
int pick(const Candidate* c, const float* score, const bool* keep, int count, float tie) {
  float best = kLowestSeparation;
  bool any = false;
  for (int i = 0; i < count; ++i) {
    if (keep[i]) continue;
    if (!any || score[i] > best) best = score[i];
    any = true;
  }
  if (!any) return -1;
  const float cutoff = best - tie;
  int chosen = -1;
  for (int i = 0; i < count; ++i) {
    if (keep[i] || score[i] < cutoff) continue;
    if (chosen < 0 || c[i].id < c[chosen].id) chosen = i;
  }
  return chosen;
}

// Keeps four of `count` (> 4) candidates: the deepest, the farthest from
// it, the one spanning the largest area with those two, and the one
// spanning the largest area on the other side (or, when none is there, the
// next largest area on the same side). Near-ties go by feature id (pick).
void reduce_to_four(const Candidate* c, int count, Vec3 normal, bool* keep) {
  float score[kMaxClip];
  for (int i = 0; i < count; ++i) keep[i] = false;
  for (int i = 0; i < count; ++i) score[i] = -c[i].separation;
  const int i1 = pick(c, score, keep, count, kDepthTie);
  keep[i1] = true;
  float best = 0.0f;
  for (int i = 0; i < count; ++i) {
    score[i] = length_squared(c[i].point - c[i1].point);
    if (!keep[i] && score[i] > best) best = score[i];
  }
  const int i2 = pick(c, score, keep, count, kSpreadTie * best);
  keep[i2] = true;
  const Vec3 e = c[i2].point - c[i1].point;
  float area[kMaxClip];
  best = 0.0f;
  for (int i = 0; i < count; ++i) {
    area[i] = dot(normal, cross(e, c[i].point - c[i1].point));
    score[i] = std::fabs(area[i]);
    if (!keep[i] && score[i] > best) best = score[i];
  }
  const int i3 = pick(c, score, keep, count, kSpreadTie * best);
  keep[i3] = true;
  // Look on the other side of the first two points first.
  const float side = area[i3] >= 0.0f ? -1.0f : 1.0f;
  best = 0.0f;
  bool other_side = false;
  for (int i = 0; i < count; ++i) {
    score[i] = side * area[i];
    if (!keep[i] && score[i] > best) {
      best = score[i];
      other_side = true;
    }
  }
  if (!other_side) {
    for (int i = 0; i < count; ++i) {
      score[i] = std::fabs(area[i]);
      if (!keep[i] && score[i] > best) best = score[i];
    }
  }
  const int i4 = pick(c, score, keep, count, kSpreadTie * best);
  keep[i4] = true;
}

// Face contact on reference face `ref_face` of `ref`. `inc_vertices` are
// the incident hull's vertices in ref's frame, `ref_to_inc` turns a ref
// direction into inc's frame; (ref_position, ref_axes) is ref's world pose.
void face_contact(const HullView& ref, uint32_t ref_face, const HullView& inc,
                  const Vec3* inc_vertices, const Mat3& ref_to_inc, bool ref_is_b,
                  Vec3 ref_position, const Mat3& ref_axes, float speculative_m, Manifold& out) {
  const HullFace& rf = ref.faces[ref_face];
  const Vec3 n = rf.normal;

  // Incident face: the most anti-parallel to n (ties to the lower index),
  // compared in inc's own frame so its stored normals are used as they are,
  // among the faces that hold one of inc's deepest vertices along -n (within
  // kDepthTie). The most anti-parallel face of all need not hold the deepest
  // vertex (a hull standing on a corner next to a broad face turned nearly
  // down), and a clip of a face without it misses the point of contact
  // that matters most. A face resting flat holds the deepest vertices, so
  // resting contacts choose as before.
  float deepest = dot(n, inc_vertices[0]);
  for (uint32_t v = 1; v < inc.vertex_count; ++v) {
    const float d = dot(n, inc_vertices[v]);
    if (d < deepest) deepest = d;
  }
  const Vec3 n_inc = ref_to_inc * n;
  uint32_t inc_face = 0;
  float lowest = 0.0f;
  bool found = false;
  for (uint32_t f = 0; f < inc.face_count; ++f) {
    const HullFace& face = inc.faces[f];
    bool holds = false;
    for (uint32_t k = 0; k < loop_count(face) && !holds; ++k) {
      holds = dot(n, inc_vertices[inc.face_vertices[face.first + k]]) <= deepest + kDepthTie;
    }
    if (!holds) continue;
    const float d = dot(face.normal, n_inc);
    if (!found || d < lowest) {
      lowest = d;
      inc_face = f;
      found = true;
    }
  }

  ClipVertex a[kMaxClip];
  ClipVertex b[kMaxClip];
  const HullFace& inf = inc.faces[inc_face];
  const uint32_t inc_count = loop_count(inf);
  for (uint32_t k = 0; k < inc_count; ++k) {
    a[k].p = inc_vertices[inc.face_vertices[inf.first + k]];
    a[k].in = static_cast<uint8_t>(k == 0 ? inc_count - 1 : k - 1);
    a[k].out = static_cast<uint8_t>(k);
  }
  int count = static_cast<int>(inc_count);
  ClipVertex* src = a;
  ClipVertex* dst = b;
  const uint32_t ref_count = loop_count(rf);
  const uint8_t* loop = ref.face_vertices + rf.first;
  for (uint32_t s = 0; s < ref_count && count > 0; ++s) {
    const Vec3 p = ref.vertices[loop[s]];
    const Vec3 q = ref.vertices[loop[s + 1 == ref_count ? 0 : s + 1]];
    // The loop runs counter-clockwise about n, so the face lies to the left
    // of each side and (q - p) x n points out of it.
    const Vec3 side = normalize_or_zero(cross(q - p, n));
    const float offset = dot(side, p) + kClipTolerance;
    count = clip_side(src, count, side, offset, static_cast<uint8_t>(kReferenceSide + s), dst);
    ClipVertex* t = src;
    src = dst;
    dst = t;
  }

  Candidate cand[kMaxClip];
  int n_cand = 0;
  const uint32_t base_id = (ref_is_b ? 1u << 30 : 0u) | (ref_face << 23) | (inc_face << 16);
  for (int m = 0; m < count; ++m) {
    const float sep = dot(n, src[m].p) - rf.offset;
    if (sep > speculative_m) continue;
    cand[n_cand].point = src[m].p - n * (0.5f * sep);
    cand[n_cand].separation = sep;
    cand[n_cand].id = base_id | (static_cast<uint32_t>(src[m].in) << 7) | src[m].out;
    ++n_cand;
  }
  bool keep[kMaxClip];
  if (n_cand > static_cast<int>(kMaxManifoldPoints)) {
    reduce_to_four(cand, n_cand, n, keep);
  } else {
    for (int m = 0; m < n_cand; ++m) keep[m] = true;
  }
  const Vec3 world_n = ref_axes * n;
  out.normal = ref_is_b ? -world_n : world_n;
  out.point_count = 0;
  for (int m = 0; m < n_cand; ++m) {
    if (!keep[m]) continue;
    ManifoldPoint& mp = out.points[out.point_count++];
    mp.point = ref_position + ref_axes * cand[m].point;
    mp.separation = cand[m].separation;
    mp.feature_id = cand[m].id;
  }
}

float clampf(float v, float lo, float hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// One point midway between the closest points of A's edge and B's edge
// (B's vertices in A's frame), which are not parallel.
void edge_contact(const HullView& a, const HullView& b, const Vec3* b_vertices, const EdgeQuery& q,
                  Vec3 position_a, const Mat3& axes_a, Manifold& out) {
  const HullEdge& ea = a.edges[q.edge_a];
  const HullEdge& eb = b.edges[q.edge_b];
  const Vec3 pa = a.vertices[ea.v0];
  const Vec3 da = a.vertices[ea.v1] - pa;
  const Vec3 pb = b_vertices[eb.v0];
  const Vec3 db = b_vertices[eb.v1] - pb;
  // Closest points of the segments pa + s da and pb + t db, s, t in [0, 1]
  // (Ericson, Real-Time Collision Detection 5.1.9).
  const Vec3 r = pa - pb;
  const float aa = dot(da, da);
  const float bb = dot(db, db);
  const float ab = dot(da, db);
  const float ar = dot(da, r);
  const float br = dot(db, r);
  const float denom = aa * bb - ab * ab;  // > 0: parallel pairs are skipped
  float s = denom > 0.0f ? clampf((ab * br - ar * bb) / denom, 0.0f, 1.0f) : 0.0f;
  float t = (ab * s + br) / bb;
  if (t < 0.0f) {
    t = 0.0f;
    s = clampf(-ar / aa, 0.0f, 1.0f);
  } else if (t > 1.0f) {
    t = 1.0f;
    s = clampf((ab - ar) / aa, 0.0f, 1.0f);
  }
  const Vec3 mid = ((pa + da * s) + (pb + db * t)) * 0.5f;
  out.normal = axes_a * q.axis;
  out.point_count = 1;
  out.points[0].point = position_a + axes_a * mid;
  out.points[0].separation = q.separation;
  out.points[0].feature_id = 0x80000000u | (q.edge_a << 8) | q.edge_b;
}

// Vertex i of a box at (+-1, +-1, +-1) by bits 0-2 of i; face 2k is -k and
// 2k + 1 is +k. Each loop runs counter-clockwise about its face's outward
// normal.
constexpr uint8_t kBoxLoops[24] = {
    0, 4, 6, 2,  // -x
    1, 3, 7, 5,  // +x
    0, 1, 5, 4,  // -y
    2, 6, 7, 3,  // +y
    0, 2, 3, 1,  // -z
    4, 5, 7, 6,  // +z
};

struct BoxEdges {
  HullEdge e[12];
};

// Each edge once, as the loops give it: walking a loop from vertex p to q
// with p < q lists edge (p, q) with this face on its left; the face whose
// loop runs q -> p is on its right.
constexpr BoxEdges make_box_edges() {
  BoxEdges out{};
  int n = 0;
  for (int f = 0; f < 6; ++f) {
    for (int s = 0; s < 4; ++s) {
      const uint8_t p = kBoxLoops[4 * f + s];
      const uint8_t q = kBoxLoops[4 * f + (s + 1) % 4];
      if (p > q) continue;
      int right = 0;
      for (int g = 0; g < 6; ++g) {
        for (int k = 0; k < 4; ++k) {
          if (kBoxLoops[4 * g + k] == q && kBoxLoops[4 * g + (k + 1) % 4] == p) right = g;
        }
      }
      out.e[n].v0 = p;
      out.e[n].v1 = q;
      out.e[n].face_left = static_cast<uint8_t>(f);
      out.e[n].face_right = static_cast<uint8_t>(right);
      ++n;
    }
  }
  return out;
}

constexpr BoxEdges kBoxEdges = make_box_edges();

}  // namespace

HullView BoxHull::view() const {
  return {vertices, 8, faces, 6, kBoxLoops, kBoxEdges.e, 12};
}

BoxHull make_box_hull(Vec3 half_extents) {
  BoxHull box;
  for (uint32_t i = 0; i < 8; ++i) {
    box.vertices[i] = {(i & 1u) ? half_extents.x : -half_extents.x,
                       (i & 2u) ? half_extents.y : -half_extents.y,
                       (i & 4u) ? half_extents.z : -half_extents.z};
  }
  const float half[3] = {half_extents.x, half_extents.y, half_extents.z};
  for (uint32_t f = 0; f < 6; ++f) {
    const uint32_t axis = f / 2;
    const float sign = (f & 1u) ? 1.0f : -1.0f;
    Vec3 n;
    n.x = axis == 0 ? sign : 0.0f;
    n.y = axis == 1 ? sign : 0.0f;
    n.z = axis == 2 ? sign : 0.0f;
    box.faces[f].normal = n;
    box.faces[f].offset = half[axis];
    box.faces[f].first = static_cast<uint16_t>(4 * f);
    box.faces[f].count = 4;
  }
  return box;
}

void collide_hulls(const HullView& a, Vec3 position_a, const Mat3& axes_a, const HullView& b,
                   Vec3 position_b, const Mat3& axes_b, float speculative_m, Manifold& out) {
  out.point_count = 0;
  out.separating_axis = kNoSeparatingAxis;
  if (!view_fits(a) || !view_fits(b)) return;
  const Transform b_to_a = relative(position_a, axes_a, position_b, axes_b);
  Vec3 b_in_a[kHullMaxVertices];
  move_vertices(b, b_to_a, b_in_a);
  // Most pairs the broadphase hands over are apart, and one of A's faces
  // shows it: A's vertices in B's frame only once none has.
  const FaceQuery face_a = query_faces(a, b_in_a, b.vertex_count, speculative_m);
  if (face_a.separation > speculative_m) {
    out.separating_axis = static_cast<uint8_t>(face_a.face);
    return;
  }
  const Transform a_to_b = relative(position_b, axes_b, position_a, axes_a);
  Vec3 a_in_b[kHullMaxVertices];
  move_vertices(a, a_to_b, a_in_b);
  const FaceQuery face_b = query_faces(b, a_in_b, a.vertex_count, speculative_m);
  if (face_b.separation > speculative_m) {
    out.separating_axis = static_cast<uint8_t>(kHullFaceAxisB + face_b.face);
    return;
  }

  const bool use_b = face_b.separation > face_a.separation + kFaceTolerance;
  const float face_sep =
      face_a.separation > face_b.separation ? face_a.separation : face_b.separation;
  const float edge_threshold =
      face_sep + kEdgeTolerance + kEdgeRelativeTolerance * std::fabs(face_sep);
  // Below both the separation that ends the test and the one an edge
  // contact needs, every edge pair leads to the same face contact.
  const float floor = std::fmin(edge_threshold, speculative_m);

  Vec3 b_normals[kMaxFaces];
  for (uint32_t f = 0; f < b.face_count; ++f) b_normals[f] = b_to_a.r * b.faces[f].normal;
  const EdgeQuery edge = query_edges(a, b, b_in_a, b_normals, b_to_a.t, floor, speculative_m);
  if (edge.separation > speculative_m) return;
  if (edge.separation > edge_threshold) {
    edge_contact(a, b, b_in_a, edge, position_a, axes_a, out);
  } else if (use_b) {
    face_contact(b, face_b.face, a, a_in_b, b_to_a.r, true, position_b, axes_b, speculative_m, out);
  } else {
    face_contact(a, face_a.face, b, b_in_a, a_to_b.r, false, position_a, axes_a, speculative_m,
                 out);
  }
}

bool hull_axis_separates(const HullView& a, Vec3 position_a, const Mat3& axes_a, const HullView& b,
                         Vec3 position_b, const Mat3& axes_b, uint8_t axis, float speculative_m) {
  if (!view_fits(a) || !view_fits(b)) return false;
  // The face's hull, the other, and the other's vertices in the face's
  // frame, each computed as collide_hulls computes them.
  const bool of_a = axis < kHullFaceAxisB;
  const HullView& hull = of_a ? a : b;
  const HullView& other = of_a ? b : a;
  const uint32_t face = of_a ? axis : axis - kHullFaceAxisB;
  if (face >= hull.face_count) return false;
  const Transform to_hull = of_a ? relative(position_a, axes_a, position_b, axes_b)
                                 : relative(position_b, axes_b, position_a, axes_a);
  Vec3 in_hull[kHullMaxVertices];
  move_vertices(other, to_hull, in_hull);
  return face_separation(hull, face, in_hull, other.vertex_count) > speculative_m;
}

void collide_hulls(const Hull& a, Vec3 position_a, const Mat3& axes_a, const Hull& b,
                   Vec3 position_b, const Mat3& axes_b, float speculative_m, Manifold& out) {
  collide_hulls(hull_view(a), position_a, axes_a, hull_view(b), position_b, axes_b, speculative_m,
                out);
}

void collide_box_hull(Vec3 box_center, const Mat3& box_axes, Vec3 half_extents, const Hull& hull,
                      Vec3 hull_position, const Mat3& hull_axes, float speculative_m,
                      Manifold& out) {
  const BoxHull box = make_box_hull(half_extents);
  collide_hulls(box.view(), box_center, box_axes, hull_view(hull), hull_position, hull_axes,
                speculative_m, out);
}

}  // namespace rwd::sim::d3
