// SPDX-License-Identifier: MIT
#include "d3/shape_ops.h"

namespace rwd::sim::d3 {
namespace {

// Indexed by ShapeType.
const ShapeOps* const kTable[kShapeTypeCount] = {&kSphereOps, &kBoxOps,  &kCapsuleOps,
                                                 &kHullOps,   &kMeshOps, &kHeightFieldOps,
                                                 &kCompoundOps};
static_assert(static_cast<uint32_t>(ShapeType::kSphere) == 0 &&
              static_cast<uint32_t>(ShapeType::kBox) == 1 &&
              static_cast<uint32_t>(ShapeType::kCapsule) == 2 &&
              static_cast<uint32_t>(ShapeType::kHull) == 3 &&
              static_cast<uint32_t>(ShapeType::kMesh) == 4 &&
              static_cast<uint32_t>(ShapeType::kHeightField) == 5 &&
              static_cast<uint32_t>(ShapeType::kCompound) == 6);

}  // namespace

const ShapeOps& shape_ops(ShapeType type) {
  return *kTable[static_cast<uint32_t>(type)];
}

ShapeCastOutput sweep_convex(const Shape& shape, const GeometryStore& store, Vec3 position,
                             const Mat3& axes, const ConvexProxy& swept, Vec3 translation,
                             float max_fraction) {
  ProxyPoints storage;
  ConvexProxy target = shape_ops(shape.type).proxy(shape, store, storage);
  target.position = position;
  target.axes = axes;
  return shape_cast(target, swept, translation, max_fraction);
}

}  // namespace rwd::sim::d3
