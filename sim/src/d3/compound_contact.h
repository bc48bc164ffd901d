// SPDX-License-Identifier: MIT
#pragma once
// A compound's contacts (shape_compound.cpp): its children against another
// shape, or against another compound's children, grouped by normal into up
// to kMaxContactParts manifolds. The narrowphase places every compound's
// children once per step (ChildFrame) and hands each pair job a
// CompoundWork of its thread's, so a pair costs its child collisions and no
// more: a compound meets several bodies a step, and zeroing the work's
// arrays for each pair cost as much as the children's collisions.
#include <cstdint>

#include "d3/aabb_tree.h"
#include "d3/compound.h"
#include "d3/manifold.h"
#include "d3/manifold_triangles.h"
#include "rewind/sim/shape.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim {
class GeometryStore;
}

namespace rwd::sim::d3 {

/// One child of a compound where it stands: its world pose, and its
/// bounds there (not grown by any speculative distance).
struct ChildFrame {
  ShapePose pose;
  Aabb bounds;
};

/// The frames of compound `s`'s children for the compound's mass frame at
/// `pose`, into frames[0, child count). Bit for bit what a pair computes.
void place_children(const Shape& s, const ShapePose& pose, const GeometryStore& store,
                    ChildFrame frames[kCompoundMaxChildren]);

/// Working arrays of collide_compound_parts: about 6 KB, so one is made per
/// thread and reused, not zeroed per pair. Nothing in it outlives a call.
struct CompoundWork {
  Manifold children[kCompoundMaxChildren];
  float deepest[kCompoundMaxChildren];
  uint32_t keys[kCompoundMaxChildren];
  uint32_t order[kCompoundMaxChildren];
  uint32_t group_of[kCompoundMaxChildren];
  Aabb grown_b[kCompoundMaxChildren];
  ChildFrame frames_a[kCompoundMaxChildren];  ///< when the caller has none placed
  ChildFrame frames_b[kCompoundMaxChildren];
  TrianglePoint points[kCompoundMaxChildren * kMaxManifoldPoints];
};

/// A compound (A, children at frames_a) against shape B at pb, or against
/// B's children at frames_b when B is a compound (frames_b null otherwise):
/// the children's manifolds grouped by normal into out[0, count), the
/// deepest group first, each normal from A to B. Returns count, at most
/// kMaxContactParts. Anchors are left for the caller.
uint32_t collide_compound_parts(const Shape& a, const ChildFrame* frames_a, const Shape& b,
                                const ShapePose& pb, const ChildFrame* frames_b,
                                float speculative_m, const GeometryStore& store, CompoundWork& work,
                                Manifold out[kMaxContactParts]);

}  // namespace rwd::sim::d3
