// SPDX-License-Identifier: MIT
#pragma once
// The 2D lane's working arithmetic: every value inside the step is a Q32.32
// number in an int64 ("W"), so slow motion, small masses and resting
// contact keep 32 fractional bits. Public values are Q16.16 (Fx) and widen
// exactly; narrowing back rounds to nearest. Products go through 128 bits
// and are rounded once (half up: floor(x + 1/2)), which is as deterministic
// as any other rule and costs one add before the shift.
//
// Overflow: the world keeps positions inside its bounds and speeds under a
// cap, so no sum or product here leaves the int64 range in a valid state;
// narrowing a 128-bit product to int64 is modular in C++20 in any case.
#include <cstdint>
#include <type_traits>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/vec2.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::sim2d::detail {

using fixed::Fx;
using fixed::I128;
using fixed::U128;

/// A Q32.32 value: raw / 2^32.
using W = int64_t;

inline constexpr int kWFrac = 32;
inline constexpr W kWOne = W{1} << kWFrac;
inline constexpr W kWHalf = W{1} << (kWFrac - 1);

/// The whole number n.
constexpr W w_int(int64_t n) {
  return n * kWOne;
}
/// num / den (den != 0), truncated toward zero.
constexpr W w_ratio(int64_t num, int64_t den) {
  return static_cast<W>((static_cast<I128>(num) << kWFrac) / den);
}
/// An Fx widened exactly.
constexpr W w_from(Fx f) {
  return static_cast<W>(f.raw()) * (W{1} << 16);
}
/// Rounded to the nearest Fx ulp (half up), saturated.
constexpr Fx w_to_fx(W w) {
  return Fx::from_raw(fixed::saturate_i32((static_cast<I128>(w) + (W{1} << 15)) >> 16));
}

/// a * b rounded once.
constexpr W wmul(W a, W b) {
  return static_cast<W>((static_cast<I128>(a) * b + kWHalf) >> kWFrac);
}
/// a * b + c * d rounded once.
constexpr W wmul_add(W a, W b, W c, W d) {
  return static_cast<W>((static_cast<I128>(a) * b + static_cast<I128>(c) * d + kWHalf) >> kWFrac);
}
/// a * b - c * d rounded once.
constexpr W wmul_sub(W a, W b, W c, W d) {
  return static_cast<W>((static_cast<I128>(a) * b - static_cast<I128>(c) * d + kWHalf) >> kWFrac);
}
/// a / b truncated toward zero; zero when b is zero (callers that can meet
/// a zero divisor test for it first; this rule only keeps the step total).
/// On x86-64 a quotient that fits in 64 bits (|a| < |b| 2^31, nearly every
/// one) takes the processor's 128-by-64-bit division, which truncates
/// toward zero as the 128-bit division does: the same quotient, in a
/// fraction of the time of the library's 128-by-128 routine.
constexpr W wdiv(W a, W b) {
  if (b == 0) return 0;
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  if (!std::is_constant_evaluated()) {
    const uint64_t ua = a < 0 ? 0 - static_cast<uint64_t>(a) : static_cast<uint64_t>(a);
    const uint64_t ub = b < 0 ? 0 - static_cast<uint64_t>(b) : static_cast<uint64_t>(b);
    if ((ua >> (63 - kWFrac)) < ub) {
      int64_t high = a >> (64 - kWFrac);
      int64_t low = static_cast<int64_t>(static_cast<uint64_t>(a) << kWFrac);
      __asm__("idivq %[d]" : "+a"(low), "+d"(high) : [d] "r"(b) : "cc");
      return low;
    }
  }
#endif
  return static_cast<W>((static_cast<I128>(a) << kWFrac) / b);
}
/// 1 / b truncated; zero when b is zero.
constexpr W winv(W b) {
  return wdiv(kWOne, b);
}
/// sqrt(a) for a >= 0 (floor of the exact root); zero for a <= 0.
W wsqrt(W a);

constexpr W wabs(W a) {
  return a < 0 ? -a : a;
}
constexpr W wmin(W a, W b) {
  return b < a ? b : a;
}
constexpr W wmax(W a, W b) {
  return a < b ? b : a;
}
constexpr W wclamp(W v, W lo, W hi) {
  return v < lo ? lo : (hi < v ? hi : v);
}

