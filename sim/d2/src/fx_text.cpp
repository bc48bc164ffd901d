// SPDX-License-Identifier: MIT
#include "fx_text.h"

#include <cstdint>

namespace rwd::sim2d::detail {

std::string fx_to_text(fixed::Fx value) {
  const int64_t raw = value.raw();
  const uint64_t magnitude = raw < 0 ? static_cast<uint64_t>(-raw) : static_cast<uint64_t>(raw);
  std::string out = raw < 0 ? "-" : "";
  out += std::to_string(magnitude >> 16);
  // frac / 65536 = frac * 5^16 / 10^16: sixteen exact decimal digits.
  uint64_t frac = (magnitude & 0xFFFF) * 152587890625ull;
  if (frac == 0) return out;
  std::string digits(16, '0');
  for (int i = 15; i >= 0; --i) {
    digits[static_cast<size_t>(i)] = static_cast<char>('0' + frac % 10);
    frac /= 10;
  }
  while (!digits.empty() && digits.back() == '0') digits.pop_back();
  return out + "." + digits;
}

}  // namespace rwd::sim2d::detail
