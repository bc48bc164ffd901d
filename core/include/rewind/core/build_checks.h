// SPDX-License-Identifier: MIT
#pragma once
// Refuse to build the deterministic engine with flags that let the compiler
// change float results between targets. Fast-math reassociates and drops
// NaN/inf semantics; it defines __FAST_MATH__ on gcc and clang.
#if defined(__FAST_MATH__)
#error "rewind_sim must not be compiled with -ffast-math: it breaks cross-machine determinism"
#endif
// FP contraction (a*b+c fused into an FMA on some targets only) cannot be
// detected by the preprocessor; the build adds -ffp-contract=off through the
// rewind_determinism target, and math.h is written to keep no room for it.
#if defined(__FLT_EVAL_METHOD__) && __FLT_EVAL_METHOD__ != 0 && __FLT_EVAL_METHOD__ != -1
#error "rewind_sim needs float math evaluated in float (no x87 excess precision): use SSE2"
#endif
