// SPDX-License-Identifier: MIT
// Colouring and packing the contact constraints into batches of eight
// (contact_batches.h), and running the solver's lane passes
// (contact_lanes.h) over them: eight AVX lanes per batch where the processor
// has them (contact_lanes_avx.cpp), else four lanes over each half.
#include "d3/contact_batches.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstring>

#include "d3/contact_lane_access.h"
#include "d3/contact_lanes.h"
#include "d3/step_threads.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

// Batches of at most this many constraints run one lane at a time.
constexpr uint32_t kOneLaneMax = 2;
bool one_lane(const ContactBatch& b) {
  return b.lanes_used <= kOneLaneMax;
}

bool use_eight_lanes() {
#if defined(REWIND_LANES_AVX)
  static const bool available = lanes8_available();
  return available;
#else
  return false;
#endif
}

// --- colouring ---------------------------------------------------------

// Sets the colour of every constraint; kColorCount for those that fit none.
void color(WorldScratch& scratch) {
  const size_t words = (scratch.solver_bodies.size() + 63) / 64;
  scratch.color_bits.assign(words * kColorCount, 0);
  scratch.color_of.resize(scratch.constraints.size());
  for (size_t k = 0; k < scratch.constraints.size(); ++k) {
    const ContactConstraint& c = scratch.constraints[k];
    const bool movable_a = scratch.solver_bodies[c.body_a].inv_mass != 0.0f;
    const bool movable_b = scratch.solver_bodies[c.body_b].inv_mass != 0.0f;
    scratch.color_of[k] =
        take_color(scratch.color_bits.data(), words, c.body_a, movable_a, c.body_b, movable_b);
  }
}

// Zeroes what the passes of a batch of `bound` points read: every field
// but the points from `bound` on.
void clear_batch(ContactBatch& batch, uint32_t bound) {
  auto* bytes = reinterpret_cast<unsigned char*>(&batch);
  const size_t points = offsetof(ContactBatch, points);
  const size_t coupling = offsetof(ContactBatch, coupling);
  std::memset(bytes, 0, points + bound * sizeof(ContactBatch::Point));
  std::memset(bytes + coupling, 0, sizeof(ContactBatch) - coupling);
}

// Packs constraint `index` into a lane: ids, axes, anchors and impulses.
// The quantities derived from them (inverse-inertia products, masses, the
// normal K matrix) are computed for all lanes at once by prepare_lanes.
void fill_lane(ContactBatch& batch, int lane, uint32_t index, const ContactConstraint& c,
               const std::vector<SolverBody>& bodies) {
  batch.constraint[lane] = index;
  batch.body_a[lane] = c.body_a;
  batch.body_b[lane] = c.body_b;
  batch.movable_a[lane] = bodies[c.body_a].inv_mass != 0.0f ? 1 : 0;
  batch.movable_b[lane] = bodies[c.body_b].inv_mass != 0.0f ? 1 : 0;
  batch.point_count[lane] = static_cast<float>(c.point_count);
  const Vec3 axes[3] = {c.normal, c.tangent1, c.tangent2};
  float(*dst[3])[kBatchLanes] = {batch.normal, batch.tangent1, batch.tangent2};
  for (int a = 0; a < 3; ++a) {
    dst[a][0][lane] = axes[a].x;
    dst[a][1][lane] = axes[a].y;
    dst[a][2][lane] = axes[a].z;
  }
  batch.overlapping = static_cast<uint8_t>(batch.overlapping | c.overlapping);
  batch.friction[lane] = c.friction;
  batch.push_rate[lane] = c.softness.bias_rate;
  batch.push_mass_scale[lane] = c.softness.mass_scale;
  for (uint32_t p = 0; p < c.point_count; ++p) {
    const ConstraintPoint& cp = c.points[p];
    ContactBatch::Point& bp = batch.points[p];
    bp.anchor_a[0][lane] = cp.anchor_a.x;
    bp.anchor_a[1][lane] = cp.anchor_a.y;
    bp.anchor_a[2][lane] = cp.anchor_a.z;
    bp.anchor_b[0][lane] = cp.anchor_b.x;
    bp.anchor_b[1][lane] = cp.anchor_b.y;
    bp.anchor_b[2][lane] = cp.anchor_b.z;
    bp.base_separation[lane] = cp.base_separation;
    bp.separation[lane] = cp.separation;
    bp.normal_impulse[lane] = cp.normal_impulse;
    bp.tangent_impulse1[lane] = cp.tangent_impulse1;
    bp.tangent_impulse2[lane] = cp.tangent_impulse2;
    bp.max_normal_impulse[lane] = cp.max_normal_impulse;
    // The tick's impulse is what each substep applied: the warm starts of
    // substeps 2..n, and the last substep's at the end (unpack_batches).
    // The first warm start applies last tick's last substep again, so it is
    // taken back here.
    bp.tick_normal_impulse[lane] = -cp.normal_impulse;
    bp.push_impulse[lane] = 0.0f;
  }
}

