// SPDX-License-Identifier: MIT
#pragma once
// Debug draw of the 2D lane: a World2D's bodies, the last step's contacts
// and its joints, and single shapes at a pose, appended to the plain
// buffers both lanes share (rewind/core/debug_draw.h). Drawing happens
// outside the step and only converts the world's fixed-point values to
// float32 for the eye: like the checksum's boundary, it is one of the two
// files of the lane allowed floating point, and nothing it computes is
// ever read back into a world.
#include "rewind/core/debug_draw.h"
#include "rewind/fixed/fx.h"
#include "rewind/fixed/vec2.h"
#include "rewind/sim2d/shape2d.h"

namespace rwd::sim2d {

class World2D;

/// Appends the world as `options` asks to `out` (rwd::DebugDrawOptions),
/// in the x-y plane at each body's z (World2D::z, its draw order): bodies
/// in slot order, coloured by state; the contact points of every touching
/// pair of the last step with normals from the first body toward the
/// second; a line between the anchors of each live joint (a grab joint's
/// anchor to its target too). A polygon's or capsule's rounding is drawn
/// as arcs; a circle has a line from its centre along the body's x axis,
/// so its turning shows. Solid shapes are triangle fans, counter-clockwise
/// seen from +z; segments and chain segments have no surface. Reads the
/// world only.
void debug_draw(const World2D& world, const rwd::DebugDrawOptions& options,
                rwd::DebugDrawBuffers& out);

/// The world's counts for a viewer (bodies, awake, contacts, joints).
rwd::WorldViewStats view_stats(const World2D& world);

/// Appends `shape` with its body origin at `position` (m) turned by
/// `angle` (rad), at draw depth `z`, in `color`.
void draw_shape(const Shape2D& shape, fixed::Vec2 position, fixed::Fx angle, fixed::Fx z,
                rwd::DrawColor color, const rwd::DebugDrawOptions& options,
                rwd::DebugDrawBuffers& out);

}  // namespace rwd::sim2d
