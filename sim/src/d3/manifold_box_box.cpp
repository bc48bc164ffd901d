// SPDX-License-Identifier: MIT
// Box-box manifold: separating-axis test over the 15 candidate axes (3 face
// normals of each box, 9 edge cross products), then either
//  - a face contact: the reference face is the face of the best face axis,
//    the incident face is the other box's face most anti-parallel to it; the
//    incident quad is clipped against the reference face's side planes
//    (polygon_clip.h) and points within the speculative distance are
//    kept, reduced to four when clipping leaves more; or
//  - an edge contact: one point between the closest points of the two edges.
// GJK/EPA was rejected for this pair: SAT is exact for boxes, cheaper, and
// gives the face features that make warm-start ids persistent.
#include <cmath>
#include <limits>

#include "d3/manifold.h"
#include "d3/polygon_clip.h"

namespace rwd::sim::d3 {
namespace {

// Face axes win near-ties: a face contact gives up to four well-spread
// points and a stable id, so an edge axis must be clearly better to be used,
// and box A's face is preferred over B's unless B's is clearly better (the
// tolerance makes the choice sticky instead of flickering between equals).
constexpr float kFaceTolerance = 0.0005f;  // metres
constexpr float kEdgeTolerance = 0.001f;   // metres
// Edge cross products shorter than this (sin of the angle between the edges)
// are parallel edges; their axis is covered by the face axes.
constexpr float kParallelSinSquared = 1e-6f;
// Side planes are pushed out by this much before clipping. Equal boxes
// stacked flush have incident corners exactly on the reference face's
// sides; without the margin, rounding decides each step whether a corner
// survives or is replaced by clipped points with other feature ids, which
// throws away warm starting and lets the stack creep.
constexpr float kClipTolerance = 0.001f;  // metres

struct BoxFrame {
  Vec3 center;
  Vec3 axis[3];
  float half[3];
};

BoxFrame make_frame(Vec3 center, const Mat3& m, Vec3 half) {
  return {center, {m.c0, m.c1, m.c2}, {half.x, half.y, half.z}};
}

// A vertex of the incident face in the reference face's frame: u and v
// along the reference face's two side axes, w along its normal, all from
// the reference box's centre. Clipping against the reference face's side
// planes is then clipping against |u| <= hu, |v| <= hv, one subtraction
// per vertex and plane instead of a dot product.
struct ClipVertex {
  float c[3];               // u, v, w
  uint8_t incident_edges;   // bit e: lies on incident edge e
  uint8_t reference_sides;  // bit s: lies on reference side plane s
};

constexpr int kMaxClip = 12;

// Keeps the part of `in` where sign * c[coord] <= limit (side plane `side`).
int clip_side(const ClipVertex* in, int count, int coord, float sign, float limit, int side,
              ClipVertex* out) {
  float dist[kMaxClip];
  for (int m = 0; m < count; ++m) dist[m] = sign * in[m].c[coord] - limit;
  return clip_polygon<kMaxClip>(
      in, dist, count, out, [side](const ClipVertex& p, const ClipVertex& q, float t, bool) {
        ClipVertex x;
        for (int k = 0; k < 3; ++k) x.c[k] = p.c[k] + (q.c[k] - p.c[k]) * t;
        x.incident_edges = static_cast<uint8_t>(p.incident_edges & q.incident_edges);
        x.reference_sides =
            static_cast<uint8_t>((p.reference_sides & q.reference_sides) | (1u << side));
        return x;
      });
}

struct Candidate {
  Vec3 point;
  float separation;
  uint32_t id;
};

// Picks four of `count` (> 4) candidates: the deepest, the farthest from it,
// then the two that span the largest area on either side of that segment.
// Strict comparisons make ties go to the earlier candidate.
void reduce_to_four(const Candidate* c, int count, Vec3 normal, bool* keep) {
  for (int i = 0; i < count; ++i) keep[i] = false;
  int i1 = 0;
  for (int i = 1; i < count; ++i) {
    if (c[i].separation < c[i1].separation) i1 = i;
  }
  keep[i1] = true;
  int i2 = -1;
  float best = -1.0f;
  for (int i = 0; i < count; ++i) {
    if (keep[i]) continue;
    float d = length_squared(c[i].point - c[i1].point);
    if (d > best) {
      best = d;
      i2 = i;
    }
  }
  keep[i2] = true;
  Vec3 e = c[i2].point - c[i1].point;
  auto area = [&](int i) { return dot(normal, cross(e, c[i].point - c[i1].point)); };
  int i3 = -1;
  best = -1.0f;
  for (int i = 0; i < count; ++i) {
    if (keep[i]) continue;
    float a = std::fabs(area(i));
    if (a > best) {
      best = a;
      i3 = i;
    }
  }
  keep[i3] = true;
  float side = area(i3) >= 0.0f ? -1.0f : 1.0f;  // look on the other side first
  int i4 = -1;
  best = 0.0f;
  for (int i = 0; i < count; ++i) {
    if (keep[i]) continue;
    float a = side * area(i);
    if (a > best) {
      best = a;
      i4 = i;
    }
  }
  if (i4 < 0) {  // nothing on the other side: take the next largest area
    best = -1.0f;
    for (int i = 0; i < count; ++i) {
      if (keep[i]) continue;
      float a = std::fabs(area(i));
      if (a > best) {
        best = a;
        i4 = i;
      }
    }
  }
  keep[i4] = true;
}

void face_contact(const BoxFrame& ref, const BoxFrame& inc, int ref_axis, bool ref_is_b,
                  float speculative_m, Manifold& out) {
  Vec3 to_inc = inc.center - ref.center;
  float ref_sign = dot(to_inc, ref.axis[ref_axis]) >= 0.0f ? 1.0f : -1.0f;
  Vec3 n = ref.axis[ref_axis] * ref_sign;
  uint32_t ref_face = static_cast<uint32_t>(ref_axis) * 2u + (ref_sign > 0.0f ? 1u : 0u);

  // Incident face: most anti-parallel to n (ties to the lower axis).
  int k = 0;
  float best = -1.0f;
  for (int m = 0; m < 3; ++m) {
    float a = std::fabs(dot(inc.axis[m], n));
    if (a > best) {
      best = a;
      k = m;
    }
  }
  float inc_sign = dot(inc.axis[k], n) > 0.0f ? -1.0f : 1.0f;
  uint32_t inc_face = static_cast<uint32_t>(k) * 2u + (inc_sign > 0.0f ? 1u : 0u);
  int u = (k + 1) % 3;
  int v = (k + 2) % 3;
  const int j = (ref_axis + 1) % 3;
  const int l = (ref_axis + 2) % 3;
  // The incident face's centre and half edges in the reference frame.
  const Vec3 frame[3] = {ref.axis[j], ref.axis[l], n};
  const Vec3 fc = inc.center + inc.axis[k] * (inc_sign * inc.half[k]) - ref.center;
  const Vec3 du = inc.axis[u] * inc.half[u];
  const Vec3 dv = inc.axis[v] * inc.half[v];
  float fc_r[3];
  float du_r[3];
  float dv_r[3];
  for (int c = 0; c < 3; ++c) {
    fc_r[c] = dot(fc, frame[c]);
    du_r[c] = dot(du, frame[c]);
    dv_r[c] = dot(dv, frame[c]);
  }
  ClipVertex a[kMaxClip];
  ClipVertex b[kMaxClip];
  const float su[4] = {1.0f, -1.0f, -1.0f, 1.0f};
  const float sv[4] = {1.0f, 1.0f, -1.0f, -1.0f};
  for (int m = 0; m < 4; ++m) {
    for (int c = 0; c < 3; ++c) a[m].c[c] = fc_r[c] + du_r[c] * su[m] + dv_r[c] * sv[m];
    // Vertex m starts edge m and ends edge m-1.
    a[m].incident_edges = static_cast<uint8_t>((1u << m) | (1u << ((m + 3) & 3)));
    a[m].reference_sides = 0;
  }
  int count = 4;
  // Side planes in order: +u, -u, +v, -v.
  const int coord[4] = {0, 0, 1, 1};
  const float sign[4] = {1.0f, -1.0f, 1.0f, -1.0f};
  const float half[4] = {ref.half[j], ref.half[j], ref.half[l], ref.half[l]};
  ClipVertex* src = a;
  ClipVertex* dst = b;
  for (int s = 0; s < 4 && count > 0; ++s) {
    count = clip_side(src, count, coord[s], sign[s], half[s] + kClipTolerance, s, dst);
    ClipVertex* t = src;
    src = dst;
    dst = t;
  }

  Candidate cand[kMaxClip];
  int n_cand = 0;
  const float face_offset = ref.half[ref_axis];
  uint32_t base_id = (ref_is_b ? 1u << 16 : 0u) | (ref_face << 12) | (inc_face << 8);
  for (int m = 0; m < count; ++m) {
    const float sep = src[m].c[2] - face_offset;
    if (sep > speculative_m) continue;
    // Midway between the incident point and the reference face.
    cand[n_cand].point = ref.center + frame[0] * src[m].c[0] + frame[1] * src[m].c[1] +
                         n * (src[m].c[2] - 0.5f * sep);
    cand[n_cand].separation = sep;
    cand[n_cand].id =
        base_id | (static_cast<uint32_t>(src[m].reference_sides) << 4) | src[m].incident_edges;
    ++n_cand;
  }
  bool keep[kMaxClip];
  if (n_cand > static_cast<int>(kMaxManifoldPoints)) {
    reduce_to_four(cand, n_cand, n, keep);
  } else {
    for (int m = 0; m < n_cand; ++m) keep[m] = true;
  }
  out.normal = ref_is_b ? -n : n;
  out.point_count = 0;
  for (int m = 0; m < n_cand; ++m) {
    if (!keep[m]) continue;
    ManifoldPoint& mp = out.points[out.point_count++];
    mp.point = cand[m].point;
    mp.separation = cand[m].separation;
    mp.feature_id = cand[m].id;
  }
}

float clampf(float v, float lo, float hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

void edge_contact(const BoxFrame& a, const BoxFrame& b, int ia, int ib, Vec3 l, float separation,
                  Manifold& out) {
  // The edge of A farthest along l and the edge of B farthest along -l.
  Vec3 pa = a.center;
  Vec3 pb = b.center;
  uint32_t code_a = 0;
  uint32_t code_b = 0;
  uint32_t bit = 0;
  for (int m = 0; m < 3; ++m) {
    if (m == ia) continue;
    bool positive = dot(a.axis[m], l) >= 0.0f;
    pa += a.axis[m] * (positive ? a.half[m] : -a.half[m]);
    code_a |= (positive ? 1u : 0u) << bit++;
  }
  bit = 0;
  for (int m = 0; m < 3; ++m) {
    if (m == ib) continue;
    bool positive = dot(b.axis[m], l) < 0.0f;
    pb += b.axis[m] * (positive ? b.half[m] : -b.half[m]);
    code_b |= (positive ? 1u : 0u) << bit++;
  }
  Vec3 da = a.axis[ia];
  Vec3 db = b.axis[ib];
  // Closest points of the lines pa + s da and pb + t db, clamped to the edges.
  Vec3 w = pa - pb;
  float bb = dot(da, db);
  float aw = dot(da, w);
  float bw = dot(db, w);
  float denom = 1.0f - bb * bb;  // > 0: parallel edges never reach here
  float s = denom > 1e-9f ? (bb * bw - aw) / denom : 0.0f;
  s = clampf(s, -a.half[ia], a.half[ia]);
  float t = clampf(bw + s * bb, -b.half[ib], b.half[ib]);
  s = clampf(t * bb - aw, -a.half[ia], a.half[ia]);
  Vec3 qa = pa + da * s;
  Vec3 qb = pb + db * t;
  out.normal = l;
  out.point_count = 1;
  out.points[0].point = (qa + qb) * 0.5f;
  out.points[0].separation = separation;
  out.points[0].feature_id = 0x80000000u | ((static_cast<uint32_t>(ia) * 4u + code_a) << 8) |
                             (static_cast<uint32_t>(ib) * 4u + code_b);
}

// The separations along the 15 axes, written once for the full test and
// the single-axis retest (box_axis_separates), so both give the same bits.
// r_ij = a_i . b_j, ta and tb the centre offset in A's and B's frames.
inline float face_a_separation(float ta_i, float half_a_i, const float* half_b, float r0, float r1,
                               float r2) {
  const float rb = half_b[0] * r0 + half_b[1] * r1 + half_b[2] * r2;
  return std::fabs(ta_i) - half_a_i - rb;
}
inline float face_b_separation(float tb_j, float half_b_j, const float* half_a, float r0, float r1,
                               float r2) {
  const float ra = half_a[0] * r0 + half_a[1] * r1 + half_a[2] * r2;
  return std::fabs(tb_j) - ra - half_b_j;
}
// The projection along a_i x b_j (not yet divided by its length) and the
// sign of the offset along it; abs_* are |r| of the entries named.
inline float edge_projection(const BoxFrame& a, const BoxFrame& b, int i, int j,
                             const float (&abs_r)[3][3], const float (&r)[3][3],
                             const float (&ta)[3], float& dl) {
  const int i1 = (i + 1) % 3;
  const int i2 = (i + 2) % 3;
  const int j1 = (j + 1) % 3;
  const int j2 = (j + 2) % 3;
  const float ra = a.half[i1] * abs_r[i2][j] + a.half[i2] * abs_r[i1][j];
  const float rb = b.half[j1] * abs_r[i][j2] + b.half[j2] * abs_r[i][j1];
  dl = ta[i2] * r[i1][j] - ta[i1] * r[i2][j];
  return std::fabs(dl) - ra - rb;
}

// Separating axes as Manifold::separating_axis numbers them.
constexpr uint8_t kFaceAxisA = 0;  // + i
constexpr uint8_t kFaceAxisB = 3;  // + j
constexpr uint8_t kEdgeAxis = 6;   // + 3 i + j

}  // namespace

void collide_boxes(const BoxPose& pose_a, const BoxPose& pose_b, float speculative_m,
                   Manifold& out) {
  collide_boxes(pose_a.center, mat3_from_quat(pose_a.rotation), pose_a.half_extents, pose_b.center,
                mat3_from_quat(pose_b.rotation), pose_b.half_extents, speculative_m, out);
}

void collide_boxes(Vec3 center_a, const Mat3& axes_a, Vec3 half_a, Vec3 center_b,
                   const Mat3& axes_b, Vec3 half_b, float speculative_m, Manifold& out) {
  out.point_count = 0;
  out.separating_axis = kNoSeparatingAxis;
  const BoxFrame a = make_frame(center_a, axes_a, half_a);
  const BoxFrame b = make_frame(center_b, axes_b, half_b);
  Vec3 d = b.center - a.center;
  constexpr float kLowest = -std::numeric_limits<float>::max();

  // B's axes in A's frame (r[i][j] = a_i . b_j) and the centre offset in
  // both frames: every one of the 15 projections is then a few products of
  // these (Gottschalk's OBB test) instead of dot products in world space.
  float r[3][3];
  float abs_r[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      r[i][j] = dot(a.axis[i], b.axis[j]);
      abs_r[i][j] = std::fabs(r[i][j]);
    }
  }
  const float ta[3] = {dot(d, a.axis[0]), dot(d, a.axis[1]), dot(d, a.axis[2])};
  const float tb[3] = {dot(d, b.axis[0]), dot(d, b.axis[1]), dot(d, b.axis[2])};

