// SPDX-License-Identifier: MIT
#pragma once
// A shape as a sweep moves it: one convex proxy (sphere, box, capsule,
// hull) or one per child of a compound, each posed in the world. Shape
// casts and continuous collision sweep it against a body's shape; the
// earliest touch of any part wins. Meshes and height fields have no proxy
// and are never swept (they only stand still to be struck).
#include <cstdint>

#include "d3/compound.h"
#include "d3/gjk.h"
#include "d3/shape_ops.h"

namespace rwd::sim::d3 {

struct SweptShape {
  SweptShape() = default;
  // The proxies point into `storage`.
  SweptShape(const SweptShape&) = delete;
  SweptShape& operator=(const SweptShape&) = delete;

  uint32_t count = 0;
  ConvexProxy parts[kCompoundMaxChildren];
  ProxyPoints storage[kCompoundMaxChildren];
};

/// Whether `shape` (canonical, checked) can be swept: it has a convex
/// proxy or is a compound of such children.
bool can_sweep(const Shape& shape);

/// Fills `out` for `shape` (can_sweep) with its mass frame at `position`,
/// `axes` in the world.
void make_swept_shape(const Shape& shape, const GeometryStore& store, Vec3 position,
                      const Mat3& axes, SweptShape& out);

/// The first touch of `swept`, moved by fraction * translation with
/// fraction in [0, max_fraction], against `target` with its mass frame at
/// `position`, `axes` (ShapeOps::sweep's conventions; ties go to the lower
/// part).
ShapeCastOutput sweep_against(const Shape& target, const GeometryStore& store, Vec3 position,
                              const Mat3& axes, const SweptShape& swept, Vec3 translation,
                              float max_fraction);

}  // namespace rwd::sim::d3
