// SPDX-License-Identifier: MIT
// Must not compile: _fx literals are plain decimals (no exponent), so the
// value is always exactly the digits written. fixed_literal_refuses_exponent
// requires the compiler to stop on the literal's own message.
#include "rewind/fixed/fx_literal.h"

using rwd::fixed::operator""_fx;
constexpr rwd::fixed::Fx kBad = 1e3_fx;
int bad_raw() {
  return kBad.raw();
}