// Calls fn(lane, constraint) for each lane in [first, first + count) of a
// batch that holds a constraint.
template <class Fn>
void for_each_packed(WorldScratch& scratch, const ContactBatch& batch, Fn fn, int first = 0,
                     int count = kBatchLanes) {
  for (int lane = first; lane < first + count; ++lane) {
    if (batch.constraint[lane] == kNoConstraint) continue;
    fn(lane, scratch.constraints[batch.constraint[lane]]);
  }
}

// The normal K matrix and masses, computed in the lanes, back to the scalar
// constraints for the push-out and restitution.
void copy_back_masses(WorldScratch& scratch) {
  for (const ContactBatch& batch : scratch.batches) {
    for_each_packed(scratch, batch, [&](int lane, ContactConstraint& c) {
      for (uint32_t i = 0; i < c.point_count; ++i) {
        for (uint32_t j = 0; j < c.point_count; ++j) c.coupling[i][j] = batch.coupling[i][j][lane];
        c.points[i].normal_mass = batch.points[i].normal_mass[lane];
      }
    });
  }
}

// The four-lane passes over half a batch, for the batch's point bound.
void prepare_half(const HalfBatch& h, const std::vector<SolverBody>& bodies) {
  for_point_bound(*h.batch, [&](auto n) { prepare_lanes<decltype(n)::value>(h, bodies); });
}
void warm_start_half(const HalfBatch& h, std::vector<SolverBody>& bodies) {
  for_point_bound(*h.batch, [&](auto n) { warm_start_lanes<decltype(n)::value>(h, bodies); });
}
void solve_half(const HalfBatch& h, std::vector<SolverBody>& bodies, float inv_h) {
  for_point_bound(*h.batch, [&](auto n) { solve_lanes<decltype(n)::value>(h, bodies, inv_h); });
}
// Both halves of a batch whose upper half holds a constraint, interleaved.
void solve_halves(ContactBatch& b, std::vector<SolverBody>& bodies, float inv_h) {
  for_point_bound(b, [&](auto n) {
    solve_lanes_pair<decltype(n)::value>(HalfBatch{&b, 0}, HalfBatch{&b, kLanes}, bodies, inv_h);
  });
}
void separations_half(const HalfBatch& h, const std::vector<SolverBody>& bodies) {
  for_point_bound(*h.batch, [&](auto n) { separations_lanes<decltype(n)::value>(h, bodies); });
}
void push_half(const HalfBatch& h, std::vector<SolverBody>& bodies, const PushSettings& push) {
  for_point_bound(*h.batch, [&](auto n) { push_lanes<decltype(n)::value>(h, bodies, push); });
}

// The passes on one lane, for the batch's point bound.
void prepare_one(const OneLane& l, const std::vector<SolverBody>& bodies) {
  for_point_bound(*l.batch, [&](auto n) { prepare_lanes<decltype(n)::value>(l, bodies); });
}
void warm_start_one(const OneLane& l, std::vector<SolverBody>& bodies) {
  for_point_bound(*l.batch, [&](auto n) { warm_start_lanes<decltype(n)::value>(l, bodies); });
}
void solve_one(const OneLane& l, std::vector<SolverBody>& bodies, float inv_h) {
  for_point_bound(*l.batch, [&](auto n) { solve_lanes<decltype(n)::value>(l, bodies, inv_h); });
}
void separations_one(const OneLane& l, const std::vector<SolverBody>& bodies) {
  for_point_bound(*l.batch, [&](auto n) { separations_lanes<decltype(n)::value>(l, bodies); });
}
void push_one(const OneLane& l, std::vector<SolverBody>& bodies, const PushSettings& push) {
  for_point_bound(*l.batch, [&](auto n) { push_lanes<decltype(n)::value>(l, bodies, push); });
}
// Each used lane of a batch in turn (they share no movable body, so the
// order is no matter).
template <class Fn>
void for_each_lane(ContactBatch& b, Fn fn) {
  for (int lane = 0; lane < b.lanes_used; ++lane) fn(OneLane{&b, lane});
}

