// SPDX-License-Identifier: MIT
// Deliberately wrong: computes in floating point without naming a
// floating-point type or writing a floating-point literal (a builtin that
// returns double), which the keyword and literal checks cannot see. The test
// fixed_no_float_detects_codegen requires the -mgeneral-regs-only compile of
// check_no_float.cmake to reject it.
int three_quarters_of_root(int v);
int three_quarters_of_root(int v) {
  return static_cast<int>(__builtin_sqrt(v) * 3) / 4;
}
