// SPDX-License-Identifier: MIT
// Scene queries and stepping in a large static level, Rewind beside Bullet in
// the same process on the same data.
//
// The level: 10,000 static boxes (SplitMix64, sizes 0.5-4 m, random
// rotations, centres over 400 m x 400 m at heights 0-40 m). Rewind builds it
// first and Bullet gets the poses and sizes Rewind kept (quantized on
// creation), so both engines hold the same solids.
//
// Query families, each iteration 1,000 queries from a fixed list:
// - Raycast/closest: World3D::raycast vs rayTest + ClosestRayResultCallback.
// - Raycast/all: World3D::raycast_all (sorted near to far) vs rayTest +
//   AllHitsRayResultCallback (unsorted: sorting is not Bullet's contract).
//   Both reuse their result storage from ray to ray.
// - ShapeCast/sphere, ShapeCast/box: World3D::shape_cast vs convexSweepTest +
//   ClosestConvexResultCallback (no allowed penetration), sweeps of 20 m
//   from free space inside the level.
// - Overlap/sphere: World3D::overlap vs contactTest with a free-standing
//   btCollisionObject. contactTest is Bullet's one-shot "what touches this
//   shape here" (broadphase box test, then the pair's algorithm per
//   candidate), which is what overlap() answers; a btPairCachingGhostObject
//   answers it only after a broadphase update per move and still needs the
//   same narrowphase, so it is the less direct equivalent. Bullet reports
//   points out to its contact threshold; only those at distance <= 0
//   (touching or overlapping, Rewind's rule) count.
// Bullet's query level gives its boxes a 1 mm collision margin instead of the
// default 4 cm: its sweeps run GJK on the shrunk box plus the margin, a box
// with edges rounded by the margin, and with 4 cm they hit 1-20 cm late near
// edges (a third of box sweeps differ by more than 1 cm), which is no longer
// the same question. Rays and overlaps do not depend on it. Bullet's tree is
// built by insertion; it gets btDbvtBroadphase::optimize() (a top-down
// rebuild) before timing, as Rewind rebuilds its query tree on the first
// query after an edit. The first query benchmark to run compares the two
// engines' answers once (not timed) and stops the run if fewer than 99% of
// any family agree (the rule is in check_agreement).
//
// Step families (stepping 200 dropped bodies with and without the level):
// query_step_bench.cpp.
//
// Built with Jolt (REWIND_JOLT_DIR), the same families run on Jolt Physics
// too: the level's boxes as Rewind kept them in a PhysicsSystem at Jolt's
// defaults (jolt_query_level.h: CastRay, CastRay with an all-hits
// collector, CastShape, CollideShape). Jolt's answers are
// checked against Rewind's like Bullet's, but a family below 99% agreement
// skips its Jolt benchmarks instead of stopping the run.
#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rewind/sim/world3d.h"

#include "query_level.h"
#include "query_step_bench.h"
#ifdef REWIND_HAVE_JOLT
#include "jolt_engine.h"
#include "jolt_query_level.h"
#endif

namespace {

using namespace rwd::bench::query_level;

// --- the agreement check --------------------------------------------------------

// Distance from `point` to the surface of level box `box` (Rewind's exact
// point query, so the yardstick is the solid both engines hold).
float surface_gap(const Level& level, int box, Vec3 point) {
  const auto hit = level.rewind.signed_distance(level.body_of_box[static_cast<size_t>(box)], point);
  return hit ? std::fabs(hit->distance) : std::numeric_limits<float>::infinity();
}

// Tallies of one family's check.
struct Tally {
  int strict = 0;    // same hit or miss, same box, distances within 1 cm
  int accepted = 0;  // strict, or within Bullet's documented tolerance (rays)
  int rewind_hits = 0;
  float largest_m = 0.0f;  // largest distance difference on the same box
};

bool strictly_same(const std::optional<Hit>& a, const std::optional<Hit>& b, Tally& t) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  if (a->box != b->box) return false;
  const float diff = std::fabs(a->distance - b->distance);
  t.largest_m = std::max(t.largest_m, diff);
  return diff <= kDistanceTolerance;
}

