// SPDX-License-Identifier: MIT
#include "golden_digest.h"

#include <array>
#include <cstdint>
#include <vector>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "rewind/fixed/aabb_sort.h"
#include "rewind/fixed/fx.h"
#include "rewind/fixed/fx_math.h"
#include "rewind/fixed/intersect2.h"
#include "rewind/fixed/raycast2.h"
#include "rewind/fixed/rot2.h"
#include "rewind/fixed/transform2.h"
#include "rewind/fixed/trig.h"
#include "rewind/fixed/vec2.h"
#include "splitmix.h"

namespace rwd::fixed {
namespace {

// Collects values as explicit little-endian bytes: never raw structs.
class Sink {
 public:
  Sink() { XXH3_64bits_reset(&state_); }
  void add(int64_t v) {
    unsigned char bytes[8];
    const auto u = static_cast<uint64_t>(v);
    for (int i = 0; i < 8; ++i) bytes[i] = static_cast<unsigned char>(u >> (8 * i));
    XXH3_64bits_update(&state_, bytes, sizeof bytes);
  }
  void add(Fx f) { add(int64_t{f.raw()}); }
  void add(Vec2 v) {
    add(v.x);
    add(v.y);
  }
  void add(bool b) { add(int64_t{b ? 1 : 0}); }
  void add(const std::optional<RayHit2>& hit) {
    add(hit.has_value());
    if (!hit) return;
    add(hit->fraction);
    add(hit->point);
    add(hit->normal);
  }
  uint64_t digest() const { return XXH3_64bits_digest(&state_); }

 private:
  XXH3_state_t state_;
};

// Inputs spread over every magnitude, range edges included.
Fx any(SplitMix64& rng) {
  return Fx::from_raw(rng.raw_i32() >> rng.below(32));
}
Vec2 any_vec(SplitMix64& rng) {
  return {any(rng), any(rng)};
}
// Small coordinates so the geometric tests see hits as well as misses.
Fx near(SplitMix64& rng) {
  return Fx::from_raw(static_cast<int32_t>(rng.below(20 * 65536)) - 10 * 65536);
}
Vec2 near_vec(SplitMix64& rng) {
  return {near(rng), near(rng)};
}
Aabb2 near_box(SplitMix64& rng) {
  const Vec2 a = near_vec(rng);
  const Vec2 b = near_vec(rng);
  return {{min(a.x, b.x), min(a.y, b.y)}, {max(a.x, b.x), max(a.y, b.y)}};
}

}  // namespace

uint64_t golden_digest() {
  Sink sink;
  SplitMix64 rng{0x60'1DE4};
  for (int i = 0; i < 4000; ++i) {
    const Fx a = any(rng);
    const Fx b = any(rng);
    sink.add(a + b);
    sink.add(a - b);
    sink.add(a * b);
    sink.add(a / b);
    sink.add(-a);
    sink.add(abs(b));
    sink.add(sqrt(abs(a)));
    sink.add(sqrt(FxWide::product(a, b)));
    const Result<Fx> r = checked_rsqrt(abs(b));
    sink.add(r.ok() ? *r : Fx::min());
    const SinCos sc = sin_cos(a);
    sink.add(sc.sin);
    sink.add(sc.cos);
    sink.add(atan2(a, b));
    sink.add(normalize_angle(b));
    const Vec2 u = any_vec(rng);
    const Vec2 w = any_vec(rng);
    sink.add(dot(u, w));
    sink.add(cross(u, w));
    sink.add(dot_wide(u, w).raw());
    sink.add(length(u));
    sink.add(distance(u, w));
    sink.add(normalized(w));
    const Rot2 q = Rot2::from_angle(a);
    sink.add(rotate(q, u));
    sink.add(inv_rotate(q, w));
    sink.add(apply(Transform2{w, q}, u));
  }
  for (int i = 0; i < 4000; ++i) {
    const Aabb2 box = near_box(rng);
    const Aabb2 other = near_box(rng);
    const Circle c{near_vec(rng), Fx::from_raw(static_cast<int32_t>(rng.below(4 * 65536)))};
    const Circle d{near_vec(rng), Fx::from_raw(static_cast<int32_t>(rng.below(4 * 65536)))};
    const Vec2 p = near_vec(rng);
    const Segment2 s{near_vec(rng), near_vec(rng)};
    const Segment2 t{near_vec(rng), near_vec(rng)};
    const Ray2 ray{near_vec(rng), near_vec(rng)};
    sink.add(overlaps(box, other));
    sink.add(overlaps(c, d));
    sink.add(overlaps(c, box));
    sink.add(contains(box, p));
    sink.add(contains(c, p));
    sink.add(intersects(s, t));
    const std::array<Vec2, 5> polygon = {near_vec(rng), near_vec(rng), near_vec(rng), near_vec(rng),
                                         near_vec(rng)};
    sink.add(*polygon_contains(polygon, p));
    sink.add(raycast(ray, box));
    sink.add(raycast(ray, c));
    sink.add(raycast(ray, s));
  }
  std::vector<IdAabb2> items;
  for (uint64_t i = 0; i < 64; ++i) items.push_back({rng.next(), near_box(rng)});
  if (sort_by_stable_id(items).ok()) {
    for (const IdAabb2& item : items) sink.add(static_cast<int64_t>(item.id));
  }
  return sink.digest();
}

}  // namespace rwd::fixed
