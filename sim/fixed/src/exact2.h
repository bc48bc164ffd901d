// SPDX-License-Identifier: MIT
#pragma once
// Exact 2D arithmetic on raw integers, shared by the library's sources.
// Differences of two Fx raws need 33 bits, so they live in int64; their
// products and sums of products in 128 bits.
#include <cstdint>

#include "rewind/fixed/vec2.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::fixed::detail {

/// A vector of raw Q16.16 units that may exceed the int32 range.
struct W2 {
  int64_t x;
  int64_t y;
};

inline W2 raw(Vec2 v) {
  return {v.x.raw(), v.y.raw()};
}
/// a - b exactly (|component| < 2^32).
inline W2 diff(Vec2 a, Vec2 b) {
  return {static_cast<int64_t>(a.x.raw()) - b.x.raw(), static_cast<int64_t>(a.y.raw()) - b.y.raw()};
}
inline I128 dot(W2 a, W2 b) {
  return static_cast<I128>(a.x) * b.x + static_cast<I128>(a.y) * b.y;
}
inline I128 cross(W2 a, W2 b) {
  return static_cast<I128>(a.x) * b.y - static_cast<I128>(a.y) * b.x;
}
inline int sign(I128 v) {
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

/// The unit vector along (x, y) in Q16.16, each component within 1 ulp;
/// zero for the zero vector. Requires |x|, |y| <= 2^32.
Vec2 unit(W2 v);

}  // namespace rwd::fixed::detail
