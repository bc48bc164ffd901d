// SPDX-License-Identifier: MIT
#include "wmath.h"

namespace rwd::sim2d::detail {

W wsqrt(W a) {
  if (a <= 0) return 0;
  // sqrt(a / 2^32) * 2^32 = sqrt(a * 2^32).
  return static_cast<W>(fixed::isqrt128(static_cast<U128>(a) << kWFrac));
}

namespace {
U128 exact_length_sq(V2 v) {
  const I128 sum = static_cast<I128>(v.x) * v.x + static_cast<I128>(v.y) * v.y;
  return static_cast<U128>(sum);
}
}  // namespace

W vlength(V2 v) {
  // The root of the exact 128-bit square (a Q64.64 value) is Q32.32.
  return static_cast<W>(fixed::isqrt128(exact_length_sq(v)));
}

UnitLength vnormalize(V2 v) {
  const W length = vlength(v);
  if (length == 0) return {};
  return {{wdiv(v.x, length), wdiv(v.y, length)}, length};
}

}  // namespace rwd::sim2d::detail
