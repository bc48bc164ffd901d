// SPDX-License-Identifier: MIT
#pragma once
// Which simulation code this build runs. A replay or a snapshot produced by
// another revision may step differently from the same inputs, so tools that
// re-simulate compare revisions before they compare checksums.
#include <cstdint>
#include <string>
#include <string_view>

namespace rwd::sim {

/// Name of the engine, as recorded in replays.
inline constexpr std::string_view kEngineName = "rewind-sim";

/// Simulation revision: raised whenever a change can alter any result (a
/// checksum, a contact, an event) for the same scene and inputs, or the
/// snapshot encoding. Builds with equal revisions re-simulate each other's
/// matches bit for bit; builds with different ones make no such promise.
///   1  first 3D lane
///   2  world bounds (out-of-bounds bodies are disabled), disabled bodies,
///      one validity rule shared by the step and the snapshot reader
///   3  gyroscopic term: angular momentum carried through each tick's turn
///      of the inertia tensor, with energy and |L| conserved
///   4  rigid contacts with the push-out on separate velocities (ordered
///      from the ground up for deep overlaps), each manifold's normal
///      impulses solved as a block, contacts
///      solved colour by colour in batches of four lanes, box-box SAT on
///      the relative rotation matrix
///   5  shallow overlaps pushed out colour by colour in the lanes (deep ones
///      still one at a time from the ground up)
///   6  box manifolds carried forward while their bodies barely move
///      relative to each other (the contact cache keeps each manifold's
///      frame); box-box clipping in the reference face's frame; push-out
///      batches with nothing to push skipped; capsules; rotation locks,
///      torques and forces at a point
///   7  convex hulls (mass frames, SAT and GJK manifolds, carried forward
///      like boxes'), continuous and contact-events flags and rolling
///      resistance per body in the checksum, continuous collision and
///      rolling resistance after the solve
///   8  a body rests by how far it strays over each half of time_to_sleep
///      (its sleep pose in the snapshot) rather than by each tick's speed;
///      small joint trees of like masses (ragdolls) solved row by row;
///      atan by a shorter series
///   9  a ball joint's cone-twist limit and motor solved apart from its
///      point (each row against the point held), the point with the point
///      joints; a limit reached stays a row rather than joining the block
///  10  the angular parts of the point joints in lane batches (ball joints'
///      and hinges') solved in the batches' lanes beside their points, a
///      batch's lanes all of one kind
///  11  gyroscopic term turned by the mean of the tick's start and end
///      rates, its energy kept through |L|^2 - 2 E I_mid
///  12  substeps longer than 1/180 s solve their contacts in three passes;
///      substeps longer than 1/120 s are refused; a compound pair keeps a
///      contact record per group of contact normals (ContactRecord::part)
///  13  substeps longer than 1/240 s are refused (joint chains and the
///      catalogue's accuracy scenes fail at 1/120 s); every substep solves
///      its contacts in one pass
///  14  a manifold's lone point runs one sweep of the normal block (the
///      later ones only moved it by rounding); a triangle's overlapping edge
///      or vertex contact whose normal points past the neighbour's face
///      across a convex fold takes that face
///  15  2D contacts solved from levers fixed at the step's start (speeds
///      along the normal and tangent as one-rounding sums of products, the
///      separation tracked through r . n and r x n) and the normal block
///      from K's inverse, with no division in a pass
///  16  2D joints solved colour by colour (each joint, in state order, in
///      the first of 24 colours where neither body it moves has one)
///  17  shape queries sweep a sphere or a box against a sphere or a box in
///      closed form (the true first touch; conservative advancement before)
///  18  a turning body's rest is measured by how far its mass-frame bounds
///      reach from the turn's axis (a dumbbell rolling about its long axis
///      comes to rest by its bells' radius, not by its length)
///  19  a mesh, height-field or compound manifold keeps the points a body
///      stands on (touching, separation <= 0) before speculative ones when
///      it reduces to four points
///  20  a box meets a mesh's or a height field's triangles by separating
///      axes (the triangle's normal preferred, then the box's faces, then
///      edge pairs) instead of GJK and EPA
///  21  one polygon clipping rule for box-box, hull-hull and a shape's
///      outline on a triangle: a vertex on a side plane is kept once, never
///      doubled by a crossing at the same place (box-box and the triangle
///      outline doubled it); the outline's clipped points come in the
///      polygon's order from its first point
inline constexpr uint32_t kSimRevision = 21;

/// "rewind-sim r11": the engine identity a replay records.
inline std::string engine_version() {
  return std::string(kEngineName) + " r" + std::to_string(kSimRevision);
}

}  // namespace rwd::sim
