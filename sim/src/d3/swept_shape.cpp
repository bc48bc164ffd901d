// SPDX-License-Identifier: MIT
#include "d3/swept_shape.h"

#include "rewind/sim/geometry.h"

namespace rwd::sim::d3 {

bool can_sweep(const Shape& shape) {
  return shape.type == ShapeType::kCompound || shape_ops(shape.type).proxy != nullptr;
}

void make_swept_shape(const Shape& shape, const GeometryStore& store, Vec3 position,
                      const Mat3& axes, SweptShape& out) {
  out.count = 0;
  if (shape.type != ShapeType::kCompound) {
    out.parts[0] = shape_ops(shape.type).proxy(shape, store, out.storage[0]);
    out.parts[0].position = position;
    out.parts[0].axes = axes;
    out.count = 1;
    return;
  }
  for (const CompoundPart& part : store.compound(shape.geometry)->parts) {
    ConvexProxy& proxy = out.parts[out.count];
    proxy = shape_ops(part.shape.type).proxy(part.shape, store, out.storage[out.count]);
    // The child's axes from the compound's matrix (no quaternion needed).
    const Mat3 child = mat3_from_quat(part.rotation);
    proxy.position = position + axes * part.position;
    proxy.axes = Mat3{axes * child.c0, axes * child.c1, axes * child.c2};
    ++out.count;
  }
}

ShapeCastOutput sweep_against(const Shape& target, const GeometryStore& store, Vec3 position,
                              const Mat3& axes, const SweptShape& swept, Vec3 translation,
                              float max_fraction) {
  const ShapeOps& ops = shape_ops(target.type);
  ShapeCastOutput best;
  float reach = max_fraction;
  for (uint32_t k = 0; k < swept.count; ++k) {
    const ShapeCastOutput hit =
        ops.sweep(target, store, position, axes, swept.parts[k], translation, reach);
    if (hit.hit && (!best.hit || hit.fraction < best.fraction)) {
      best = hit;
      reach = hit.fraction;
    }
  }
  return best;
}

}  // namespace rwd::sim::d3
