// SPDX-License-Identifier: MIT
#include "d3/shape_ops.h"

namespace rwd::sim::d3 {
namespace {

// Indexed by ShapeType.
const ShapeOps* const kTable[kShapeTypeCount] = {&kSphereOps, &kBoxOps, &kCapsuleOps, &kHullOps};
static_assert(static_cast<uint32_t>(ShapeType::kSphere) == 0 &&
              static_cast<uint32_t>(ShapeType::kBox) == 1 &&
              static_cast<uint32_t>(ShapeType::kCapsule) == 2 &&
              static_cast<uint32_t>(ShapeType::kHull) == 3);

}  // namespace

const ShapeOps& shape_ops(ShapeType type) {
  return *kTable[static_cast<uint32_t>(type)];
}

}  // namespace rwd::sim::d3
