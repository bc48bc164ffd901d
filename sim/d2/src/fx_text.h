// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "rewind/fixed/fx.h"

namespace rwd::sim2d::detail {

/// The exact decimal value of `value` (every Q16.16 number has a finite
/// decimal expansion of at most 16 fractional digits), trailing zeros
/// dropped: "-10", "0.005000305175781250" becomes "0.00500030517578125".
std::string fx_to_text(fixed::Fx value);

}  // namespace rwd::sim2d::detail
