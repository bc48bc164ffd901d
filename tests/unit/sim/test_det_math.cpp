// SPDX-License-Identifier: MIT
// det_math accuracy against long double references over a grid. This is the
// only test allowed to call the C library's trigonometry: it is the
// reference, never the implementation.
#include "rewind/core/det_math.h"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

TEST(DetMath, SinCosWithinDocumentedErrorOnAGrid) {
  double worst_sin = 0.0;
  double worst_cos = 0.0;
  for (int i = -200000; i <= 200000; ++i) {
    float x = static_cast<float>(i) * 0.0005f;  // [-100, 100]
    long double ref_s = std::sin(static_cast<long double>(x));
    long double ref_c = std::cos(static_cast<long double>(x));
    worst_sin = std::fmax(worst_sin, static_cast<double>(std::fabs(det_sin(x) - ref_s)));
    worst_cos = std::fmax(worst_cos, static_cast<double>(std::fabs(det_cos(x) - ref_c)));
  }
  // Large arguments: the reduction must stay accurate up to 1e5.
  for (int i = 0; i <= 20000; ++i) {
    float x = 5.0f * static_cast<float>(i) + 0.123f;
    long double ref_s = std::sin(static_cast<long double>(x));
    worst_sin = std::fmax(worst_sin, static_cast<double>(std::fabs(det_sin(x) - ref_s)));
  }
  EXPECT_LT(worst_sin, 2e-7);
  EXPECT_LT(worst_cos, 2e-7);
  std::printf("det_sin max error %.3g, det_cos max error %.3g\n", worst_sin, worst_cos);
}

TEST(DetMath, Atan2AcosExpWithinTolerance) {
  double worst_atan = 0.0;
  for (int i = -100; i <= 100; ++i) {
    for (int j = -100; j <= 100; ++j) {
      float y = static_cast<float>(i) * 0.37f;
      float x = static_cast<float>(j) * 0.41f;
      if (x == 0.0f && y == 0.0f) continue;
      long double ref = std::atan2(static_cast<long double>(y), static_cast<long double>(x));
      worst_atan = std::fmax(worst_atan, static_cast<double>(std::fabs(det_atan2(y, x) - ref)));
    }
  }
  EXPECT_LT(worst_atan, 4e-7);  // |angle| <= pi: one float ulp is 2.4e-7
  EXPECT_EQ(det_atan2(0.0f, 0.0f), 0.0f);

  double worst_acos = 0.0;
  for (int i = -1000; i <= 1000; ++i) {
    float x = static_cast<float>(i) * 0.001f;
    long double ref = std::acos(static_cast<long double>(x));
    worst_acos = std::fmax(worst_acos, static_cast<double>(std::fabs(det_acos(x) - ref)));
  }
  EXPECT_LT(worst_acos, 4e-7);
  EXPECT_FLOAT_EQ(det_acos(2.0f), 0.0f);  // clamped
  EXPECT_NEAR(det_acos(-2.0f), kPi, 1e-6f);

  double worst_exp_rel = 0.0;
  for (int i = -8000; i <= 8000; ++i) {
    float x = static_cast<float>(i) * 0.01f;
    long double ref = std::exp(static_cast<long double>(x));
    worst_exp_rel =
        std::fmax(worst_exp_rel, static_cast<double>(std::fabs((det_exp(x) - ref) / ref)));
  }
  EXPECT_LT(worst_exp_rel, 2e-7);  // about one float ulp, relative
  EXPECT_TRUE(std::isfinite(det_exp(1000.0f)));
  EXPECT_GE(det_exp(-1000.0f), 0.0f);
  std::printf("det_atan2 %.3g, det_acos %.3g, det_exp rel %.3g\n", worst_atan, worst_acos,
              worst_exp_rel);
}

TEST(Quantize, SnapsToTheGridHalfAwayFromZero) {
  const float step = 1.0f / 1048576.0f;
  EXPECT_EQ(quantize(0.0f), 0.0f);
  EXPECT_EQ(quantize(1.0f), 1.0f);
  EXPECT_EQ(quantize(0.1f) / step, std::round(0.1 / step));
  EXPECT_EQ(quantize(0.4f * step), 0.0f);
  EXPECT_EQ(quantize(0.5f * step), step);
  EXPECT_EQ(quantize(-0.5f * step), -step);
  EXPECT_EQ(quantize(-0.4f * step), 0.0f);
  // Beyond 2^11 values pass through unchanged.
  EXPECT_EQ(quantize(4096.3f), 4096.3f);
  // Every output is a multiple of 2^-20 and idempotent.
  for (int i = -5000; i <= 5000; ++i) {
    float v = static_cast<float>(i) * 0.0137f + 1e-7f;
    float q = quantize(v);
    float scaled = q * 1048576.0f;
    EXPECT_EQ(scaled, std::trunc(scaled)) << v;
    EXPECT_EQ(quantize(q), q);
    EXPECT_LE(std::fabs(q - v), 0.5f * step + 1e-9f);
  }
  EXPECT_TRUE(std::isnan(quantize(std::nanf(""))));
}

}  // namespace
}  // namespace rwd::sim
