// SPDX-License-Identifier: MIT
#pragma once
// Rotations a game builds: about an axis, and facing a direction. Made of
// det_sin/det_cos (rewind/core/det_math.h), + - * / and sqrt only, so every
// machine builds the same bits; std::sin and std::cos may differ between
// C libraries and must not feed the state.
#include "rewind/sim/math.h"

namespace rwd::sim {

/// The rotation by `angle` radians about `axis`, counter-clockwise when
/// the axis points at the viewer. `axis` need not be unit length; a zero or
/// non-finite axis or angle gives the identity.
Quat axis_angle(Vec3 axis, float angle);

/// The rotation that turns +Z onto `forward` and +Y as close to `up` as
/// that allows (a body "looks" along its +Z). Neither need be unit length.
/// A zero or non-finite `forward` gives the identity; an `up` parallel to
/// `forward` (or zero) is replaced by +Y, or by +X when `forward` is along
/// Y, so the result is always defined.
Quat look_at(Vec3 forward, Vec3 up = {0.0f, 1.0f, 0.0f});

}  // namespace rwd::sim
