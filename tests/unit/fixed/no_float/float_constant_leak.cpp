// SPDX-License-Identifier: MIT
// Deliberately wrong: a floating-point literal the compiler folds into an
// integer constant, so neither the keyword check nor the
// -mgeneral-regs-only compile can see it. The test
// fixed_no_float_detects_literal requires the literal scan of
// check_no_float.cmake to reject it.
long half_of_three();
long half_of_three() {
  return static_cast<long>(3 * 0.5);
}
