// SPDX-License-Identifier: MIT
#pragma once
#include "rewind/core/status.h"
#include "rewind/fixed/fx.h"
#include "rewind/fixed/fx_wide.h"

namespace rwd::fixed {

/// The square root rounded to the nearest ulp: exact to the last bit (the
/// result r minimises |r - sqrt(a)| over all Fx values; no tie can occur).
/// Integer digit-by-digit method; no floating point. A negative argument
/// gives zero; use checked_sqrt() to refuse it.
Fx sqrt(Fx a);

/// sqrt(a) rounded to the nearest Fx ulp, exact to the last bit; saturates
/// at Fx::max() (sqrt of a Q32.32 value can exceed the Fx range only when a
/// is at least 2^30). A negative argument gives zero.
Fx sqrt(FxWide a);

/// sqrt(a), or kInvalidArgument when a is negative.
Result<Fx> checked_sqrt(Fx a);

/// 1 / sqrt(a) rounded to the nearest ulp from the exact root (within one
/// ulp of the true value), saturating at Fx::max() for a tiny a. Zero or a
/// negative a is refused with kInvalidArgument.
Result<Fx> checked_rsqrt(Fx a);

/// a / b, or kInvalidArgument when b is zero (a / b itself saturates).
Result<Fx> checked_div(Fx a, Fx b);

}  // namespace rwd::fixed
