// SPDX-License-Identifier: MIT
// Deliberately wrong: computes with a floating-point literal without naming
// a floating-point type, which the keyword check cannot see. The test
// fixed_no_float_detects_codegen requires the -mgeneral-regs-only compile of
// check_no_float.cmake to reject it.
int three_quarters_of(int v);
int three_quarters_of(int v) {
  return static_cast<int>(v * 0.75);
}