#if !defined(REWIND_LANES_AVX)
// Without AVX in the build the eight-lane passes never run; these keep
// for_batches' callers whole and would take the two halves in turn.
void prepare_full(ContactBatch& b, const std::vector<SolverBody>& bodies) {
  prepare_half(HalfBatch{&b, 0}, bodies);
  prepare_half(HalfBatch{&b, kLanes}, bodies);
}
void warm_start_full(ContactBatch& b, std::vector<SolverBody>& bodies) {
  warm_start_half(HalfBatch{&b, 0}, bodies);
  warm_start_half(HalfBatch{&b, kLanes}, bodies);
}
void solve_full(ContactBatch& b, std::vector<SolverBody>& bodies, float inv_h) {
  solve_half(HalfBatch{&b, 0}, bodies, inv_h);
  solve_half(HalfBatch{&b, kLanes}, bodies, inv_h);
}
void solve_full_pair(ContactBatch& first, ContactBatch& second, std::vector<SolverBody>& bodies,
                     float inv_h) {
  solve_full(first, bodies, inv_h);
  solve_full(second, bodies, inv_h);
}
void separations_full(ContactBatch& b, const std::vector<SolverBody>& bodies) {
  separations_half(HalfBatch{&b, 0}, bodies);
  separations_half(HalfBatch{&b, kLanes}, bodies);
}
void push_full(ContactBatch& b, std::vector<SolverBody>& bodies, const PushSettings& push) {
  push_half(HalfBatch{&b, 0}, bodies, push);
  push_half(HalfBatch{&b, kLanes}, bodies, push);
}
#endif

// Runs a pass on every batch, colour by colour (for_colors): `one` on each
// lane of a batch of one or two constraints (the overflow's batches, which
// hold one each, among them), else `full` (eight AVX lanes) where the
// processor has AVX, else `half` on each half that holds a constraint.
template <class One, class Full, class Half>
void for_batches(WorldScratch& scratch, One one, Full full, Half half) {
  std::vector<ContactBatch>& batches = scratch.batches;
  const bool eight = use_eight_lanes();
  const uint32_t colored_end = scratch.batch_start[kColorCount];
  for_colors(scratch, [&](uint32_t first, uint32_t last) {
    for (uint32_t k = first; k < last; ++k) {
      ContactBatch& b = batches[k];
      if (one_lane(b)) {
        for_each_lane(b, one);
        continue;
      }
      if (eight && k < colored_end) {
        full(b);
        continue;
      }
      half(HalfBatch{&b, 0});
      if (b.constraint[kLanes] != kNoConstraint) half(HalfBatch{&b, kLanes});
    }
  });
}

}  // namespace

