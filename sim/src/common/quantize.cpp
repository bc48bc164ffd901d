// SPDX-License-Identifier: MIT
// The canonical input grid. Values from outside (API, scene files, parsers
// on different platforms) are snapped to multiples of 2^-20 so that every
// client starts from the same bits.
#include <cstdint>

#include "rewind/sim/world3d.h"

namespace rwd::sim {

float quantize(float value) {
  // NaN fails both comparisons and is returned unchanged (callers validate).
  if (!(value < 2048.0f && value > -2048.0f)) return value;
  // Scaling by a power of two is exact. |scaled| < 2^31 fits int64; for
  // |value| >= 8 the float ulp is already >= 2^-20, so scaled is an integer
  // and the round trip is exact; below 8, |scaled| < 2^23 and every integer
  // there is a float. Rounding is half away from zero through integer
  // truncation only, which C++ specifies exactly (std::nearbyint would
  // depend on the current rounding mode, which a host may change).
  float scaled = value * 1048576.0f;
  auto truncated = static_cast<int64_t>(scaled);
  float fraction = scaled - static_cast<float>(truncated);  // exact
  if (fraction >= 0.5f) ++truncated;
  if (fraction <= -0.5f) --truncated;
  return static_cast<float>(truncated) * (1.0f / 1048576.0f);
}

Vec3 quantize(Vec3 value) {
  return {quantize(value.x), quantize(value.y), quantize(value.z)};
}

}  // namespace rwd::sim