/// A 2D vector of W components.
struct V2 {
  W x = 0;
  W y = 0;
  friend constexpr bool operator==(V2 a, V2 b) = default;
  friend constexpr V2 operator+(V2 a, V2 b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr V2 operator-(V2 a, V2 b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr V2 operator-(V2 a) { return {-a.x, -a.y}; }
  constexpr V2& operator+=(V2 b) { return *this = *this + b; }
  constexpr V2& operator-=(V2 b) { return *this = *this - b; }
};

constexpr V2 v_from(fixed::Vec2 v) {
  return {w_from(v.x), w_from(v.y)};
}
constexpr fixed::Vec2 v_to_fx(V2 v) {
  return {w_to_fx(v.x), w_to_fx(v.y)};
}
/// s * v, each component rounded once.
constexpr V2 vscale(W s, V2 v) {
  return {wmul(s, v.x), wmul(s, v.y)};
}
/// a + s * b.
constexpr V2 vmul_add(V2 a, W s, V2 b) {
  return {a.x + wmul(s, b.x), a.y + wmul(s, b.y)};
}
/// a - s * b.
constexpr V2 vmul_sub(V2 a, W s, V2 b) {
  return {a.x - wmul(s, b.x), a.y - wmul(s, b.y)};
}
constexpr W vdot(V2 a, V2 b) {
  return wmul_add(a.x, b.x, a.y, b.y);
}
constexpr W vcross(V2 a, V2 b) {
  return wmul_sub(a.x, b.y, a.y, b.x);
}
/// s x v for a scalar s (the z of an angular velocity): (-s*y, s*x).
constexpr V2 vcross_sv(W s, V2 v) {
  return {-wmul(s, v.y), wmul(s, v.x)};
}
/// v x s: (s*y, -s*x).
constexpr V2 vcross_vs(V2 v, W s) {
  return {wmul(s, v.y), -wmul(s, v.x)};
}
/// A quarter turn counter-clockwise: (-y, x).
constexpr V2 vperp(V2 v) {
  return {-v.y, v.x};
}
/// A quarter turn clockwise: (y, -x).
constexpr V2 vperp_cw(V2 v) {
  return {v.y, -v.x};
}
constexpr V2 vmin(V2 a, V2 b) {
  return {wmin(a.x, b.x), wmin(a.y, b.y)};
}
constexpr V2 vmax(V2 a, V2 b) {
  return {wmax(a.x, b.x), wmax(a.y, b.y)};
}
/// |v|^2 rounded once.
constexpr W vlength_sq(V2 v) {
  return vdot(v, v);
}
/// |v| (floor of the exact root of the exact 128-bit square).
W vlength(V2 v);
/// v / |v| and |v|; the zero vector gives ({0, 0}, 0).
struct UnitLength {
  V2 unit;
  W length = 0;
};
UnitLength vnormalize(V2 v);

/// A rotation as its cosine/sine pair (Q32.32), kept unit length.
struct Rot {
  W c = kWOne;
  W s = 0;
  friend constexpr bool operator==(Rot a, Rot b) = default;
};

constexpr V2 rotate(Rot q, V2 v) {
  return {wmul_sub(q.c, v.x, q.s, v.y), wmul_add(q.s, v.x, q.c, v.y)};
}
constexpr V2 inv_rotate(Rot q, V2 v) {
  return {wmul_add(q.c, v.x, q.s, v.y), wmul_sub(q.c, v.y, q.s, v.x)};
}
/// "b, then a".
constexpr Rot rmul(Rot a, Rot b) {
  return {wmul_sub(a.c, b.c, a.s, b.s), wmul_add(a.s, b.c, a.c, b.s)};
}
/// inverse(a) then b: the rotation from a's frame to b's.
constexpr Rot rinv_mul(Rot a, Rot b) {
  return {wmul_add(a.c, b.c, a.s, b.s), wmul_sub(a.c, b.s, a.s, b.c)};
}
/// Brings a nearly unit (c, s) back to unit length with Newton steps of
/// 1/sqrt about 1, scale = (3 - |q|^2) / 2: the error after a step is about
/// the square of the error before, so a rotation turned by a small angle
/// needs one step and a large turn (up to a quarter turn) a few, with no
/// square root or division. Stops once |q|^2 is within 2^-28 of 1.
constexpr Rot renormalize(Rot q) {
  for (int i = 0; i < 6; ++i) {
    const W m2 = wmul_add(q.c, q.c, q.s, q.s);
    const W scale = (3 * kWOne - m2) / 2;
    q = {wmul(q.c, scale), wmul(q.s, scale)};
    if (wabs(m2 - kWOne) <= (kWOne >> 28)) break;
  }
  return q;
}
/// q turned by the small angle `angle` (radians, Q32.32): the first-order
/// update q + angle * perp(q), renormalized.
constexpr Rot integrate_rotation(Rot q, W angle) {
  return renormalize({q.c - wmul(angle, q.s), q.s + wmul(angle, q.c)});
}

/// A rigid transform: p + q * v.
struct Xf {
  V2 p;
  Rot q;
};

constexpr V2 transform_point(const Xf& xf, V2 v) {
  return xf.p + rotate(xf.q, v);
}
constexpr V2 inv_transform_point(const Xf& xf, V2 v) {
  return inv_rotate(xf.q, v - xf.p);
}
/// inverse(a) * b: b expressed in a's frame.
constexpr Xf inv_mul_xf(const Xf& a, const Xf& b) {
  return {inv_rotate(a.q, b.p - a.p), rinv_mul(a.q, b.q)};
}

}  // namespace rwd::sim2d::detail