namespace {

// Constraints by colour and, within a colour, by point count, most first,
// stable (constraint order within a bucket), into scratch.colored, with
// each colour's first position in scratch.color_start; the overflow last,
// in constraint order (its constraints share bodies, so their order
// matters). Order within a colour never changes a result.
constexpr uint32_t kSizes = kMaxManifoldPoints;
constexpr uint32_t kBuckets = kColorCount * kSizes + 1;
// Up to this many constraints are sorted by insertion: a small world's
// few contacts would otherwise pay for a table of every bucket, zeroed
// and summed each step.
constexpr uint32_t kInsertionSortMax = 16;

void sort_by_color(WorldScratch& scratch) {
  const uint32_t count = static_cast<uint32_t>(scratch.constraints.size());
  const auto bucket_of = [&](uint32_t k) {
    const uint32_t col = scratch.color_of[k];
    if (col == kColorCount) return kBuckets - 1;
    return col * kSizes + (kSizes - scratch.constraints[k].point_count);
  };
  scratch.color_start.resize(kColorCount + 2);
  scratch.colored.resize(count);
  if (count <= kInsertionSortMax) {
    uint32_t keys[kInsertionSortMax];
    for (uint32_t k = 0; k < count; ++k) {
      const uint32_t key = bucket_of(k);
      uint32_t at = k;
      for (; at > 0 && keys[at - 1] > key; --at) {
        keys[at] = keys[at - 1];
        scratch.colored[at] = scratch.colored[at - 1];
      }
      keys[at] = key;
      scratch.colored[at] = k;
    }
    // Colour col starts at the first key of bucket col * kSizes or later;
    // the overflow's bucket is kColorCount * kSizes.
    uint32_t at = 0;
    for (uint32_t col = 0; col <= kColorCount; ++col) {
      while (at < count && keys[at] < col * kSizes) ++at;
      scratch.color_start[col] = at;
    }
    scratch.color_start[kColorCount + 1] = count;
    return;
  }
  std::vector<uint32_t>& fill = scratch.color_fill;
  fill.assign(kBuckets + 1, 0);
  for (uint32_t k = 0; k < count; ++k) ++fill[bucket_of(k) + 1];
  for (uint32_t b = 0; b < kBuckets; ++b) fill[b + 1] += fill[b];
  for (uint32_t col = 0; col < kColorCount; ++col) scratch.color_start[col] = fill[col * kSizes];
  scratch.color_start[kColorCount] = fill[kBuckets - 1];
  scratch.color_start[kColorCount + 1] = count;
  for (uint32_t k = 0; k < count; ++k) scratch.colored[fill[bucket_of(k)]++] = k;
}

}  // namespace

void build_batches(WorldScratch& scratch) {
  color(scratch);
  sort_by_color(scratch);

  // Batches of eight within a colour; overflow constraints one per batch.
  scratch.batches.clear();
  scratch.batch_start.resize(kColorCount + 2);  // every entry is set below
  for (uint32_t col = 0; col <= kColorCount; ++col) {
    scratch.batch_start[col] = static_cast<uint32_t>(scratch.batches.size());
    const uint32_t begin = scratch.color_start[col];
    const uint32_t end = scratch.color_start[col + 1];
    const uint32_t per_batch = col == kColorCount ? 1 : kBatchLanes;
    for (uint32_t first = begin; first < end; first += per_batch) {
      // Zeroed where the passes read: an empty lane, and the points past a
      // manifold's count, are all zeros (prepare_lanes keeps what it
      // derives for them at zero too); points past the batch's bound are
      // never read.
      uint32_t bound = 1;
      for (uint32_t at = first; at < std::min(first + per_batch, end); ++at) {
        bound = std::max(bound, scratch.constraints[scratch.colored[at]].point_count);
      }
      ContactBatch& batch = scratch.batches.emplace_back();
      clear_batch(batch, bound);
      batch.point_bound = 1;
      batch.lanes_used = static_cast<uint8_t>(std::min(per_batch, end - first));
      for (uint32_t lane = 0; lane < kBatchLanes; ++lane) {
        const uint32_t at = first + lane;
        if (lane < per_batch && at < end) {
          const uint32_t index = scratch.colored[at];
          scratch.constraints[index].batch = static_cast<uint32_t>(scratch.batches.size() - 1);
          scratch.constraints[index].lane = lane;
          fill_lane(batch, static_cast<int>(lane), index, scratch.constraints[index],
                    scratch.solver_bodies);
          batch.point_bound = std::max(batch.point_bound, scratch.constraints[index].point_count);
        } else {
          batch.constraint[lane] = kNoConstraint;
        }
      }
    }
  }
  scratch.batch_start[kColorCount + 1] = static_cast<uint32_t>(scratch.batches.size());
  const std::vector<SolverBody>& bodies = scratch.solver_bodies;
  for_batches(
      scratch, [&](const OneLane& l) { prepare_one(l, bodies); },
      [&](ContactBatch& b) { prepare_full(b, bodies); },
      [&](const HalfBatch& h) { prepare_half(h, bodies); });
  copy_back_masses(scratch);
}

