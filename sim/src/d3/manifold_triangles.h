// SPDX-License-Identifier: MIT
#pragma once
// A convex shape against static triangles (a TriangleMesh or a HeightField
// queried for the triangles near the shape): one contact manifold, and the
// earliest hit of a sweep.
//
// Frame: everything is in the triangle source's local frame. The caller
// gives the shape's proxy a pose in that frame (the shape's world pose
// mapped by the inverse of the source's) and maps the results back.
//
// Normal: from the triangles (shape A) to the convex shape (shape B), so a
// shape resting on an upward-facing floor gets (0, 1, 0). Separation is
// negative when overlapping and each point lies midway between the
// surfaces, as in manifold.h; anchors are left zero (the caller fills them).
//
// Per triangle (manifold_triangle_contact.cpp): a box by separating axes
// (box_triangle.h); other shapes by GJK between the triangle and the
// shape's core when they are apart (closed form for a point or segment
// core), EPA (cores of three or more points) or a separating-axis test (a
// point or segment core) when the cores overlap. A contact within kFaceSnapCos of the face normal
// is a face contact: the shape's lowest face (its core points within kFaceSlab of the deepest, as a
// convex outline) is clipped against the triangle, so a box resting on a triangle gets its corners,
// a capsule its two ends. A contact whose triangle feature (the triangle's support along the
// normal) is an inactive edge, or a vertex whose two edges are inactive, is made a face contact too
// (the internal-edge fix: bodies slide over flat and concave edges without catching); if the
// shape's outline then does not reach over the triangle, the triangle gives nothing, since the
// neighbour across the inactive feature (flat or concave, so under the shape) has the contact.
// Other edge and vertex contacts give one point; an overlapping one whose
// normal points past the face of the neighbour across a convex fold there
// (TriangleRef::across) takes that face's normal instead, at the depth
// that lifts the shape out of both faces (EPA against the one triangle
// would let a corner just past the fold out sideways). One-sided: a shape
// whose core centroid is behind the triangle's plane is ignored, and one
// reaching through from the front is pushed out along the face normal.
//
// Reduction to one manifold: the normal of the deepest triangle contact
// (ties to the lower triangle id), blended with those of the contacts
// within 30 degrees of it that are nearly as deep (kBlendCos, kSupportBand:
// a body across a ridge is held by both faces); points of contacts whose
// normals lie within 30 degrees of it, their separations measured along
// it; then at most four: the deepest (near-ties, within kDepthTie,
// to the one farthest from the points' centroid), the farthest from it, the
// one making the largest triangle with those two, and the one that adds the
// most area to that triangle, the last three among the points that touch
// (separation <= 0) before the speculative ones, so a body keeps the points
// it stands on. Every choice is a total order on (value,
// feature id), so below the cap (see Limits) the result does not depend on
// the order the triangles arrive in.
//
// Feature ids: (triangle id << 5) | code, with code
//   0-15   the shape's core point (index & 15: a box's corner, a capsule's
//          end, the sphere's centre) inside the triangle on a face contact
//   16-21  where the shape's face outline crosses triangle edge e on a face
//          contact: 16 + 2e entering, 17 + 2e leaving (in the outline's
//          order in the plane's (tangent_basis) coordinates)
//   24-26  a single-point contact on triangle edge e (0-2)
//   27-29  a single-point contact at triangle vertex k (0-2)
//   30     a face contact whose clipped outline was empty (one point at
//          the witness points; dropped when the manifold has other points)
// so ids persist while the same triangles touch the same features. Hull
// cores of more than 16 points share codes (index & 15), which only
// weakens warm starting. Triangle ids must stay below 2^27.
//
// Limits: no allocation. At most kMaxContactTriangles touching triangles
// are kept, each with at most kMaxTrianglePoints points (a clipped outline
// with more is reduced to four first). Beyond that cap a contact joins a
// stored one with nearly the same normal (keeping the deepest point and
// the extremes along eight directions in the plane), else replaces
// the shallowest stored contact if deeper; the result then depends on the
// order triangles arrive in, which mesh_query and height_field_query fix
// as a function of their inputs. Below the cap the order does not matter.
// Any number of triangles may be offered: far ones cost a GJK call each
// and are not stored.
#include <cstdint>
#include <span>

#include "d3/box_triangle.h"
#include "d3/gjk.h"
#include "d3/manifold.h"
#include "d3/triangle.h"