// Bullet's ray test against a convex shape (btSubsimplexConvexCast, its
// default) stops once the ray point is within 1 cm of the surface
// (squared distance below 1e-4), so its hit lies up to 1 cm off the surface
// along the normal (several cm along a slanting ray) and a ray passing within
// 1 cm of an edge counts as a hit. A Bullet hit is accepted when its point is
// within 1 cm of the box it names and no farther than Rewind's first hit; a
// hit Rewind finds must be found by Bullet too.
bool ray_accepted(const Level& level, const Ray& ray, const std::optional<Hit>& rewind,
                  const std::optional<Hit>& bullet) {
  if (!bullet) return !rewind;
  const Vec3 point = ray.origin + ray.direction * bullet->distance;
  if (surface_gap(level, bullet->box, point) > kDistanceTolerance) return false;
  return !rewind || bullet->distance <= rewind->distance + kDistanceTolerance;
}

double report(const char* family, const Tally& t) {
  const double accepted = static_cast<double>(t.accepted) / kQueries;
  std::fprintf(stderr,
               "query_bench: %-16s %4d/%d strictly same (hit or miss, body, distance within "
               "1 cm), %4d/%d accepted; %d hits in Rewind; largest distance difference on the "
               "same body %.1f mm\n",
               family, t.strict, kQueries, t.accepted, kQueries, t.rewind_hits,
               static_cast<double>(t.largest_m) * 1000.0);
  if (accepted < kMinAgreement) {
    std::fprintf(stderr,
                 "query_bench: %s: Rewind and Bullet agree on %.1f%% of the queries (need "
                 "%.0f%%), so they would not be doing the same work; stopping.\n",
                 family, accepted * 100.0, kMinAgreement * 100.0);
    std::exit(EXIT_FAILURE);
  }
  return accepted * 100.0;
}

void check_agreement(Level& level) {
  Tally closest;
  for (const Ray& r : level.rays) {
    const auto a = rewind_closest(level, r);
    const auto b = bullet_closest(level, r);
    closest.rewind_hits += a.has_value();
    const bool strict = strictly_same(a, b, closest);
    closest.strict += strict;
    closest.accepted += strict || ray_accepted(level, r, a, b);
  }
  level.agree_closest = report("Raycast/closest", closest);

  // Every body along the ray: each Rewind hit needs a Bullet hit on the same
  // body, and each Bullet hit must pass the closest-hit rule on its own.
  Tally all;
  std::vector<rwd::sim::RayHit> rewind_hits;
  btCollisionWorld::AllHitsRayResultCallback cb({}, {});
  for (const Ray& r : level.rays) {
    rewind_all(level, r, rewind_hits);
    bullet_all(level, r, cb);
    std::vector<Hit> x;
    std::vector<Hit> y;
    for (const auto& h : rewind_hits) x.push_back({level.box_of_index[h.body.index], h.distance});
    for (int i = 0; i < cb.m_collisionObjects.size(); ++i) {
      y.push_back({cb.m_collisionObjects[i]->getUserIndex(), cb.m_hitFractions[i] * kRayLength});
    }
    const auto by_box = [](const Hit& l, const Hit& h) { return l.box < h.box; };
    std::sort(x.begin(), x.end(), by_box);
    std::sort(y.begin(), y.end(), by_box);
    all.rewind_hits += !x.empty();
    bool strict = x.size() == y.size();
    for (size_t i = 0; strict && i < x.size(); ++i) strict = strictly_same(x[i], y[i], all);
    bool accepted = strict;
    if (!accepted) {
      accepted = true;
      for (const Hit& h : x) {
        accepted = accepted && std::binary_search(y.begin(), y.end(), h, by_box);
      }
      for (const Hit& h : y) {
        const auto same = std::lower_bound(x.begin(), x.end(), h, by_box);
        const bool in_x = same != x.end() && same->box == h.box;
        accepted =
            accepted && ray_accepted(level, r, in_x ? std::optional<Hit>(*same) : std::nullopt, h);
      }
    }
    all.strict += strict;
    all.accepted += accepted;
  }
  level.agree_all = report("Raycast/all", all);

  const auto sweeps = [&](const char* family, const Shape& shape, const btConvexShape& bt_shape,
                          const std::vector<Sweep>& list) {
    Tally t;
    for (const Sweep& s : list) {
      const auto a = rewind_sweep(level, shape, s);
      t.rewind_hits += a.has_value();
      const bool strict = strictly_same(a, bullet_sweep(level, bt_shape, s), t);
      t.strict += strict;
      t.accepted += strict;
    }
    return report(family, t);
  };
  level.agree_sphere =
      sweeps("ShapeCast/sphere", level.cast_sphere, level.bt_cast_sphere, level.sphere_sweeps);
  level.agree_box = sweeps("ShapeCast/box", level.cast_box, level.bt_cast_box, level.box_sweeps);

  Tally overlap;
  std::vector<BodyId> ids;
  OverlapCollector collector;
  for (const Vec3& c : level.overlap_centres) {
    rewind_overlap(level, c, ids);
    bullet_overlap(level, c, collector);
    std::vector<int> x;
    for (BodyId id : ids) x.push_back(level.box_of_index[id.index]);
    std::sort(x.begin(), x.end());
    std::sort(collector.boxes.begin(), collector.boxes.end());
    overlap.rewind_hits += !x.empty();
    const bool same = x == collector.boxes;
    overlap.strict += same;
    overlap.accepted += same;
  }
  level.agree_overlap = report("Overlap/sphere", overlap);
}

