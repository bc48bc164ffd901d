// SPDX-License-Identifier: MIT
#pragma once
// Manifold reuse: a contact's manifold carried forward while its two bodies
// barely move relative to each other, instead of colliding the shapes again
// (as Jolt's contact cache does). The contact record keeps the frame of
// the last computed manifold: B's pose and the normal in A's body frame,
// and each point's position on A's surface with its separation then. While
// every point of B stays within kReuseDistance of where that pose put it,
// each point's A side stays fixed on A, its B side moves with B, and the
// separation is measured between the two along the normal.
//
// Only pairs of shapes whose contact features are fixed on them (boxes and
// hulls) are carried: a rolling sphere's or capsule's contact point moves over its
// surface, which carrying would turn into a tilted normal.
//
// The frame is not updated on reuse, so slow drift adds up until it crosses
// the bound and the shapes are collided again; the bound is well under the
// slop, so a feature that comes into reach meanwhile (a box tipping onto a
// new corner) is at most that late. Everything here is a pure function of
// state, so a restored world reuses exactly where the original did.
#include "d3/manifold.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

/// How far (metres) the centre of B, and separately any point of B through
/// its turn, may move relative to A from the pose its manifold was computed
/// at before the shapes are collided again.
inline constexpr float kReuseDistance = 0.0005f;

/// B's pose in A's body frame.
struct RelativePose {
  Vec3 position;
  Quat rotation;
};

/// `axes_a` is A's rotation as a matrix (mat3_from_quat(a.rotation)).
RelativePose relative_pose(const BodySim& a, const Mat3& axes_a, const BodySim& b);

/// Whether B, now at `now` in A's frame, is still within kReuseDistance of
/// the pose `rec`'s manifold was computed at. `turn` = now.rotation *
/// conjugate(rec.frame_rotation), the turn since then; extent_b is B's
/// largest distance from its centre to its surface.
bool within_reuse(const ContactRecord& rec, const RelativePose& now, Quat turn, float extent_b);

/// `old`'s manifold (point_count > 0) carried to the bodies' current poses
/// `sa` (with its matrix `axes_a`) and `sb` (`now` and `turn` as for
/// within_reuse): normal, points with their anchors, separations and
/// feature ids.
void carry_manifold(const BodySim& sa, const Mat3& axes_a, const BodySim& sb,
                    const ContactRecord& old, const RelativePose& now, Quat turn, Manifold& m);

/// Records in `rec` the frame of `m`, a manifold just computed at poses
/// `axes_a` (A's matrix) and `now` (B relative to A), whose first
/// rec.point_count points are rec's points in order (anchors filled, as
/// collide_shapes leaves them).
void record_frame(const Mat3& axes_a, const RelativePose& now, const Manifold& m,
                  ContactRecord& rec);

}  // namespace rwd::sim::d3
