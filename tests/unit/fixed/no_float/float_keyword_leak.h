// SPDX-License-Identifier: MIT
// Deliberately wrong: names a floating-point type. The test
// fixed_no_float_detects_keyword requires check_no_float.cmake to reject it.
#pragma once

inline int half_of(int v) {
  return static_cast<int>(static_cast<float>(v) / 2);
}
