// SPDX-License-Identifier: MIT
// Reduction of per-triangle contacts to one manifold, and the sweep
// against triangles. Conventions and limits: manifold_triangles.h.
#include <algorithm>
#include <cmath>
#include <limits>

#include "d3/manifold_triangles.h"

namespace rwd::sim::d3 {
namespace {

// A point closer than this to the points chosen so far (to the first, or
// to the line or the triangle through them) adds no support (metres).
constexpr float kMinSpread = 1e-3f;
constexpr uint32_t kCodeMask = (1u << kTriangleFeatureShift) - 1;
constexpr uint32_t kFaceCode = 30;  // as manifold_triangle_contact.cpp
// Beyond kMaxContactTriangles, contacts whose normals are this close
// (cosine) merge.
constexpr float kMergeCos = 0.9999f;

// Whether contact a is deeper than b (ties to the lower triangle id).
bool deeper(const TriangleContact& a, const TriangleContact& b) {
  return a.separation < b.separation || (a.separation == b.separation && a.id < b.id);
}

// Whether hit (fraction, id) comes before the best so far.
bool earlier(float fraction, uint32_t id, const TriangleCastOutput& best) {
  return !best.hit || fraction < best.fraction || (fraction == best.fraction && id < best.id);
}

// Joins contact c to m (nearly the same normal). When the points are more
// than a contact holds, m keeps the deepest and the extreme point along
// each of eight directions in its plane (ties to the lower feature id):
// each slot is a maximum over everything merged so far, so a corner of the
// union survives however the triangles were grouped.
void merge_into(TriangleContact& m, const TriangleContact& c) {
  TrianglePoint pts[2 * kMaxTrianglePoints];
  uint32_t n = 0;
  for (uint32_t k = 0; k < m.count; ++k) pts[n++] = m.points[k];
  for (uint32_t k = 0; k < c.count; ++k) pts[n++] = c.points[k];
  if (deeper(c, m)) {
    m.separation = c.separation;
    m.id = c.id;
  }
  if (n <= kMaxTrianglePoints) {
    for (uint32_t k = m.count; k < n; ++k) m.points[k] = pts[k];
    m.count = n;
    return;
  }
  // Witness-point stand-ins (code 30) give way to real points.
  bool real = false;
  for (uint32_t k = 0; k < n; ++k) real = real || (pts[k].feature_id & kCodeMask) != kFaceCode;
  if (real) {
    uint32_t r = 0;
    for (uint32_t k = 0; k < n; ++k) {
      if ((pts[k].feature_id & kCodeMask) != kFaceCode) pts[r++] = pts[k];
    }
    n = r;
  }
  Vec3 t1;
  Vec3 t2;
  tangent_basis(m.normal, t1, t2);
  const Vec3 dirs[8] = {t1, -t1, t2, -t2, t1 + t2, -t1 - t2, t1 - t2, t2 - t1};
  auto id_before = [&](uint32_t a, uint32_t b) { return pts[a].feature_id < pts[b].feature_id; };
  uint32_t keep[9];
  keep[0] = 0;
  for (uint32_t k = 1; k < n; ++k) {
    const float a = pts[k].separation;
    const float b = pts[keep[0]].separation;
    if (a < b || (a == b && id_before(k, keep[0]))) keep[0] = k;
  }
  for (uint32_t d = 0; d < 8; ++d) {
    uint32_t best = 0;
    float best_dot = dot(pts[0].point, dirs[d]);
    for (uint32_t k = 1; k < n; ++k) {
      const float v = dot(pts[k].point, dirs[d]);
      if (v > best_dot || (v == best_dot && id_before(k, best))) {
        best_dot = v;
        best = k;
      }
    }
    keep[d + 1] = best;
  }
  m.count = 0;
  for (uint32_t s = 0; s < 9; ++s) {
    bool seen = false;
    for (uint32_t r = 0; r < s; ++r) seen = seen || keep[r] == keep[s];
    if (!seen) m.points[m.count++] = pts[keep[s]];
  }
}

}  // namespace

uint32_t reduce_triangle_points(const TrianglePoint* points, uint32_t count, Vec3 normal,
                                uint32_t chosen[4]) {
  if (count == 0) return 0;
  // Every choice below breaks ties by feature id and then by position in
  // the input; ids are unique across triangles, so the result does not
  // depend on the order triangles arrived in.
  auto before = [&](uint32_t a, uint32_t b) {
    return points[a].feature_id < points[b].feature_id ||
           (points[a].feature_id == points[b].feature_id && a < b);
  };
  // The centroid, summed in id order so its rounding is order-free too.
  uint32_t order[kMaxContactTriangles * kMaxTrianglePoints];
  const uint32_t n = count < kMaxContactTriangles * kMaxTrianglePoints
                         ? count
                         : kMaxContactTriangles * kMaxTrianglePoints;
  for (uint32_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order, order + n, before);
  Vec3 centroid;
  float deepest = points[order[0]].separation;
  for (uint32_t k = 0; k < n; ++k) {
    centroid += points[order[k]].point;
    deepest = std::fmin(deepest, points[order[k]].separation);
  }
  centroid = centroid * (1.0f / static_cast<float>(n));
  // In-plane offset of q from p.
  auto planar = [&](Vec3 p, Vec3 q) {
    const Vec3 d = q - p;
    return d - normal * dot(d, normal);
  };
  // Picks the point with the greatest score (ties to the earlier in id
  // order); returns false when none scores above `floor`.
  auto pick = [&](auto&& score, float floor, uint32_t& out) {
    bool found = false;
    float best = floor;
    for (uint32_t k = 0; k < n; ++k) {
      const float s = score(order[k]);
      if (s > best) {
        best = s;
        out = order[k];
        found = true;
      }
    }
    return found;
  };
  // Points that touch (separation <= 0) hold the body up; speculative
  // ones only catch it as it comes down. Choices 2 to 4 are made among the
  // touching points first and fall back to every point only when none of
  // those spreads the patch enough. Chosen by spread alone, a box tilted
  // across a terrain fold kept its two lifted corners and only two of the
  // three points it stood on: resting on a line, it rocked about it, the
  // deepest of the near-tied supports changing the line each way, and
  // never came to rest.
  auto pick_touching_first = [&](auto&& score, float floor, uint32_t& out) {
    const auto touching = [&](uint32_t i) {
      return points[i].separation <= 0.0f ? score(i) : -std::numeric_limits<float>::infinity();
    };
    return pick(touching, floor, out) || pick(score, floor, out);
  };
  uint32_t c = 0;
  // 1. The deepest; near-ties to the one farthest from the centroid (a
  //    corner of the patch rather than a point inside it).
  pick(
      [&](uint32_t i) {
        return points[i].separation <= deepest + kDepthTie
                   ? length_squared(planar(centroid, points[i].point))
                   : -1.0f;
      },
      -0.5f, chosen[c]);
  const Vec3 p0 = points[chosen[c++]].point;
  // 2. The farthest from it.
  if (!pick_touching_first([&](uint32_t i) { return length_squared(planar(p0, points[i].point)); },
                           kMinSpread * kMinSpread, chosen[c])) {
    return c;
  }
  const Vec3 p1 = points[chosen[c++]].point;
  // 3. The largest triangle with those two (either side of their line).
  auto area = [&](Vec3 a, Vec3 b, Vec3 q) { return dot(cross(b - a, q - a), normal); };
  // Twice the area over the base: the distance from the line times |p1 - p0|.
  const float base = length(planar(p0, p1));
  if (!pick_touching_first([&](uint32_t i) { return std::fabs(area(p0, p1, points[i].point)); },
                           kMinSpread * base, chosen[c])) {
    return c;
  }
  const Vec3 p2 = points[chosen[c++]].point;
  // 4. The one that adds the most area: outside one of the triangle's
  //    edges (signs relative to the triangle's winding).
  const float wind = area(p0, p1, p2) > 0.0f ? 1.0f : -1.0f;
  auto added = [&](uint32_t i) {
    const Vec3 q = points[i].point;
    const float a01 = -wind * area(p0, p1, q);
    const float a12 = -wind * area(p1, p2, q);
    const float a20 = -wind * area(p2, p0, q);
    return std::fmax(a01, std::fmax(a12, a20));
  };
  if (pick_touching_first(added, kMinSpread * base, chosen[c])) ++c;
  return c;
}

TriangleManifoldBuilder::TriangleManifoldBuilder(const ConvexProxy& shape, bool one_sided,
                                                 float speculative_m, const Vec3* box_half)
    : core_(make_shape_core(shape, box_half)),
      one_sided_(one_sided),
      speculative_m_(speculative_m) {}

void TriangleManifoldBuilder::add(const TriangleRef& tri) {
  TriangleContact c;
  if (!collide_convex_triangle(core_, tri, one_sided_, speculative_m_, c)) return;
  if (count_ < kMaxContactTriangles) {
    contacts_[count_++] = c;
    return;
  }
  // Full. A contact with (nearly) the same normal as a stored one joins
  // it (merge_into), so a large shape on a finely split floor keeps the
  // corners of its whole patch. Otherwise the new contact replaces the
  // shallowest if it is deeper.
  for (uint32_t i = 0; i < count_; ++i) {
    if (dot(contacts_[i].normal, c.normal) >= kMergeCos) {
      merge_into(contacts_[i], c);
      return;
    }
  }
  uint32_t worst = 0;
  for (uint32_t i = 1; i < count_; ++i) {
    if (deeper(contacts_[worst], contacts_[i])) worst = i;
  }
  if (deeper(c, contacts_[worst])) contacts_[worst] = c;
}

void TriangleManifoldBuilder::finish(Manifold& out) const {
  out.point_count = 0;
  out.separating_axis = kNoSeparatingAxis;
  out.normal = Vec3{};
  if (count_ == 0) return;
  uint32_t deepest = 0;
  for (uint32_t i = 1; i < count_; ++i) {
    if (deeper(contacts_[i], contacts_[deepest])) deepest = i;
  }
  // A body resting across a fold (a ridge or a valley of the terrain) is
  // held by both faces about equally; taking either face's normal alone
  // would flip from one to the other tick by tick and rock it. So the
  // normal blends every contact within kBlendCos of the deepest's, each
  // weighted by how far it reaches within kSupportBand of the deepest
  // (a weight that grows continuously from zero, so the normal does not
  // jump as a contact comes in); on flat ground it is the face normal.
  const TriangleContact& first = contacts_[deepest];
  // Summed in ascending triangle id, so the normal does not depend on the
  // order the triangles arrived in.
  uint32_t by_id[kMaxContactTriangles];
  for (uint32_t i = 0; i < count_; ++i) {
    uint32_t k = i;
    while (k > 0 && contacts_[by_id[k - 1]].id > contacts_[i].id) {
      by_id[k] = by_id[k - 1];
      --k;
    }
    by_id[k] = i;
  }
  Vec3 sum;
  bool one_normal = true;  // then the face's own normal, bit for bit
  for (uint32_t j = 0; j < count_; ++j) {
    const TriangleContact& c = contacts_[by_id[j]];
    if (!(dot(c.normal, first.normal) >= kBlendCos)) continue;
    const float weight = first.separation + kSupportBand - c.separation;
    if (!(weight > 0.0f)) continue;
    // Normals within a hair of the deepest's are taken as it (rounding
    // must not tilt a body resting on a flat floor).
    const bool same = dot(c.normal, first.normal) >= kFaceSnapCos;
    sum += (same ? first.normal : c.normal) * weight;
    one_normal = one_normal && same;
  }
  const Vec3 blended = normalize_or_zero(sum);
  const Vec3 normal = one_normal || blended == Vec3{} ? first.normal : blended;
  TrianglePoint pts[kMaxContactTriangles * kMaxTrianglePoints];
  uint32_t n = 0;
  for (uint32_t i = 0; i < count_; ++i) {
    const TriangleContact& c = contacts_[i];
    const float cos = dot(c.normal, normal);
    if (!(cos >= kBlendCos)) continue;
    for (uint32_t k = 0; k < c.count; ++k) {
      // The witness points are separation * c.normal apart: their gap
      // along the chosen normal.
      const float sep = c.points[k].separation * cos;
      if (!(sep <= speculative_m_)) continue;
      pts[n++] = {c.points[k].point, sep, c.points[k].feature_id};
    }
  }
  // Points of face contacts whose outline missed their triangle (code 30,
  // mostly inactive edges: the neighbour across the edge has the real
  // contact) only stand in when no other point does.
  bool real = false;
  for (uint32_t i = 0; i < n; ++i) real = real || (pts[i].feature_id & kCodeMask) != kFaceCode;
  if (real) {
    uint32_t k = 0;
    for (uint32_t i = 0; i < n; ++i) {
      if ((pts[i].feature_id & kCodeMask) != kFaceCode) pts[k++] = pts[i];
    }
    n = k;
  }
  uint32_t chosen[4];
  const uint32_t m = reduce_triangle_points(pts, n, normal, chosen);
  out.normal = normal;
  for (uint32_t i = 0; i < m; ++i) {
    ManifoldPoint& mp = out.points[i];
    mp.point = pts[chosen[i]].point;
    mp.anchor_a = Vec3{};
    mp.anchor_b = Vec3{};
    mp.separation = pts[chosen[i]].separation;
    mp.feature_id = pts[chosen[i]].feature_id;
  }
  out.point_count = m;
}

void collide_convex_triangles(const ConvexProxy& shape, std::span<const TriangleRef> triangles,
                              bool one_sided, float speculative_m, Manifold& out,
                              const Vec3* box_half) {
  TriangleManifoldBuilder builder(shape, one_sided, speculative_m, box_half);
  for (const TriangleRef& t : triangles) builder.add(t);
  builder.finish(out);
}

TriangleCaster::TriangleCaster(const ConvexProxy& swept, Vec3 translation, bool one_sided,
                               float max_fraction)
    : swept_(&swept),
      translation_(translation),
      centroid_(make_shape_core(swept).centroid),
      one_sided_(one_sided),
      max_fraction_(max_fraction) {}

void TriangleCaster::add(const TriangleRef& tri) {
  const bool front = dot(centroid_ - tri.p[0], tri.normal) >= 0.0f;
  if (one_sided_ && !front) return;
  ConvexProxy tri_proxy;
  tri_proxy.points = tri.p;
  tri_proxy.count = 3;
  // Sweeps only as far as the best hit so far: shape_cast's steps do not
  // depend on the limit, so a hit found is the same either way, and one at
  // exactly the best fraction still comes back for the id tie.
  const float reach = best_.hit ? best_.fraction : max_fraction_;
  const ShapeCastOutput c = shape_cast(tri_proxy, *swept_, translation_, reach);
  if (!c.hit || !earlier(c.fraction, tri.id, best_)) return;
  const Vec3 side = front ? tri.normal : -tri.normal;
  bool replaced = false;
  uint32_t code = 0;
  Vec3 normal = c.normal;
  if (!(dot(normal, side) >= kFaceSnapCos)) {
    normal = triangle_detail::fix_internal_edge(tri, side, normal, replaced, code);
  }
  best_.hit = true;
  best_.initially_overlapping = c.initially_overlapping;
  best_.fraction = c.fraction;
  best_.point = c.point;
  best_.normal = normal;
  best_.id = tri.id;
}

TriangleCastOutput shape_cast_triangles(const ConvexProxy& swept, Vec3 translation,
                                        std::span<const TriangleRef> triangles, bool one_sided,
                                        float max_fraction) {
  TriangleCaster caster(swept, translation, one_sided, max_fraction);
  for (const TriangleRef& t : triangles) caster.add(t);
  return caster.result();
}

}  // namespace rwd::sim::d3