// Built on first use by a query benchmark, so a filter that runs only the
// step benchmarks skips it.
Level& level() {
  static std::unique_ptr<Level> instance = [] {
    auto l = std::make_unique<Level>();
    LevelIds ids = add_level(l->rewind, &l->bullet, kQueryMargin);
    l->box_of_index = std::move(ids.box_of_index);
    l->body_of_box = std::move(ids.body_of_box);
    l->bullet.broadphase.optimize();
    SplitMix64 rng{0xACE0F5BA5Eull};
    for (int i = 0; i < kQueries; ++i) {
      const Vec3 origin{rng.uniform(-200.0f, 200.0f), rng.uniform(45.0f, 60.0f),
                        rng.uniform(-200.0f, 200.0f)};
      l->rays.push_back({origin, downward_direction(rng)});
      l->overlap_centres.push_back(
          {rng.uniform(-200.0f, 200.0f), rng.uniform(0.0f, 40.0f), rng.uniform(-200.0f, 200.0f)});
    }
    l->sphere_sweeps = make_sweeps(l->rewind, l->cast_sphere, 0x5111E5ull);
    l->box_sweeps = make_sweeps(l->rewind, l->cast_box, 0xB0C5ull);
    check_agreement(*l);
    return l;
  }();
  return *instance;
}

// --- query benchmarks ---------------------------------------------------------

void finish(benchmark::State& state, size_t found, double agree_pct) {
  state.SetItemsProcessed(state.iterations() * kQueries);
  state.counters["found_per_query"] =
      static_cast<double>(found) / static_cast<double>(state.iterations() * kQueries);
  state.counters["agree_pct"] = agree_pct;
}

void raycast_closest_rewind(benchmark::State& state) {
  const Level& l = level();
  size_t found = 0;
  for (auto _ : state) {
    for (const Ray& r : l.rays) found += rewind_closest(l, r).has_value();
  }
  finish(state, found, l.agree_closest);
}
void raycast_closest_bullet(benchmark::State& state) {
  const Level& l = level();
  size_t found = 0;
  for (auto _ : state) {
    for (const Ray& r : l.rays) found += bullet_closest(l, r).has_value();
  }
  finish(state, found, l.agree_closest);
}
void raycast_all_rewind(benchmark::State& state) {
  const Level& l = level();
  std::vector<rwd::sim::RayHit> out;
  size_t found = 0;
  for (auto _ : state) {
    for (const Ray& r : l.rays) found += rewind_all(l, r, out);
  }
  finish(state, found, l.agree_all);
}
void raycast_all_bullet(benchmark::State& state) {
  const Level& l = level();
  btCollisionWorld::AllHitsRayResultCallback cb({}, {});
  size_t found = 0;
  for (auto _ : state) {
    for (const Ray& r : l.rays) found += bullet_all(l, r, cb);
  }
  finish(state, found, l.agree_all);
}
void shape_cast_rewind(benchmark::State& state, bool box) {
  const Level& l = level();
  const Shape& shape = box ? l.cast_box : l.cast_sphere;
  const std::vector<Sweep>& sweeps = box ? l.box_sweeps : l.sphere_sweeps;
  size_t found = 0;
  for (auto _ : state) {
    for (const Sweep& s : sweeps) found += rewind_sweep(l, shape, s).has_value();
  }
  finish(state, found, box ? l.agree_box : l.agree_sphere);
}
void shape_cast_bullet(benchmark::State& state, bool box) {
  const Level& l = level();
  const btConvexShape& shape =
      box ? static_cast<const btConvexShape&>(l.bt_cast_box) : l.bt_cast_sphere;
  const std::vector<Sweep>& sweeps = box ? l.box_sweeps : l.sphere_sweeps;
  size_t found = 0;
  for (auto _ : state) {
    for (const Sweep& s : sweeps) found += bullet_sweep(l, shape, s).has_value();
  }
  finish(state, found, box ? l.agree_box : l.agree_sphere);
}
void overlap_rewind(benchmark::State& state) {
  const Level& l = level();
  std::vector<BodyId> out;
  size_t found = 0;
  for (auto _ : state) {
    for (const Vec3& c : l.overlap_centres) found += rewind_overlap(l, c, out);
  }
  finish(state, found, l.agree_overlap);
}
void overlap_bullet(benchmark::State& state) {
  Level& l = level();
  OverlapCollector out;
  size_t found = 0;
  for (auto _ : state) {
    for (const Vec3& c : l.overlap_centres) found += bullet_overlap(l, c, out);
  }
  finish(state, found, l.agree_overlap);
}