void warm_start_batches(WorldScratch& scratch) {
  std::vector<SolverBody>& bodies = scratch.solver_bodies;
  for_batches(
      scratch, [&](const OneLane& l) { warm_start_one(l, bodies); },
      [&](ContactBatch& b) { warm_start_full(b, bodies); },
      [&](const HalfBatch& h) { warm_start_half(h, bodies); });
}

namespace {

// The real-velocity pass over every batch in order, two at a time where
// the order allows: `each(b)` runs first on every batch (the separation
// update, or nothing), then the solve, on consecutive batches of one colour
// with the same point bound as a pair (eight lanes), else on a batch's two
// halves as a pair (four lanes). Batches of one colour share no movable
// body, so the pairs give the results of the batches one after the other.
template <class Each>
void solve_pass(WorldScratch& scratch, float inv_h, Each each) {
  std::vector<ContactBatch>& batches = scratch.batches;
  std::vector<SolverBody>& bodies = scratch.solver_bodies;
  const bool eight = use_eight_lanes();
  const uint32_t colored_end = scratch.batch_start[kColorCount];
  for_colors(scratch, [&](uint32_t first, uint32_t last) {
    uint32_t color = 0;
    for (uint32_t k = first; k < last; ++k) {
      ContactBatch& b = batches[k];
      if (one_lane(b)) {
        each(b);
        for_each_lane(b, [&](const OneLane& l) { solve_one(l, bodies, inv_h); });
        continue;
      }
      if (eight && k < colored_end) {
        // Pairs never span two colours (nor two ranges of one).
        while (scratch.batch_start[color + 1] <= k) ++color;
        const uint32_t end = std::min(last, scratch.batch_start[color + 1]);
        const bool pair =
            k + 1 < end && batches[k + 1].point_bound == b.point_bound && !one_lane(batches[k + 1]);
        each(b);
        if (!pair) {
          solve_full(b, bodies, inv_h);
          continue;
        }
        each(batches[k + 1]);
        solve_full_pair(b, batches[k + 1], bodies, inv_h);
        ++k;
        continue;
      }
      each(b);
      if (b.constraint[kLanes] != kNoConstraint) {
        solve_halves(b, bodies, inv_h);
      } else {
        solve_half(HalfBatch{&b, 0}, bodies, inv_h);
      }
    }
  });
}

}  // namespace

void solve_batches(WorldScratch& scratch, float inv_h) {
  solve_pass(scratch, inv_h, [](ContactBatch&) {});
}

namespace {

// The separations of lanes [first, first + count) of a batch, as the lanes
// computed them, back to their scalar constraints (the push-out reads
// those); notes in scratch.overlapping whether any point overlaps past the
// slop.
void copy_back_separations(WorldScratch& scratch, float slop, ContactBatch& batch, int first = 0,
                           int count = kBatchLanes) {
  bool overlapping = false;
  bool deep = false;
  const float deep_limit = -kDeepOverlapSlops * slop;
  for_each_packed(
      scratch, batch,
      [&](int lane, ContactConstraint& c) {
        for (uint32_t p = 0; p < c.point_count; ++p) {
          const float separation = batch.points[p].separation[lane];
          c.points[p].separation = separation;
          overlapping = overlapping || separation + slop < 0.0f;
          deep = deep || separation + slop < deep_limit;
        }
      },
      first, count);
  // Batches of a colour run at the same time on the step's threads. A flag
  // already set is only read: the scratch's line with it holds the vectors
  // every batch reads, and a write from each thread would pass that line
  // back and forth between the cores. (The compiler's atomic builtins
  // rather than std::atomic_ref, which Emscripten's standard library does
  // not have yet.)
  const auto raise = [](bool& flag) {
    if (!__atomic_load_n(&flag, __ATOMIC_RELAXED)) __atomic_store_n(&flag, true, __ATOMIC_RELAXED);
  };
  if (overlapping) raise(scratch.overlapping);
  if (deep) raise(scratch.deep_overlap);
  // The first lanes start the batch's flag, an upper half adds to it.
  if (first == 0) batch.overlapping = 0;
  if (overlapping) batch.overlapping = 1;
}

}  // namespace

