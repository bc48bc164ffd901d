// SPDX-License-Identifier: MIT
// Deterministic transcendental functions. Everything is computed in IEEE
// double with + - * / only and rounded once to float at the end, so the
// result is the same bits on every IEEE-754 target (double arithmetic is as
// reproducible as float arithmetic; it simply gives the polynomials headroom
// so the float result is within ~1 ulp of the true value). The C library is
// rejected because its results differ between libm versions and targets.
#include "rewind/core/det_math.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace rwd {
namespace {

// pi/2 split Cody-Waite style: kPio2Hi has 33 significant bits, so k * kPio2Hi
// is exact for |k| < 2^20 (|x| < 1.6e6), and kPio2Lo carries the rest.
constexpr double kPio2Hi = 1.57079632673412561417e+00;
constexpr double kPio2Lo = 6.07710050650619224932e-11;
constexpr double kTwoOverPi = 6.36619772367581382433e-01;
constexpr double kPiD = 3.14159265358979311600e+00;
constexpr double kPio2D = 1.57079632679489655800e+00;
constexpr double kPio4D = 7.85398163397448278999e-01;

// Rounds to the nearest integer, halves away from zero, by integer
// conversion only (truncation toward zero is exactly specified by C++).
int64_t round_to_int(double v) {
  return static_cast<int64_t>(v >= 0.0 ? v + 0.5 : v - 0.5);
}

// Taylor polynomials on |r| <= pi/4 (+ a little): truncation error of the
// next term is below 3e-14 (sin, x^15/15!) and 1e-15 (cos, x^16/16!).
double sin_poly(double r) {
  double r2 = r * r;
  double p = -1.0 / 1307674368000.0;  // -1/15!
  p = p * r2 + 1.0 / 6227020800.0;    // 1/13!
  p = p * r2 - 1.0 / 39916800.0;      // -1/11!
  p = p * r2 + 1.0 / 362880.0;        // 1/9!
  p = p * r2 - 1.0 / 5040.0;          // -1/7!
  p = p * r2 + 1.0 / 120.0;           // 1/5!
  p = p * r2 - 1.0 / 6.0;             // -1/3!
  return r + r * r2 * p;
}
double cos_poly(double r) {
  double r2 = r * r;
  double p = 1.0 / 20922789888000.0;  // 1/16!
  p = p * r2 - 1.0 / 87178291200.0;   // -1/14!
  p = p * r2 + 1.0 / 479001600.0;     // 1/12!
  p = p * r2 - 1.0 / 3628800.0;       // -1/10!
  p = p * r2 + 1.0 / 40320.0;         // 1/8!
  p = p * r2 - 1.0 / 720.0;           // -1/6!
  p = p * r2 + 1.0 / 24.0;            // 1/4!
  p = p * r2 - 0.5;                   // -1/2!
  return 1.0 + r2 * p;
}

// Reduces x to r in [-pi/4, pi/4] with x = r + k*pi/2; returns k mod 4.
int reduce_quadrant(double x, double& r) {
  int64_t k = round_to_int(x * kTwoOverPi);
  double kd = static_cast<double>(k);
  r = (x - kd * kPio2Hi) - kd * kPio2Lo;
  return static_cast<int>(k & 3);
}

// atan on [0, 1]: shift by pi/4 above tan(pi/8) so the series argument
// stays below 0.4143, where the alternating series cut after t^21 leaves
// < 2e-10 relative, far below a float ulp (6e-8) of the result. Evaluated
// in Estrin's order (pairs, then pairs of pairs) rather than Horner's: the
// terms combine in four dependent steps instead of ten, and atan is on the
// joint limits' hot path. The order is fixed in the source, so every build
// rounds it alike.
double atan_unit(double t) {
  double offset = 0.0;
  if (t > 0.41421356237309503) {
    t = (t - 1.0) / (t + 1.0);
    offset = kPio4D;
  }
  const double t2 = t * t;
  const double t4 = t2 * t2;
  const double t8 = t4 * t4;
  const double q0 = -1.0 / 3.0 + t2 * (1.0 / 5.0);
  const double q1 = -1.0 / 7.0 + t2 * (1.0 / 9.0);
  const double q2 = -1.0 / 11.0 + t2 * (1.0 / 13.0);
  const double q3 = -1.0 / 15.0 + t2 * (1.0 / 17.0);
  const double q4 = -1.0 / 19.0 + t2 * (1.0 / 21.0);
  const double r0 = q0 + t4 * q1;
  const double r1 = q2 + t4 * q3;
  const double p = (r0 + t8 * r1) + (t8 * t8) * q4;
  return offset + t + t * t2 * p;
}

double atan2_d(double y, double x) {
  if (x == 0.0 && y == 0.0) return 0.0;
  double ax = x < 0.0 ? -x : x;
  double ay = y < 0.0 ? -y : y;
  double a = ay <= ax ? atan_unit(ay / ax) : kPio2D - atan_unit(ax / ay);
  if (x < 0.0) a = kPiD - a;
  return y < 0.0 ? -a : a;
}

}  // namespace

float det_sin(float x) {
  double r = 0.0;
  switch (reduce_quadrant(static_cast<double>(x), r)) {
    case 0:
      return static_cast<float>(sin_poly(r));
    case 1:
      return static_cast<float>(cos_poly(r));
    case 2:
      return static_cast<float>(-sin_poly(r));
    default:
      return static_cast<float>(-cos_poly(r));
  }
}

float det_cos(float x) {
  double r = 0.0;
  switch (reduce_quadrant(static_cast<double>(x), r)) {
    case 0:
      return static_cast<float>(cos_poly(r));
    case 1:
      return static_cast<float>(-sin_poly(r));
    case 2:
      return static_cast<float>(-cos_poly(r));
    default:
      return static_cast<float>(sin_poly(r));
  }
}

float det_atan2(float y, float x) {
  return static_cast<float>(atan2_d(static_cast<double>(y), static_cast<double>(x)));
}

float det_acos(float x) {
  double c = static_cast<double>(x);
  if (!(c > -1.0)) c = -1.0;  // also maps NaN to pi rather than spreading it
  if (c > 1.0) c = 1.0;
  // acos(c) = atan2(sqrt(1 - c^2), c); (1-c)(1+c) keeps precision near |c| = 1.
  double s = std::sqrt((1.0 - c) * (1.0 + c));
  return static_cast<float>(atan2_d(s, c));
}

float det_exp(float x) {
  // Clamp to the float range: e^88.7 overflows float, e^-103 underflows.
  double v = static_cast<double>(x);
  if (!(v > -104.0)) v = -104.0;
  if (v > 88.7) v = 88.7;
  constexpr double kLn2Hi = 6.93147180369123816490e-01;  // 32 significant bits
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  constexpr double kInvLn2 = 1.44269504088896338700e+00;
  int64_t k = round_to_int(v * kInvLn2);
  double kd = static_cast<double>(k);
  double r = (v - kd * kLn2Hi) - kd * kLn2Lo;  // |r| <= 0.347
  // Taylor to r^13/13!: next term < 1e-17 relative.
  // Horner form 1 + r(1 + r/2(1 + r/3(... (1 + r/13)))).
  double p = 1.0;
  for (double n = 13.0; n >= 1.0; n -= 1.0) p = 1.0 + r * p / n;
  // Scale by 2^k through the exponent field: exact, no libm ldexp.
  uint64_t bits = static_cast<uint64_t>(k + 1023) << 52;
  double scale = 0.0;
  std::memcpy(&scale, &bits, sizeof scale);
  return static_cast<float>(p * scale);
}

}  // namespace rwd