namespace rwd::sim::d3 {

inline constexpr uint32_t kMaxContactTriangles = 64;
/// Nine: a merged contact (see Limits) keeps its deepest point and the
/// extremes along eight directions.
inline constexpr uint32_t kMaxTrianglePoints = 9;
inline constexpr uint32_t kTriangleFeatureShift = 5;
/// cos(30 degrees): contacts whose normals are this close to the deepest
/// one's share the manifold's normal (blended, weighted by depth) and
/// contribute points.
inline constexpr float kBlendCos = 0.8660254f;
/// Contacts within this of the deepest separation (metres) weigh in the
/// blended normal, the deeper the more.
inline constexpr float kSupportBand = 0.005f;
/// Separations within this of the deepest count as equally deep (metres).
inline constexpr float kDepthTie = 1e-4f;
/// Core points within this of the shape's deepest along a face normal form
/// its face for clipping (metres), on top of the speculative distance.
inline constexpr float kFaceSlab = 1e-3f;
/// A contact normal this close to the face normal (cosine) is taken as it.
inline constexpr float kFaceSnapCos = 0.9999f;

/// One triangle's contact, before reduction.
struct TrianglePoint {
  Vec3 point;  ///< midway between the surfaces
  float separation = 0.0f;
  uint32_t feature_id = 0;
};
struct TriangleContact {
  Vec3 normal;              ///< unit, from the triangle to the shape
  float separation = 0.0f;  ///< the least of the points'
  uint32_t id = 0;          ///< the triangle's
  uint32_t count = 0;
  TrianglePoint points[kMaxTrianglePoints];
};

/// The shape's core mapped into the source's frame, once per call.
struct ShapeCore {
  const ConvexProxy* proxy = nullptr;
  Vec3 points[kProxyMaxPoints];
  uint32_t count = 0;
  float radius = 0.0f;
  Vec3 centroid;
  /// A box meets each triangle by separating axes (box_triangle.h), not
  /// GJK and EPA; `box_frame` is then its pose and half extents.
  bool box = false;
  BoxFrame box_frame;
};
/// `box_half`: the half extents when the shape is a box (its proxy's
/// corners), else null.
ShapeCore make_shape_core(const ConvexProxy& shape, const Vec3* box_half = nullptr);

/// One triangle's contact with the shape (points beyond speculative_m
/// dropped); false when there is none.
bool collide_convex_triangle(const ShapeCore& core, const TriangleRef& tri, bool one_sided,
                             float speculative_m, TriangleContact& out);

/// Streams triangles into one manifold: add() each triangle (any order,
/// ids unique), then finish(). Holds its scratch (about 20 KB) inline.
class TriangleManifoldBuilder {
 public:
  /// `box_half` as for make_shape_core.
  TriangleManifoldBuilder(const ConvexProxy& shape, bool one_sided, float speculative_m,
                          const Vec3* box_half = nullptr);
  void add(const TriangleRef& tri);
  void finish(Manifold& out) const;

 private:
  ShapeCore core_;
  bool one_sided_;
  float speculative_m_;
  uint32_t count_ = 0;
  // Left unset when a builder is made (a union member is constructed only
  // when asked): only the first count_ are ever read, and zeroing all of
  // them, about 20 KB, cost a pair on a height field more than a triangle.
  union {
    TriangleContact contacts_[kMaxContactTriangles];
  };
};

/// The shape (pose in the triangles' frame) against the triangles: one
/// manifold, at most four points (conventions above).
void collide_convex_triangles(const ConvexProxy& shape, std::span<const TriangleRef> triangles,
                              bool one_sided, float speculative_m, Manifold& out,
                              const Vec3* box_half = nullptr);

/// Up to four of the `count` points (indices into them), chosen as the
/// reduction above describes along `normal`; returns how many.
uint32_t reduce_triangle_points(const TrianglePoint* points, uint32_t count, Vec3 normal,
                                uint32_t chosen[4]);

struct TriangleCastOutput {
  bool hit = false;
  /// The surfaces overlap at fraction 0 (see ShapeCastOutput).
  bool initially_overlapping = false;
  float fraction = 0.0f;
  Vec3 point;       ///< on the triangle at the hit (source frame)
  Vec3 normal;      ///< unit, from the triangle to the swept shape
  uint32_t id = 0;  ///< the triangle hit
};

/// Earliest hit of the shape swept by fraction * translation, fraction in
/// [0, max_fraction] (shape_cast per triangle; ties to the lower id). The
/// internal-edge fix applies to the hit normal; one-sided triangles are
/// skipped when the shape's core centroid starts behind them.
class TriangleCaster {
 public:
  TriangleCaster(const ConvexProxy& swept, Vec3 translation, bool one_sided, float max_fraction);
  void add(const TriangleRef& tri);
  const TriangleCastOutput& result() const { return best_; }

 private:
  const ConvexProxy* swept_;
  Vec3 translation_;
  Vec3 centroid_;
  bool one_sided_;
  float max_fraction_;
  TriangleCastOutput best_;
};

TriangleCastOutput shape_cast_triangles(const ConvexProxy& swept, Vec3 translation,
                                        std::span<const TriangleRef> triangles, bool one_sided,
                                        float max_fraction = 1.0f);

namespace triangle_detail {
/// The normal after the internal-edge fix: `normal` (from the triangle to
/// the shape) unless the triangle's feature along it is inactive from the
/// side `side` (the face normal toward the shape), then `side`.
Vec3 fix_internal_edge(const TriangleRef& tri, Vec3 side, Vec3 normal, bool& replaced,
                       uint32_t& code);
/// The face contact along `side` (unit face normal toward the shape): the
/// shape's lowest core points as an outline clipped to the triangle
/// (manifold_triangle_face.cpp). When the outline misses the triangle,
/// `slack` keeps its deepest point lying within a hair (1e-5 of the edge's
/// length) of the triangle (a shape exactly over a shared edge or vertex,
/// which rounding may put outside every triangle there). Returns whether
/// any point is within speculative_m.
bool face_contact(const ShapeCore& core, const TriangleRef& tri, Vec3 side, bool slack,
                  float speculative_m, TriangleContact& out);
}  // namespace triangle_detail

}  // namespace rwd::sim::d3
