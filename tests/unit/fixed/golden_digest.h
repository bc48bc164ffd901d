// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

namespace rwd::fixed {

/// XXH3-64 over the raw results of every operation of the fixed-point
/// library applied to a fixed splitmix64 input stream, each value written as
/// little-endian bytes in a fixed order.
uint64_t golden_digest();

}  // namespace rwd::fixed
