// SPDX-License-Identifier: MIT
#pragma once
// Outlines and surfaces of 3D shapes for debug draw (rewind/sim/debug_draw3d.h).
#include "rewind/core/debug_draw.h"
#include "rewind/sim/geometry.h"
#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"

namespace rwd::sim::d3 {

/// Appends `shape` with its mass frame at `position`, `rotation` (a body's
/// BodySim pose): outline lines when options.shapes, surface triangles when
/// options.solid_shapes. Meshes and height fields, which have no mass, are
/// placed by their frame's centre as the world places them (mass_frame.h).
/// `options` must be sanitized(). An id `store` does not hold draws nothing.
void draw_shape_mass_frame(const GeometryStore& store, const Shape& shape, Vec3 position,
                           Quat rotation, DrawColor color, const DebugDrawOptions& options,
                           DebugDrawBuffers& out);

/// The twelve edges of the box from `lower` to `upper` (world axes).
void draw_box_edges(Vec3 lower, Vec3 upper, DrawColor color, DebugDrawBuffers& out);

}  // namespace rwd::sim::d3
