// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/sim2d/shape2d.h"
#include "wmath.h"

namespace rwd::sim2d::detail {

/// A Q32.32 value in 128 bits. The mass and second moment of the largest
/// shapes a body may have (a polygon 2^16 m across at 30000 kg/m^2 weighs
/// about 2^47 kg, with an inertia near 2^81 kg m^2) leave the int64 range
/// long before the body's limits are checked, so they are computed in this.
using WW = I128;

/// Mass, centre of mass (body frame) and rotational inertia about that
/// centre of a shape of uniform density (kg/m^2). Where a value fits the
/// int64 range it has the same bits as the lane's W arithmetic gives.
struct MassData2 {
  WW mass = 0;
  V2 center;
  WW inertia = 0;
};

/// pi to 32 fractional bits.
inline constexpr W kWPi = 13493037705;

MassData2 compute_mass(const Shape2D& shape, W density);

}  // namespace rwd::sim2d::detail