  float best_a = kLowest;
  int face_a = 0;
  for (int i = 0; i < 3; ++i) {
    const float sep =
        face_a_separation(ta[i], a.half[i], b.half, abs_r[i][0], abs_r[i][1], abs_r[i][2]);
    if (sep > speculative_m) {
      out.separating_axis = static_cast<uint8_t>(kFaceAxisA + i);
      return;
    }
    if (sep > best_a) {
      best_a = sep;
      face_a = i;
    }
  }
  float best_b = kLowest;
  int face_b = 0;
  for (int j = 0; j < 3; ++j) {
    const float sep =
        face_b_separation(tb[j], b.half[j], a.half, abs_r[0][j], abs_r[1][j], abs_r[2][j]);
    if (sep > speculative_m) {
      out.separating_axis = static_cast<uint8_t>(kFaceAxisB + j);
      return;
    }
    if (sep > best_b) {
      best_b = sep;
      face_b = j;
    }
  }
  bool use_b = best_b > best_a + kFaceTolerance;
  float best_face = use_b ? best_b : best_a;
  // An edge axis is used only if it separates more than the best face axis
  // by kEdgeTolerance. Its distance is the projection along the
  // unnormalized axis divided by |a_i x b_j| = sqrt(1 - r_ij^2) <= 1, which
  // can only make a negative projection more negative: an axis whose
  // projection is negative and already within that threshold can neither
  // win nor separate, and its square root and division are skipped.
  const float edge_threshold = best_face + kEdgeTolerance;
  float best_edge = kLowest;
  int edge_a = 0;
  int edge_b = 0;
  float edge_sign = 1.0f;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const float len_sq = 1.0f - r[i][j] * r[i][j];
      if (len_sq < kParallelSinSquared) continue;
      float dl = 0.0f;
      const float projection = edge_projection(a, b, i, j, abs_r, r, ta, dl);
      if (projection < 0.0f && projection <= edge_threshold) continue;
      float sep = projection / std::sqrt(len_sq);
      if (sep > speculative_m) {
        out.separating_axis = static_cast<uint8_t>(kEdgeAxis + 3 * i + j);
        return;
      }
      if (sep > best_edge) {
        best_edge = sep;
        edge_a = i;
        edge_b = j;
        edge_sign = dl >= 0.0f ? 1.0f : -1.0f;
      }
    }
  }

  if (best_edge > best_face + kEdgeTolerance) {
    const Vec3 l = cross(a.axis[edge_a], b.axis[edge_b]);
    const Vec3 edge_axis = l * (edge_sign / std::sqrt(length_squared(l)));
    edge_contact(a, b, edge_a, edge_b, edge_axis, best_edge, out);
  } else if (use_b) {
    face_contact(b, a, face_b, true, speculative_m, out);
  } else {
    face_contact(a, b, face_a, false, speculative_m, out);
  }
}

