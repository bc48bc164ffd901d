// SPDX-License-Identifier: MIT
#include "rewind/fixed/vec2.h"

#include "exact2.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::fixed {

namespace detail {

Vec2 unit(W2 v) {
  const U128 s = static_cast<U128>(dot(v, v));  // < 2^65
  if (s == 0) return Vec2::zero();
  // The length in raw units times 2^16, from the exact squared length.
  const U128 len16 = isqrt128_round(s << 32);
  // x / len * 2^16 = x * 2^32 / len16.
  const auto component = [&](int64_t c) {
    return Fx::from_raw(
        saturate_i32(div_round(static_cast<I128>(c) * (I128{1} << 32), static_cast<I128>(len16))));
  };
  return {component(v.x), component(v.y)};
}

}  // namespace detail

Fx length(Vec2 v) {
  const detail::W2 w = detail::raw(v);
  // sqrt(raw^2 sum) is the length in raw units: rounded to nearest.
  return Fx::from_raw(
      saturate_i32(static_cast<I128>(isqrt128_round(static_cast<U128>(detail::dot(w, w))))));
}

Fx distance(Vec2 a, Vec2 b) {
  const detail::W2 d = detail::diff(a, b);
  return Fx::from_raw(
      saturate_i32(static_cast<I128>(isqrt128_round(static_cast<U128>(detail::dot(d, d))))));
}

Vec2 normalized(Vec2 v) {
  return detail::unit(detail::raw(v));
}

}  // namespace rwd::fixed