#ifdef REWIND_HAVE_JOLT
// --- Jolt ---------------------------------------------------------------------

using rwd::bench::JoltLevelBox;
using rwd::bench::JoltLevelHit;
using rwd::bench::JoltQueryLevel;
using rwd::bench::kept_boxes;

struct JoltLevel {
  std::unique_ptr<JoltQueryLevel> jolt;
  double agree_closest = 0.0;
  double agree_all = 0.0;
  double agree_sphere = 0.0;
  double agree_box = 0.0;
  double agree_overlap = 0.0;
};

// Agreement with Rewind, in percent, printed like Bullet's.
double report_jolt(const char* family, const Tally& t) {
  const double agree = 100.0 * static_cast<double>(t.accepted) / kQueries;
  std::fprintf(stderr,
               "query_bench: jolt %-16s %4d/%d same as Rewind (hit or miss, body, distance "
               "within 1 cm); largest distance difference on the same body %.1f mm%s\n",
               family, t.accepted, kQueries, static_cast<double>(t.largest_m) * 1000.0,
               agree < kMinAgreement * 100.0 ? "; its Jolt benchmarks are skipped" : "");
  return agree;
}

std::optional<Hit> as_hit(const std::optional<JoltLevelHit>& h) {
  if (!h) return std::nullopt;
  return Hit{h->box, h->distance};
}

void check_jolt_agreement(Level& level, JoltLevel& j) {
  Tally closest;
  for (const Ray& r : level.rays) {
    closest.accepted +=
        strictly_same(rewind_closest(level, r),
                      as_hit(j.jolt->closest(r.origin, r.direction, kRayLength)), closest);
  }
  j.agree_closest = report_jolt("Raycast/closest", closest);

  Tally all;
  std::vector<rwd::sim::RayHit> rewind_hits;
  std::vector<JoltLevelHit> jolt_hits;
  const auto by_box = [](const Hit& l, const Hit& h) { return l.box < h.box; };
  for (const Ray& r : level.rays) {
    rewind_all(level, r, rewind_hits);
    j.jolt->all(r.origin, r.direction, kRayLength, jolt_hits);
    std::vector<Hit> x;
    std::vector<Hit> y;
    for (const auto& h : rewind_hits) x.push_back({level.box_of_index[h.body.index], h.distance});
    for (const auto& h : jolt_hits) y.push_back({h.box, h.distance});
    std::sort(x.begin(), x.end(), by_box);
    std::sort(y.begin(), y.end(), by_box);
    bool same = x.size() == y.size();
    for (size_t i = 0; same && i < x.size(); ++i) same = strictly_same(x[i], y[i], all);
    all.accepted += same;
  }
  j.agree_all = report_jolt("Raycast/all", all);

  const auto sweeps = [&](const char* family, const Shape& shape, const std::vector<Sweep>& list) {
    Tally t;
    for (const Sweep& s : list) {
      t.accepted +=
          strictly_same(rewind_sweep(level, shape, s),
                        as_hit(j.jolt->cast(shape, s.origin, s.rotation, s.translation)), t);
    }
    return report_jolt(family, t);
  };
  j.agree_sphere = sweeps("ShapeCast/sphere", level.cast_sphere, level.sphere_sweeps);
  j.agree_box = sweeps("ShapeCast/box", level.cast_box, level.box_sweeps);

  Tally overlap;
  std::vector<BodyId> ids;
  std::vector<int> boxes;
  for (const Vec3& c : level.overlap_centres) {
    rewind_overlap(level, c, ids);
    j.jolt->overlap(c, kOverlapRadius, boxes);
    std::vector<int> x;
    for (BodyId id : ids) x.push_back(level.box_of_index[id.index]);
    std::sort(x.begin(), x.end());
    std::sort(boxes.begin(), boxes.end());
    overlap.accepted += x == boxes;
  }
  j.agree_overlap = report_jolt("Overlap/sphere", overlap);
}

