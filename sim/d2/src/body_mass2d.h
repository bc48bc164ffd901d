// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/sim2d/shape2d.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

/// Mass, centre of mass (body frame) and rotational inertia about that
/// centre of a shape of uniform density (kg/m^2).
struct MassData2 {
  W mass = 0;
  V2 center;
  W inertia = 0;
};

/// pi to 32 fractional bits.
inline constexpr W kWPi = 13493037705;

MassData2 compute_mass(const Shape2D& shape, W density);

}  // namespace rwd::sim2d::detail
