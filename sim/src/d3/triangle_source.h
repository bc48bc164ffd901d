// SPDX-License-Identifier: MIT
#pragma once
// What meshes and height fields share as shapes: both are static triangle
// sources in a local frame (the frame their data was given in), placed by
// a body whose mass frame sits at the centre of their bounds (mass_frame.h).
// A convex shape meets them in that local frame: its proxy is mapped in,
// the triangles near it are streamed to the manifold builder or the caster
// (manifold_triangles.h), and the results are mapped back.
//
// `Query` is a callable (const Aabb& local_box, Visit&& visit) that calls
// visit(const TriangleRef&) for every triangle whose bounds meet the box,
// in an order that is a pure function of the source and the box.
#include <string>

#include "d3/body_storage.h"
#include "d3/gjk.h"
#include "d3/manifold.h"
#include "d3/manifold_triangles.h"
#include "d3/shape_ops.h"

namespace rwd::sim::d3 {

// The table entries meshes and height fields share: surfaces have no
// volume (the state rule keeps them off dynamic bodies), and their shape's
// half extents are half the size of their data's bounds, about whose centre
// the body sits.
inline void surface_canonical(Shape& s, const Aabb& bounds) {
  s.radius = 0.0f;
  s.half_height = 0.0f;
  s.half_extents = (bounds.upper - bounds.lower) * 0.5f;
}
inline float surface_extent(const Shape& s, const GeometryStore& /*store*/) {
  return length(s.half_extents);
}
inline float surface_volume(const Shape& /*s*/, const GeometryStore& /*store*/) {
  return 0.0f;
}
inline Vec3 surface_inertia(const Shape& /*s*/, const GeometryStore& /*store*/, float /*mass*/) {
  return {};
}
inline Vec3 surface_half_bounds(const Shape& s, const Mat3& axes) {
  const Vec3 h = s.half_extents;
  return abs(axes.c0) * h.x + abs(axes.c1) * h.y + abs(axes.c2) * h.z;
}

inline Vec3 bounds_center(const Aabb& b) {
  return (b.lower + b.upper) * 0.5f;
}
/// ShapeOps::check of a surface: its id must name a `kind` in the store.
inline Status check_surface(bool found, const char* kind, uint32_t id) {
  if (found) return Status::Ok();
  return Status::Error(ErrorCode::kInvalidArgument,
                       std::string(kind) + " shape refers to geometry " + std::to_string(id) +
                           ", which is not a " + kind + " in this world's geometry store");
}

/// The source's local frame in the world: x_world = origin + axes * x_local.
struct SourceFrame {
  Vec3 origin;
  Mat3 axes;
};

/// The frame of a source whose body's mass frame is at `position`, `axes`,
/// with `center` the centre of its bounds in its local frame.
inline SourceFrame source_frame(Vec3 position, const Mat3& axes, Vec3 center) {
  return {position - axes * center, axes};
}

inline Vec3 to_local(const SourceFrame& f, Vec3 world) {
  return gjk_detail::mul_transpose(f.axes, world - f.origin);
}

inline Mat3 to_local_axes(const SourceFrame& f, const Mat3& axes) {
  return {gjk_detail::mul_transpose(f.axes, axes.c0), gjk_detail::mul_transpose(f.axes, axes.c1),
          gjk_detail::mul_transpose(f.axes, axes.c2)};
}

/// The source (A) against the convex `shape` (B) at `pose`: one manifold,
/// normal from the source to the shape, in the world frame.
template <class Query>
void collide_source_convex(const SourceFrame& f, bool one_sided, Query&& query, const Shape& shape,
                           const ShapePose& pose, const GeometryStore& store, float speculative_m,
                           Manifold& out) {
  ProxyPoints storage;
  ConvexProxy proxy = shape_ops(shape.type).proxy(shape, store, storage);
  proxy.position = to_local(f, pose.position);
  proxy.axes = to_local_axes(f, pose.axes);
  Aabb box = shape_aabb(shape, proxy.position, proxy.axes);
  const Vec3 reach{speculative_m, speculative_m, speculative_m};
  box = {box.lower - reach, box.upper + reach};
  TriangleManifoldBuilder builder(proxy, one_sided, speculative_m,
                                  shape.type == ShapeType::kBox ? &shape.half_extents : nullptr);
  query(box, [&builder](const TriangleRef& tri) { builder.add(tri); });
  builder.finish(out);
  out.separating_axis = kNoSeparatingAxis;
  out.normal = f.axes * out.normal;
  for (uint32_t i = 0; i < out.point_count; ++i) {
    out.points[i].point = f.origin + f.axes * out.points[i].point;
  }
}

/// ShapeOps::sweep of a triangle source: the convex `swept` (world frame)
/// moved by fraction * translation against the triangles in its path.
template <class Query>
ShapeCastOutput sweep_source(const SourceFrame& f, bool one_sided, Query&& query,
                             const ConvexProxy& swept, Vec3 translation, float max_fraction) {
  ConvexProxy local = swept;
  local.position = to_local(f, swept.position);
  local.axes = to_local_axes(f, swept.axes);
  const Vec3 move = gjk_detail::mul_transpose(f.axes, translation);
  // The path's bounds in the local frame: the proxy's bounds at both ends.
  Vec3 lo{1e30f, 1e30f, 1e30f};
  Vec3 hi{-1e30f, -1e30f, -1e30f};
  for (uint32_t i = 0; i < local.count; ++i) {
    const Vec3 p = local.position + local.axes * local.points[i];
    lo = min(lo, min(p, p + move * max_fraction));
    hi = max(hi, max(p, p + move * max_fraction));
  }
  const Vec3 r{local.radius, local.radius, local.radius};
  TriangleCaster caster(local, move, one_sided, max_fraction);
  query(Aabb{lo - r, hi + r}, [&caster](const TriangleRef& tri) { caster.add(tri); });
  const TriangleCastOutput& hit = caster.result();
  ShapeCastOutput out;
  out.hit = hit.hit;
  out.initially_overlapping = hit.initially_overlapping;
  out.fraction = hit.fraction;
  out.point = f.origin + f.axes * hit.point;
  out.normal = f.axes * hit.normal;
  return out;
}

/// The ShapeOps entries and the convex contact of a triangle source,
/// written once for meshes (shape_mesh.cpp) and height fields
/// (shape_height_field.cpp), which differ only in how their geometry is
/// found, cast against, queried and measured. `Source` provides:
///   using Data (with an Aabb `bounds` in the local frame);
///   static constexpr const char* kName;
///   static const Data* find(const GeometryStore&, uint32_t geometry);
///   static bool one_sided(const Data&);
///   static bool raycast(const Data&, Vec3 origin, Vec3 dir, float max_t,
///                       float& t, Vec3& normal)       (local frame);
///   static void query(const Data&, const Aabb&, Visit&&)  (a `Query`);
///   static bool signed_distance(const Data&, Vec3 q, SurfaceDistance&)
///                                                     (local frame).
template <class Source>
struct SurfaceShape {
  using Data = typename Source::Data;

