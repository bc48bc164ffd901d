// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/fixed/fx.h"

namespace rwd::sim2d::detail {

/// lo <= v <= hi.
constexpr bool in_range(fixed::Fx v, fixed::Fx lo, fixed::Fx hi) {
  return !(v < lo) && !(hi < v);
}

}  // namespace rwd::sim2d::detail