bool box_axis_separates(Vec3 center_a, const Mat3& axes_a, Vec3 half_a, Vec3 center_b,
                        const Mat3& axes_b, Vec3 half_b, uint8_t axis, float speculative_m) {
  const BoxFrame a = make_frame(center_a, axes_a, half_a);
  const BoxFrame b = make_frame(center_b, axes_b, half_b);
  const Vec3 d = b.center - a.center;
  // Only the entries of r, |r|, ta and tb the axis reads, each computed as
  // collide_boxes computes it.
  float r[3][3] = {};
  float abs_r[3][3] = {};
  float ta[3] = {};
  const auto entry = [&](int i, int j) {
    r[i][j] = dot(a.axis[i], b.axis[j]);
    abs_r[i][j] = std::fabs(r[i][j]);
  };
  if (axis < kFaceAxisB) {
    const int i = axis - kFaceAxisA;
    for (int j = 0; j < 3; ++j) entry(i, j);
    return face_a_separation(dot(d, a.axis[i]), a.half[i], b.half, abs_r[i][0], abs_r[i][1],
                             abs_r[i][2]) > speculative_m;
  }
  if (axis < kEdgeAxis) {
    const int j = axis - kFaceAxisB;
    for (int i = 0; i < 3; ++i) entry(i, j);
    return face_b_separation(dot(d, b.axis[j]), b.half[j], a.half, abs_r[0][j], abs_r[1][j],
                             abs_r[2][j]) > speculative_m;
  }
  if (axis >= kEdgeAxis + 9) return false;
  const int i = (axis - kEdgeAxis) / 3;
  const int j = (axis - kEdgeAxis) % 3;
  const int i1 = (i + 1) % 3;
  const int i2 = (i + 2) % 3;
  entry(i, j);
  entry(i1, j);
  entry(i2, j);
  entry(i, (j + 1) % 3);
  entry(i, (j + 2) % 3);
  ta[i1] = dot(d, a.axis[i1]);
  ta[i2] = dot(d, a.axis[i2]);
  const float len_sq = 1.0f - r[i][j] * r[i][j];
  if (len_sq < kParallelSinSquared) return false;
  float dl = 0.0f;
  const float projection = edge_projection(a, b, i, j, abs_r, r, ta, dl);
  // A separating projection is positive, so collide_boxes never skips it.
  if (!(projection > 0.0f)) return false;
  return projection / std::sqrt(len_sq) > speculative_m;
}

}  // namespace rwd::sim::d3
