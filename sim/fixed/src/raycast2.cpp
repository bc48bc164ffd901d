// SPDX-License-Identifier: MIT
#include "rewind/fixed/raycast2.h"

#include <cstdint>

#include "exact2.h"
#include "rewind/fixed/wide_int.h"

namespace rwd::fixed {

using detail::W2;

namespace {

// A fraction num / den with den > 0, kept exact until the hit is reported.
struct Ratio {
  I128 num;
  I128 den;
};

bool less(Ratio a, Ratio b) {
  return a.num * b.den < b.num * a.den;
}

Fx to_fx(Ratio t) {
  return Fx::from_raw(saturate_i32(div_round(t.num * Fx::kOneRaw, t.den)));
}

// origin + delta * t, each component rounded once from the exact value.
Vec2 point_at(Ray2 ray, Ratio t) {
  const auto along = [&](Fx o, Fx d) {
    return Fx::from_raw(
        saturate_i32(o.raw() + div_round(static_cast<I128>(d.raw()) * t.num, t.den)));
  };
  return {along(ray.origin.x, ray.delta.x), along(ray.origin.y, ray.delta.y)};
}

bool is_zero(Vec2 v) {
  return v.x.raw() == 0 && v.y.raw() == 0;
}

}  // namespace

std::optional<RayHit2> raycast(Ray2 ray, Aabb2 box) {
  if (is_zero(ray.delta)) return std::nullopt;
  const int64_t origin[2] = {ray.origin.x.raw(), ray.origin.y.raw()};
  const int64_t delta[2] = {ray.delta.x.raw(), ray.delta.y.raw()};
  const int64_t lower[2] = {box.lower.x.raw(), box.lower.y.raw()};
  const int64_t upper[2] = {box.upper.x.raw(), box.upper.y.raw()};
  bool has_range = false;
  Ratio enter{0, 1};
  Ratio exit{0, 1};
  int enter_axis = 0;
  for (int k = 0; k < 2; ++k) {
    if (delta[k] == 0) {
      // Parallel to this slab: inside it for the whole sweep, or never.
      if (origin[k] < lower[k] || origin[k] > upper[k]) return std::nullopt;
      continue;
    }
    // Entry and exit fractions of this slab, with a positive denominator.
    const bool forward = delta[k] > 0;
    const I128 den = forward ? delta[k] : -delta[k];
    const I128 to_lower = lower[k] - origin[k];
    const I128 to_upper = upper[k] - origin[k];
    const Ratio near{forward ? to_lower : -to_upper, den};
    const Ratio far{forward ? to_upper : -to_lower, den};
    if (!has_range || less(enter, near)) {
      enter = near;
      enter_axis = k;
    }
    if (!has_range || less(far, exit)) exit = far;
    has_range = true;
  }
  // Starting inside (or past) the box puts the entry behind the origin.
  if (enter.num < 0 || enter.num > enter.den || less(exit, enter)) return std::nullopt;
  RayHit2 hit;
  hit.fraction = to_fx(enter);
  hit.point = point_at(ray, enter);
  const Fx facing = delta[enter_axis] > 0 ? -Fx::one() : Fx::one();
  hit.normal = enter_axis == 0 ? Vec2{facing, Fx::zero()} : Vec2{Fx::zero(), facing};
  return hit;
}

std::optional<RayHit2> raycast(Ray2 ray, Circle circle) {
  W2 m = detail::diff(ray.origin, circle.center);
  W2 d = detail::raw(ray.delta);
  I128 r = circle.radius.raw();
  // Keep |m| below 2^31 per axis so every product below fits in 128 bits:
  // a, |b|, |m|^2 < 2^63 and b^2, a*c < 2^126.
  constexpr int64_t kLimit = int64_t{1} << 31;
  if (m.x >= kLimit || m.x <= -kLimit || m.y >= kLimit || m.y <= -kLimit) {
    m = {m.x >> 1, m.y >> 1};
    d = {d.x >> 1, d.y >> 1};
    r >>= 1;
  }
  // |m + t d|^2 = r^2  <=>  a t^2 + 2 b t + c = 0.
  const I128 a = detail::dot(d, d);
  if (a == 0) return std::nullopt;
  const I128 b = detail::dot(m, d);
  const I128 c = detail::dot(m, m) - r * r;
  if (c < 0) return std::nullopt;  // origin strictly inside
  if (b > 0) return std::nullopt;  // moving away (the nearer root is behind)
  const I128 disc = b * b - a * c;
  if (disc < 0) return std::nullopt;
  // t = (-b - sqrt(disc)) / a <= 1  <=>  -b - a <= sqrt(disc); exact.
  const I128 beyond = -b - a;
  if (beyond > 0 && beyond * beyond > disc) return std::nullopt;
  const I128 root = static_cast<I128>(isqrt128_round(static_cast<U128>(disc)));
  I128 num = -b - root;
  if (num < 0) num = 0;  // the rounded root can pass -b by one unit
  if (num > a) num = a;
  const Ratio t{num, a};
  RayHit2 hit;
  hit.fraction = to_fx(t);
  hit.point = point_at(ray, t);
  hit.normal = detail::unit(detail::diff(hit.point, circle.center));
  // A point-sized circle hit dead centre has no surface direction: face the ray.
  if (is_zero(hit.normal))
    hit.normal = detail::unit({-int64_t{ray.delta.x.raw()}, -int64_t{ray.delta.y.raw()}});
  return hit;
}

std::optional<RayHit2> raycast(Ray2 ray, Segment2 segment) {
  const W2 d = detail::raw(ray.delta);
  const W2 e = detail::diff(segment.b, segment.a);
  const W2 w = detail::diff(segment.a, ray.origin);
  // origin + t d = a + u e; crossing both sides with e and with d gives t
  // and u over the same denominator. Zero means parallel (or degenerate).
  I128 den = detail::cross(d, e);
  if (den == 0) return std::nullopt;
  I128 t_num = detail::cross(w, e);
  I128 u_num = detail::cross(w, d);
  if (den < 0) {
    den = -den;
    t_num = -t_num;
    u_num = -u_num;
  }
  if (t_num < 0 || t_num > den || u_num < 0 || u_num > den) return std::nullopt;
  const Ratio t{t_num, den};
  RayHit2 hit;
  hit.fraction = to_fx(t);
  hit.point = point_at(ray, t);
  W2 n{-e.y, e.x};
  if (detail::dot(n, d) > 0) n = {-n.x, -n.y};
  hit.normal = detail::unit(n);
  return hit;
}

}  // namespace rwd::fixed