  static const Data& data(const Shape& s, const GeometryStore& store) {
    return *Source::find(store, s.geometry);
  }
  static SourceFrame frame(const Data& d, Vec3 position, const Mat3& axes) {
    return source_frame(position, axes, bounds_center(d.bounds));
  }
  static auto triangles(const Data& d) {
    return [&d](const Aabb& box, auto&& visit) { Source::query(d, box, visit); };
  }

  static Status check(const Shape& s, const GeometryStore& store) {
    return check_surface(Source::find(store, s.geometry) != nullptr, Source::kName, s.geometry);
  }
  static void canonical(Shape& s, const GeometryStore& store) {
    surface_canonical(s, data(s, store).bounds);
  }
  /// The ray is cast in the local frame; the normal comes back in the world's.
  static bool raycast(const Shape& s, const GeometryStore& store, Vec3 position, Quat rotation,
                      Vec3 origin, Vec3 dir, float max_distance, float& t, Vec3& normal) {
    const Data& d = data(s, store);
    const SourceFrame f = frame(d, position, mat3_from_quat(rotation));
    Vec3 n;
    if (!Source::raycast(d, to_local(f, origin), gjk_detail::mul_transpose(f.axes, dir),
                         max_distance, t, n)) {
      return false;
    }
    normal = f.axes * n;
    return true;
  }
  static ShapeCastOutput sweep(const Shape& s, const GeometryStore& store, Vec3 position,
                               const Mat3& axes, const ConvexProxy& swept, Vec3 translation,
                               float max_fraction) {
    const Data& d = data(s, store);
    return sweep_source(frame(d, position, axes), Source::one_sided(d), triangles(d), swept,
                        translation, max_fraction);
  }
  /// Measured in the local frame and mapped back to the world's.
  static bool signed_distance(const Shape& s, const GeometryStore& store, Vec3 position,
                              const Mat3& axes, Vec3 point, SurfaceDistance& out) {
    const Data& d = data(s, store);
    const SourceFrame f = frame(d, position, axes);
    SurfaceDistance local;
    if (!Source::signed_distance(d, to_local(f, point), local)) return false;
    out.distance = local.distance;
    out.point = f.origin + f.axes * local.point;
    out.normal = f.axes * local.normal;
    return true;
  }
  /// The source (A, mass-frame pose `pose`) against the convex `shape` (B).
  static void collide_convex(const Shape& surface, const ShapePose& pose, const Shape& shape,
                             const ShapePose& shape_pose, float speculative_m,
                             const GeometryStore& store, Manifold& out) {
    const Data& d = data(surface, store);
    collide_source_convex(frame(d, pose.position, pose.axes), Source::one_sided(d), triangles(d),
                          shape, shape_pose, store, speculative_m, out);
  }
  /// The table entry: a surface (not solid), with no convex proxy.
  static constexpr ShapeOps ops() {
    return {Source::kName,  false,          check,           canonical,
            surface_extent, surface_volume, surface_inertia, surface_half_bounds,
            raycast,        nullptr,        sweep,           signed_distance};
  }
};

}  // namespace rwd::sim::d3