JoltLevel& jolt_level() {
  static std::unique_ptr<JoltLevel> instance = [] {
    Level& l = level();
    auto j = std::make_unique<JoltLevel>();
    j->jolt = std::make_unique<JoltQueryLevel>(kept_boxes(l.rewind, l.body_of_box));
    check_jolt_agreement(l, *j);
    return j;
  }();
  return *instance;
}

// False (and the benchmark skipped) when Jolt answers a family differently.
bool jolt_agrees(benchmark::State& state, double agree_pct) {
  if (agree_pct >= kMinAgreement * 100.0) return true;
  state.SkipWithError("Jolt disagrees with Rewind on this family (see stderr)");
  return false;
}

void raycast_closest_jolt(benchmark::State& state) {
  JoltLevel& j = jolt_level();
  if (!jolt_agrees(state, j.agree_closest)) return;
  const Level& l = level();
  size_t found = 0;
  for (auto _ : state) {
    for (const Ray& r : l.rays)
      found += j.jolt->closest(r.origin, r.direction, kRayLength).has_value();
  }
  finish(state, found, j.agree_closest);
}
void raycast_all_jolt(benchmark::State& state) {
  JoltLevel& j = jolt_level();
  if (!jolt_agrees(state, j.agree_all)) return;
  const Level& l = level();
  std::vector<JoltLevelHit> out;
  size_t found = 0;
  for (auto _ : state) {
    for (const Ray& r : l.rays) found += j.jolt->all(r.origin, r.direction, kRayLength, out);
  }
  finish(state, found, j.agree_all);
}
void shape_cast_jolt(benchmark::State& state, bool box) {
  JoltLevel& j = jolt_level();
  const double agree = box ? j.agree_box : j.agree_sphere;
  if (!jolt_agrees(state, agree)) return;
  const Level& l = level();
  const Shape& shape = box ? l.cast_box : l.cast_sphere;
  const std::vector<Sweep>& sweeps = box ? l.box_sweeps : l.sphere_sweeps;
  size_t found = 0;
  for (auto _ : state) {
    for (const Sweep& s : sweeps) {
      found += j.jolt->cast(shape, s.origin, s.rotation, s.translation).has_value();
    }
  }
  finish(state, found, agree);
}
void overlap_jolt(benchmark::State& state) {
  JoltLevel& j = jolt_level();
  if (!jolt_agrees(state, j.agree_overlap)) return;
  const Level& l = level();
  std::vector<int> out;
  size_t found = 0;
  for (auto _ : state) {
    for (const Vec3& c : l.overlap_centres) found += j.jolt->overlap(c, kOverlapRadius, out);
  }
  finish(state, found, j.agree_overlap);
}
#endif

void register_all() {
  using benchmark::RegisterBenchmark;
  for (auto* b : {
           RegisterBenchmark("Raycast/closest/Rewind", raycast_closest_rewind),
           RegisterBenchmark("Raycast/closest/Bullet", raycast_closest_bullet),
           RegisterBenchmark("Raycast/all/Rewind", raycast_all_rewind),
           RegisterBenchmark("Raycast/all/Bullet", raycast_all_bullet),
           RegisterBenchmark("ShapeCast/sphere/Rewind", shape_cast_rewind, false),
           RegisterBenchmark("ShapeCast/sphere/Bullet", shape_cast_bullet, false),
           RegisterBenchmark("ShapeCast/box/Rewind", shape_cast_rewind, true),
           RegisterBenchmark("ShapeCast/box/Bullet", shape_cast_bullet, true),
           RegisterBenchmark("Overlap/sphere/Rewind", overlap_rewind),
           RegisterBenchmark("Overlap/sphere/Bullet", overlap_bullet),
       }) {
    b->Unit(benchmark::kMicrosecond);  // per iteration of 1,000 queries
  }
#ifdef REWIND_HAVE_JOLT
  for (auto* b : {
           RegisterBenchmark("Raycast/closest/Jolt", raycast_closest_jolt),
           RegisterBenchmark("Raycast/all/Jolt", raycast_all_jolt),
           RegisterBenchmark("ShapeCast/sphere/Jolt", shape_cast_jolt, false),
           RegisterBenchmark("ShapeCast/box/Jolt", shape_cast_jolt, true),
           RegisterBenchmark("Overlap/sphere/Jolt", overlap_jolt),
       }) {
    b->Unit(benchmark::kMicrosecond);
  }
#endif
  register_step_benchmarks();
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