void push_batches(WorldScratch& scratch, const WorldConfig& config, float inv_h) {
  std::vector<SolverBody>& bodies = scratch.solver_bodies;
  const PushSettings push{inv_h, config.linear_slop_m, config.contact_push_max_mps,
                          -kDeepOverlapSlops * config.linear_slop_m};
  // A lane pushes only when it overlaps or one of its bodies already moves
  // on push velocities; a batch with neither (decided for the whole batch
  // before either half runs, so every lane width skips the same batches)
  // would change nothing and is skipped.
  const auto idle = [&](const ContactBatch& b) {
    if (b.overlapping != 0) return false;
    for (int lane = 0; lane < kBatchLanes; ++lane) {
      if (bodies[b.body_a[lane]].pushed != 0.0f || bodies[b.body_b[lane]].pushed != 0.0f) {
        return false;
      }
    }
    return true;
  };
  for_batches(
      scratch,
      [&](const OneLane& l) {
        // As for the upper half below: a lane's push only marks bodies, so
        // a batch busy before its first lane is busy after it.
        if (!idle(*l.batch)) push_one(l, bodies, push);
      },
      [&](ContactBatch& b) {
        if (!idle(b)) push_full(b, bodies, push);
      },
      [&](const HalfBatch& h) {
        // Asked again for the upper half, the answer is the same: pushing
        // only ever marks bodies, so a batch busy before its lower half is
        // busy after it, and an idle one had its lower half skipped.
        if (!idle(*h.batch)) push_half(h, bodies, push);
      });
}

namespace {

// The separation update, and when `relax` is set the relax pass fused into
// it, batch by batch.
void separation_pass(WorldScratch& scratch, float slop, bool relax, float inv_h) {
  std::vector<SolverBody>& bodies = scratch.solver_bodies;
  scratch.overlapping = false;
  scratch.deep_overlap = false;
  // A batch's separations depend only on its bodies' motion so far, which
  // the relax pass (velocities only) does not change.
  const bool eight = use_eight_lanes();
  const uint32_t colored_end = scratch.batch_start[kColorCount];
  const auto separations = [&](ContactBatch& b) {
    const uint32_t k = static_cast<uint32_t>(&b - scratch.batches.data());
    if (one_lane(b)) {
      for_each_lane(b, [&](const OneLane& l) {
        separations_one(l, bodies);
        copy_back_separations(scratch, slop, b, l.lane, 1);
      });
      return;
    }
    if (eight && k < colored_end) {
      separations_full(b, bodies);
      copy_back_separations(scratch, slop, b);
      return;
    }
    separations_half(HalfBatch{&b, 0}, bodies);
    copy_back_separations(scratch, slop, b, 0, kLanes);
    if (b.constraint[kLanes] == kNoConstraint) return;
    separations_half(HalfBatch{&b, kLanes}, bodies);
    copy_back_separations(scratch, slop, b, kLanes, kLanes);
  };
  if (relax) {
    solve_pass(scratch, inv_h, separations);
  } else {
    for_colors(scratch, [&](uint32_t first, uint32_t last) {
      for (uint32_t k = first; k < last; ++k) separations(scratch.batches[k]);
    });
  }
}

}  // namespace

void update_separations(WorldScratch& scratch, float slop) {
  separation_pass(scratch, slop, false, 0.0f);
}

void update_separations_and_relax(WorldScratch& scratch, float slop, float inv_h) {
  separation_pass(scratch, slop, true, inv_h);
}

void unpack_batches(WorldScratch& scratch) {
  for (const ContactBatch& batch : scratch.batches) {
    for_each_packed(scratch, batch, [&](int lane, ContactConstraint& c) {
      for (uint32_t p = 0; p < c.point_count; ++p) {
        const ContactBatch::Point& bp = batch.points[p];
        ConstraintPoint& cp = c.points[p];
        cp.normal_impulse = bp.normal_impulse[lane];
        cp.tangent_impulse1 = bp.tangent_impulse1[lane];
        cp.tangent_impulse2 = bp.tangent_impulse2[lane];
        cp.max_normal_impulse = bp.max_normal_impulse[lane];
        cp.tick_normal_impulse = bp.tick_normal_impulse[lane] + bp.normal_impulse[lane];
      }
    });
  }
}

}  // namespace rwd::sim::d3
