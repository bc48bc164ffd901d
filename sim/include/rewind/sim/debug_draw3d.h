// SPDX-License-Identifier: MIT
#pragma once
// Debug draw of the 3D lane: a World3D's bodies, the last step's contacts,
// its joints and bounds, and single shapes at a pose (a query's or a cast's
// shape), appended to plain buffers (rewind/core/debug_draw.h).
#include "rewind/core/debug_draw.h"
#include "rewind/sim/geometry.h"
#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"

namespace rwd::sim {

class World3D;

/// Appends the world as `options` asks to `out` (see DebugDrawOptions):
/// bodies in slot order, each coloured by its state; contact points of
/// every touching pair of the last step, midway between the two surfaces,
/// with normals from the first body toward the second; a line between the
/// anchors of each live joint (broken ones in their own colour). Meshes and
/// height fields draw every triangle edge (holes left out), so a large
/// level is many lines: a viewer that redraws every frame can draw statics
/// once and pass `static_shapes = false` after. Reads the world only.
void debug_draw(const World3D& world, const DebugDrawOptions& options, DebugDrawBuffers& out);

/// The world's counts for a viewer (bodies, awake, contacts, joints).
WorldViewStats view_stats(const World3D& world);

/// Appends `shape` placed at `position` (m) and `rotation` as a body of it
/// would be placed (its authored frame), in `color`: lines, and triangles
/// when options.solid_shapes. Its hull, mesh, height field or compound is
/// read from `store`; an id the store does not hold, or a non-finite pose,
/// draws nothing.
void draw_shape(const GeometryStore& store, const Shape& shape, Vec3 position, Quat rotation,
                DrawColor color, const DebugDrawOptions& options, DebugDrawBuffers& out);

}  // namespace rwd::sim
