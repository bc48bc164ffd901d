// SPDX-License-Identifier: MIT
#include "rewind/fixed/fx_math.h"

#include <string>

#include "rewind/fixed/wide_int.h"

namespace rwd::fixed {

Fx sqrt(Fx a) {
  if (a.raw() <= 0) return Fx::zero();
  // sqrt(raw / 2^16) * 2^16 = sqrt(raw * 2^16).
  const U128 root = isqrt128_round(static_cast<U128>(a.raw()) << 16);
  return Fx::from_raw(static_cast<int32_t>(root));  // < 2^24: always fits
}

Fx sqrt(FxWide a) {
  if (a.raw() <= 0) return Fx::zero();
  // sqrt(raw / 2^32) * 2^16 = sqrt(raw).
  const U128 root = isqrt128_round(static_cast<U128>(a.raw()));
  return Fx::from_raw(saturate_i32(static_cast<I128>(root)));
}

Result<Fx> checked_sqrt(Fx a) {
  if (a.raw() < 0) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "sqrt of a negative value (raw " + std::to_string(a.raw()) + ")");
  }
  return sqrt(a);
}

Result<Fx> checked_rsqrt(Fx a) {
  if (a.raw() <= 0) {
    return Status::Error(
        ErrorCode::kInvalidArgument,
        "rsqrt of a value that is not positive (raw " + std::to_string(a.raw()) + ")");
  }
  // 1/sqrt(raw / 2^16) * 2^16 = 2^24 / sqrt(raw). Take the root with 24
  // extra bits (sqrt(raw * 2^48) = sqrt(raw) * 2^24) and divide once.
  const U128 root = isqrt128_round(static_cast<U128>(a.raw()) << 48);
  const I128 num = I128{1} << 48;
  return Fx::from_raw(saturate_i32(div_round(num, static_cast<I128>(root))));
}

Result<Fx> checked_div(Fx a, Fx b) {
  if (b.raw() == 0) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "division by zero (dividend raw " + std::to_string(a.raw()) + ")");
  }
  return a / b;
}

}  // namespace rwd::fixed
