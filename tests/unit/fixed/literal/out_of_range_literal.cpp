// SPDX-License-Identifier: MIT
// Must not compile: 32768 is beyond the Q16.16 range, and a literal is
// refused rather than saturated. fixed_literal_refuses_out_of_range requires
// the compiler to stop on the literal's own message.
#include "rewind/fixed/fx_literal.h"

using rwd::fixed::operator""_fx;
constexpr rwd::fixed::Fx kBad = 32768_fx;
int bad_raw() {
  return kBad.raw();
}
