// SPDX-License-Identifier: MIT
// The compound: registered convex children (compound.h) in the body's mass
// frame. Each child meets the other shape through the collide table; the
// children's manifolds become one (the body pair has one contact record):
// the deepest child's normal, the points of every child manifold within 30
// degrees of it (their separations measured along it), reduced to four as
// triangle contacts are (manifold_triangles.h). Feature ids mix the child
// index into the child's id, so they persist while the same children touch.
#include <string>

#include "d3/compound.h"
#include "d3/manifold.h"
#include "d3/manifold_triangles.h"
#include "d3/shape_ops.h"

namespace rwd::sim::d3 {
namespace {

const Compound& compound_of(const Shape& s, const GeometryStore& store) {
  return *store.compound(s.geometry);
}

// A child's pose in the world, for a compound whose mass frame is at `pose`.
ShapePose child_pose(const ShapePose& pose, const CompoundPart& part) {
  ShapePose p;
  p.position = pose.position + pose.axes * part.position;
  p.rotation = normalize(pose.rotation * part.rotation);
  p.axes = mat3_from_quat(p.rotation);
  return p;
}

Status check(const Shape& s, const GeometryStore& store) {
  if (store.compound(s.geometry) == nullptr) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "compound shape refers to geometry " + std::to_string(s.geometry) +
                             ", which is not a compound in this world's geometry store");
  }
  return Status::Ok();
}

void canonical(Shape& s, const GeometryStore& store) {
  s.radius = 0.0f;
  s.half_height = 0.0f;
  s.half_extents = compound_of(s, store).half_size;
}

float extent(const Shape& s, const GeometryStore& store) {
  return compound_of(s, store).extent;
}

float volume(const Shape& s, const GeometryStore& store) {
  return compound_of(s, store).volume;
}

Vec3 inertia(const Shape& s, const GeometryStore& store, float mass) {
  return compound_of(s, store).unit_inertia * mass;
}

Vec3 half_bounds(const Shape& s, const Mat3& axes) {
  const Vec3 h = s.half_extents;
  return abs(axes.c0) * h.x + abs(axes.c1) * h.y + abs(axes.c2) * h.z;
}

// The nearest child hit (ties to the lower child).
bool raycast(const Shape& s, const GeometryStore& store, Vec3 position, Quat rotation, Vec3 origin,
             Vec3 dir, float max_distance, float& t, Vec3& normal) {
  const ShapePose pose{position, rotation, mat3_from_quat(rotation)};
  bool hit = false;
  float best = max_distance;
  for (const CompoundPart& part : compound_of(s, store).parts) {
    const ShapePose p = child_pose(pose, part);
    float ct = 0.0f;
    Vec3 cn;
    if (shape_ops(part.shape.type)
            .raycast(part.shape, store, p.position, p.rotation, origin, dir, best, ct, cn) &&
        (!hit || ct < best)) {
      hit = true;
      best = ct;
      normal = cn;
    }
  }
  t = best;
  return hit;
}

// The earliest child hit (ties to the lower child).
ShapeCastOutput sweep(const Shape& s, const GeometryStore& store, Vec3 position, const Mat3& axes,
                      const ConvexProxy& swept, Vec3 translation, float max_fraction) {
  ShapePose pose;
  pose.position = position;
  pose.axes = axes;
  ShapeCastOutput best;
  float reach = max_fraction;
  for (const CompoundPart& part : compound_of(s, store).parts) {
    // The child's axes from the compound's matrix (no quaternion needed).
    const Mat3 child = mat3_from_quat(part.rotation);
    const Mat3 world{axes * child.c0, axes * child.c1, axes * child.c2};
    const ShapeCastOutput hit = shape_ops(part.shape.type)
                                    .sweep(part.shape, store, position + axes * part.position,
                                           world, swept, translation, reach);
    if (hit.hit && (!best.hit || hit.fraction < best.fraction)) {
      best = hit;
      reach = hit.fraction;
    }
  }
  return best;
}

}  // namespace

void collide_compound(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                      float speculative_m, const GeometryStore& store, Manifold& out) {
  const Compound& c = compound_of(a, store);
  Manifold parts[kCompoundMaxChildren];
  uint32_t deepest = kCompoundMaxChildren;
  float deepest_sep = 0.0f;
  for (uint32_t i = 0; i < c.parts.size(); ++i) {
    collide_shapes(c.parts[i].shape, child_pose(pa, c.parts[i]), b, pb, speculative_m, parts[i],
                   &store);
    for (uint32_t k = 0; k < parts[i].point_count; ++k) {
      if (deepest == kCompoundMaxChildren || parts[i].points[k].separation < deepest_sep) {
        deepest = i;
        deepest_sep = parts[i].points[k].separation;
      }
    }
  }
  out.point_count = 0;
  out.separating_axis = kNoSeparatingAxis;
  out.normal = {0.0f, 1.0f, 0.0f};
  if (deepest == kCompoundMaxChildren) return;
  const Vec3 normal = parts[deepest].normal;
  TrianglePoint points[kCompoundMaxChildren * kMaxManifoldPoints];
  uint32_t n = 0;
  for (uint32_t i = 0; i < c.parts.size(); ++i) {
    const float cos = dot(parts[i].normal, normal);
    if (!(cos >= kBlendCos)) continue;
    for (uint32_t k = 0; k < parts[i].point_count; ++k) {
      const ManifoldPoint& p = parts[i].points[k];
      points[n++] = {p.point, p.separation * cos, (i << 27) ^ p.feature_id};
    }
  }
  uint32_t chosen[4];
  const uint32_t m = reduce_triangle_points(points, n, normal, chosen);
  out.normal = normal;
  for (uint32_t i = 0; i < m; ++i) {
    ManifoldPoint& mp = out.points[i];
    mp.point = points[chosen[i]].point;
    mp.separation = points[chosen[i]].separation;
    mp.feature_id = points[chosen[i]].feature_id;
  }
  out.point_count = m;
}

extern const ShapeOps kCompoundOps{"compound", true,        check,   canonical, extent, volume,
                                   inertia,    half_bounds, raycast, nullptr,   sweep,  nullptr};

}  // namespace rwd::sim::d3
