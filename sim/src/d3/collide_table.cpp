// SPDX-License-Identifier: MIT
// The collide table: one routine per pair of shape types, indexed [a][b].
// A pair is written once, for the order its routine takes; the reversed
// entry calls it with the shapes swapped and turns the normal around, so
// the normal always runs from A to B (as Box2D v3's s_registers and Jolt's
// CollisionDispatch do). Every entry is filled: there is no default that
// treats an unknown shape as some other shape.
#include <cstdint>

#include "d3/hull.h"
#include "d3/manifold.h"
#include "d3/manifold_hull.h"
#include "d3/manifold_hull_sat.h"
#include "d3/shape_ops.h"

namespace rwd::sim::d3 {
namespace {

using CollideFn = void (*)(const Shape&, const ShapePose&, const Shape&, const ShapePose&, float,
                           const GeometryStore*, Manifold&);

void sphere_sphere(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                   float speculative_m, const GeometryStore* /*store*/, Manifold& out) {
  collide_spheres(pa.position, a.radius, pb.position, b.radius, speculative_m, out);
}

void box_sphere(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                float speculative_m, const GeometryStore* /*store*/, Manifold& out) {
  collide_box_sphere({pa.position, pa.rotation, a.half_extents}, pb.position, b.radius,
                     speculative_m, out);
}

void box_box(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
             float speculative_m, const GeometryStore* /*store*/, Manifold& out) {
  collide_boxes(pa.position, pa.axes, a.half_extents, pb.position, pb.axes, b.half_extents,
                speculative_m, out);
}

CapsulePose capsule_pose(const Shape& s, const ShapePose& p) {
  return {p.position, p.axes.c1, s.half_height, s.radius};
}

void capsule_sphere(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                    float speculative_m, const GeometryStore* /*store*/, Manifold& out) {
  collide_capsule_sphere(capsule_pose(a, pa), pb.position, b.radius, speculative_m, out);
}

void capsule_capsule(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                     float speculative_m, const GeometryStore* /*store*/, Manifold& out) {
  collide_capsules(capsule_pose(a, pa), capsule_pose(b, pb), speculative_m, out);
}

void box_capsule(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                 float speculative_m, const GeometryStore* /*store*/, Manifold& out) {
  collide_box_capsule({pa.position, pa.rotation, a.half_extents}, capsule_pose(b, pb),
                      speculative_m, out);
}

const Hull& hull_of(const Shape& s, const GeometryStore* store) {
  return *store->hull(s.geometry);
}

void hull_sphere(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                 float speculative_m, const GeometryStore* store, Manifold& out) {
  collide_hull_sphere(hull_of(a, store), pa.position, pa.axes, pb.position, b.radius, speculative_m,
                      out);
}

void hull_capsule(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                  float speculative_m, const GeometryStore* store, Manifold& out) {
  collide_hull_capsule(hull_of(a, store), pa.position, pa.axes, capsule_pose(b, pb), speculative_m,
                       out);
}

void box_hull(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
              float speculative_m, const GeometryStore* store, Manifold& out) {
  collide_box_hull(pa.position, pa.axes, a.half_extents, hull_of(b, store), pb.position, pb.axes,
                   speculative_m, out);
}

void hull_hull(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
               float speculative_m, const GeometryStore* store, Manifold& out) {
  collide_hulls(hull_of(a, store), pa.position, pa.axes, hull_of(b, store), pb.position, pb.axes,
                speculative_m, out);
}

void mesh_convex(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                 float speculative_m, const GeometryStore* store, Manifold& out) {
  collide_mesh_convex(a, pa, b, pb, speculative_m, *store, out);
}

void field_convex(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                  float speculative_m, const GeometryStore* store, Manifold& out) {
  collide_height_field_convex(a, pa, b, pb, speculative_m, *store, out);
}

// Meshes and height fields belong to static and kinematic bodies, which
// never need contacts with each other: the pair has no points.
void surfaces(const Shape& /*a*/, const ShapePose& /*pa*/, const Shape& /*b*/,
              const ShapePose& /*pb*/, float /*speculative_m*/, const GeometryStore* /*store*/,
              Manifold& out) {
  out.point_count = 0;
  out.normal = {0.0f, 1.0f, 0.0f};
}

void compound_any(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                  float speculative_m, const GeometryStore* store, Manifold& out) {
  collide_compound(a, pa, b, pb, speculative_m, *store, out);
}

struct Entry {
  CollideFn fn = nullptr;
  bool reversed = false;  // fn takes (b, a)
};

struct Table {
  Entry at[kShapeTypeCount][kShapeTypeCount];
};

constexpr Table make_table() {
  Table t;
  const auto add = [&t](ShapeType a, ShapeType b, CollideFn fn) {
    const auto ia = static_cast<uint32_t>(a);
    const auto ib = static_cast<uint32_t>(b);
    t.at[ia][ib] = {fn, false};
    if (ia != ib) t.at[ib][ia] = {fn, true};
  };
  add(ShapeType::kSphere, ShapeType::kSphere, sphere_sphere);
  add(ShapeType::kBox, ShapeType::kSphere, box_sphere);
  add(ShapeType::kBox, ShapeType::kBox, box_box);
  add(ShapeType::kCapsule, ShapeType::kSphere, capsule_sphere);
  add(ShapeType::kCapsule, ShapeType::kCapsule, capsule_capsule);
  add(ShapeType::kBox, ShapeType::kCapsule, box_capsule);
  add(ShapeType::kHull, ShapeType::kSphere, hull_sphere);
  add(ShapeType::kHull, ShapeType::kCapsule, hull_capsule);
  add(ShapeType::kBox, ShapeType::kHull, box_hull);
  add(ShapeType::kHull, ShapeType::kHull, hull_hull);
  for (ShapeType convex :
       {ShapeType::kSphere, ShapeType::kBox, ShapeType::kCapsule, ShapeType::kHull}) {
    add(ShapeType::kMesh, convex, mesh_convex);
    add(ShapeType::kHeightField, convex, field_convex);
  }
  add(ShapeType::kMesh, ShapeType::kMesh, surfaces);
  add(ShapeType::kMesh, ShapeType::kHeightField, surfaces);
  add(ShapeType::kHeightField, ShapeType::kHeightField, surfaces);
  for (uint32_t other = 0; other < kShapeTypeCount; ++other) {
    add(ShapeType::kCompound, static_cast<ShapeType>(other), compound_any);
  }
  return t;
}

constexpr Table kTable = make_table();

constexpr bool complete(const Table& t) {
  for (const auto& row : t.at) {
    for (const Entry& e : row) {
      if (e.fn == nullptr) return false;
    }
  }
  return true;
}
static_assert(complete(kTable), "every pair of shape types needs a collide routine");

}  // namespace

void collide_shapes(const Shape& shape_a, Vec3 position_a, Quat rotation_a, const Shape& shape_b,
                    Vec3 position_b, Quat rotation_b, float speculative_m, Manifold& out,
                    const GeometryStore* store) {
  collide_shapes(shape_a, {position_a, rotation_a, mat3_from_quat(rotation_a)}, shape_b,
                 {position_b, rotation_b, mat3_from_quat(rotation_b)}, speculative_m, out, store);
}

void collide_shapes(const Shape& shape_a, const ShapePose& pose_a, const Shape& shape_b,
                    const ShapePose& pose_b, float speculative_m, Manifold& out,
                    const GeometryStore* store) {
  out.separating_axis = kNoSeparatingAxis;
  const Entry& e =
      kTable.at[static_cast<uint32_t>(shape_a.type)][static_cast<uint32_t>(shape_b.type)];
  if (e.reversed) {
    e.fn(shape_b, pose_b, shape_a, pose_a, speculative_m, store, out);
    out.normal = -out.normal;  // the routine's normal ran from B to A
    // separating_axis stays in the routine's order: shapes_still_separated
    // tests it in that order too.
  } else {
    e.fn(shape_a, pose_a, shape_b, pose_b, speculative_m, store, out);
  }
  for (uint32_t i = 0; i < out.point_count; ++i) {
    out.points[i].anchor_a = out.points[i].point - pose_a.position;
    out.points[i].anchor_b = out.points[i].point - pose_b.position;
  }
}

bool shapes_still_separated(const Shape& shape_a, const ShapePose& pose_a, const Shape& shape_b,
                            const ShapePose& pose_b, uint8_t axis, float speculative_m,
                            const GeometryStore* store) {
  if (axis == kNoSeparatingAxis) return false;
  const Entry& e =
      kTable.at[static_cast<uint32_t>(shape_a.type)][static_cast<uint32_t>(shape_b.type)];
  // The routine's own A and B.
  const Shape& a = e.reversed ? shape_b : shape_a;
  const Shape& b = e.reversed ? shape_a : shape_b;
  const ShapePose& pa = e.reversed ? pose_b : pose_a;
  const ShapePose& pb = e.reversed ? pose_a : pose_b;
  if (a.type == ShapeType::kBox && b.type == ShapeType::kBox) {
    return box_axis_separates(pa.position, pa.axes, a.half_extents, pb.position, pb.axes,
                              b.half_extents, axis, speculative_m);
  }
  if (b.type != ShapeType::kHull || store == nullptr) return false;
  const HullView hb = hull_view(hull_of(b, store));
  if (a.type == ShapeType::kBox) {
    const BoxHull box = make_box_hull(a.half_extents);
    return hull_axis_separates(box.view(), pa.position, pa.axes, hb, pb.position, pb.axes, axis,
                               speculative_m);
  }
  if (a.type != ShapeType::kHull) return false;
  return hull_axis_separates(hull_view(hull_of(a, store)), pa.position, pa.axes, hb, pb.position,
                             pb.axes, axis, speculative_m);
}

}  // namespace rwd::sim::d3
