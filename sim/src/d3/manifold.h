// SPDX-License-Identifier: MIT
#pragma once
// Contact manifolds: the narrowphase routines for each shape pair. Every
// routine is a pure function of its inputs' bits (no state, no allocation).
//
// Conventions: the normal points from shape A to shape B; separation is
// negative when the shapes overlap; each point lies midway between the two
// surfaces; points farther apart than `speculative_m` are dropped.
//
// Feature ids name the features that produced a point, so a point keeps its
// id from one step to the next while the contact configuration persists and
// its impulse can be warm-started:
//   sphere-sphere:   0
//   box-sphere:      region of the sphere centre in the box frame: outside,
//                    cx + 3cy + 9cz with c = 0 (below), 1 (within), 2 (above);
//                    inside, 27 + closest face (axis * 2 + (positive ? 1 : 0))
//   box-box face:    bit 16 = reference is box B, bits 12-15 reference face,
//                    bits 8-11 incident face, bits 0-3 incident edges the point
//                    lies on, bits 4-7 reference side planes it lies on
//   box-box edge:    bit 31 set, bits 8-15 edge of A, bits 0-7 edge of B
//   capsules:        see manifold_capsule.cpp
#include <cstdint>

#include "rewind/sim/geometry.h"
#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

struct ManifoldPoint {
  Vec3 point;        ///< world position, midway between the surfaces
  Vec3 anchor_a;     ///< point - centre of A (filled by collide_shapes)
  Vec3 anchor_b;     ///< point - centre of B (filled by collide_shapes)
  float separation;  ///< metres, negative when overlapping
  uint32_t feature_id;
};

/// Manifold::separating_axis when no axis separated the shapes (or the
/// routine does not say).
inline constexpr uint8_t kNoSeparatingAxis = 0xFF;

struct Manifold {
  Vec3 normal;  ///< unit, from A to B
  uint32_t point_count = 0;
  /// The axis that put the shapes farther apart than the speculative
  /// distance, so the next step can try it first (shapes_still_separated):
  /// collide_boxes names 0-2 A's faces, 3-5 B's, 6 + 3i + j the edge pair
  /// a_i x b_j; collide_hulls (hull and box-hull pairs) a face (see
  /// kHullFaceAxisB). Named in the order of the routine the collide table
  /// runs for the pair.
  uint8_t separating_axis = kNoSeparatingAxis;
  ManifoldPoint points[kMaxManifoldPoints];
};

/// A box pose: centre, rotation and half extents.
struct BoxPose {
  Vec3 center;
  Quat rotation;
  Vec3 half_extents;
};

/// A capsule's pose: centre, unit axis (its local y in the world), half
/// height and radius.
struct CapsulePose {
  Vec3 center;
  Vec3 axis;
  float half_height;
  float radius;
};

/// The closest points of the segments p + s d and q + t e, s and t in
/// [0, 1] (Ericson, Real-Time Collision Detection 5.1.9); a segment of zero
/// length is a point. Shared by the capsule and hull-capsule manifolds.
void closest_on_segments(Vec3 p, Vec3 d, Vec3 q, Vec3 e, float& s, float& t);

void collide_spheres(Vec3 center_a, float radius_a, Vec3 center_b, float radius_b,
                     float speculative_m, Manifold& out);
/// Capsule A against sphere B (normal from the capsule to the sphere).
void collide_capsule_sphere(const CapsulePose& capsule, Vec3 center, float radius,
                            float speculative_m, Manifold& out);
void collide_capsules(const CapsulePose& a, const CapsulePose& b, float speculative_m,
                      Manifold& out);
/// Box A against capsule B (normal from the box to the capsule).
void collide_box_capsule(const BoxPose& box, const CapsulePose& capsule, float speculative_m,
                         Manifold& out);
/// Box A against sphere B (normal from the box to the sphere).
void collide_box_sphere(const BoxPose& box, Vec3 center, float radius, float speculative_m,
                        Manifold& out);
/// SAT over the 15 axes, then reference/incident face clipping (up to four
/// points) or a single edge-edge point.
void collide_boxes(const BoxPose& a, const BoxPose& b, float speculative_m, Manifold& out);
/// The same with each box's rotation given as its matrix (mat3_from_quat),
/// so a caller that has it does not rebuild it per pair.
void collide_boxes(Vec3 center_a, const Mat3& axes_a, Vec3 half_a, Vec3 center_b,
                   const Mat3& axes_b, Vec3 half_b, float speculative_m, Manifold& out);

/// Whether `axis` (as Manifold::separating_axis numbers it) alone puts the
/// boxes farther apart than speculative_m, computed bit for bit as
/// collide_boxes computes that axis: when it does, collide_boxes finds no
/// points either, so a caller may skip it.
bool box_axis_separates(Vec3 center_a, const Mat3& axes_a, Vec3 half_a, Vec3 center_b,
                        const Mat3& axes_b, Vec3 half_b, uint8_t axis, float speculative_m);

/// A shape's pose for collide_shapes: centre, rotation and its matrix
/// (mat3_from_quat(rotation), which boxes use).
struct ShapePose {
  Vec3 position;
  Quat rotation;
  Mat3 axes;
};

/// Dispatches on the shape types; fills anchors. Normal always from A to B.
/// Poses are of the shapes' mass frames. `store` holds the geometry of
/// shapes that refer to it (hulls); it may be null when neither does.
void collide_shapes(const Shape& shape_a, const ShapePose& pose_a, const Shape& shape_b,
                    const ShapePose& pose_b, float speculative_m, Manifold& out,
                    const GeometryStore* store = nullptr);
void collide_shapes(const Shape& shape_a, Vec3 position_a, Quat rotation_a, const Shape& shape_b,
                    Vec3 position_b, Quat rotation_b, float speculative_m, Manifold& out,
                    const GeometryStore* store = nullptr);

/// Whether `axis` (a Manifold::separating_axis collide_shapes gave for this
/// pair of shapes, in this order) alone still puts them farther apart than
/// speculative_m, computed bit for bit as collide_shapes computes it: then
/// collide_shapes would find no points. False for an axis it cannot test.
bool shapes_still_separated(const Shape& shape_a, const ShapePose& pose_a, const Shape& shape_b,
                            const ShapePose& pose_b, uint8_t axis, float speculative_m,
                            const GeometryStore* store);

}  // namespace rwd::sim::d3
