// SPDX-License-Identifier: MIT
#pragma once
// The contact constraints of a step, coloured and packed eight to a batch
// for the solver's wide passes (contact_batches.cpp).
//
// Colouring (as Box2D v3's constraint graph): each constraint takes the
// first of kColorCount colours in which neither of its movable bodies has a
// constraint yet (static, sleeping and kinematic bodies never block: the
// solver does not change their velocities). Constraints of one colour share
// no movable body, so they can be solved in any order, four or eight at a
// time, with the same result; the colours are solved one after another, constraints
// that found no colour last, one per batch. The order depends only on the
// constraint list, never on the lane count or the instruction set.
#include <cstddef>
#include <cstdint>

#include "d3/wide_float.h"
#include "rewind/core/detail/take_color.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim {
class WorldScratch;
}

namespace rwd::sim::d3 {

inline constexpr uint32_t kColorCount = 24;

/// The first colour in which neither solver body a nor b (each only if it
/// can move) is taken yet, marking them taken in it; kColorCount when every
/// colour has one of them (rewind/core/detail/take_color.h). `bits` holds
/// kColorCount runs of `words` words, one bit per solver body.
inline uint32_t take_color(uint64_t* bits, size_t words, uint32_t a, bool movable_a, uint32_t b,
                           bool movable_b) {
  return detail::take_color(bits, words, kColorCount, a, movable_a, b, movable_b);
}
/// Gauss-Seidel sweeps over a manifold's normal system per pass: enough for
/// four points on a face to agree (one sweep is the usual sequential
/// impulse, which leaves the body turning toward the last point solved; a
/// tall stack of such tilts never settles and walks off its base).
inline constexpr int kManifoldSweeps = 4;
/// An overlap deeper than this many linear slops past the slop is pushed out
/// from the ground up, one contact at a time (support_order.cpp); shallower
/// ones are pushed out in the lanes.
inline constexpr float kDeepOverlapSlops = 4.0f;
/// The constraint of an empty lane.
inline constexpr uint32_t kNoConstraint = 0xFFFFFFFFu;
/// Constraints per batch: one AVX register of lanes, or two of SSE2/NEON
/// (the four-lane passes take a batch in two halves). Lanes are filled
/// from the first, so a batch whose upper half is empty can skip it.
inline constexpr int kBatchLanes = 2 * kLanes;

/// Eight contact constraints, structure of arrays: [component][lane] or
/// [point][lane]. Points past a manifold's count (and empty lanes) have
/// zero masses and couplings, so the same arithmetic leaves them at zero.
struct alignas(32) ContactBatch {
  /// Left uninitialised: build_batches zeroes only the parts a batch of its
  /// point bound uses (clear_batch), half a batch or less for one-point
  /// manifolds, which small worlds step many times a tick.
  ContactBatch() {}  // NOLINT(modernize-use-equals-default): = default would zero it
  uint32_t constraint[kBatchLanes];  ///< index into scratch.constraints, or kNoConstraint
  uint32_t body_a[kBatchLanes];      ///< solver body (0, the immovable body, for empty lanes)
  uint32_t body_b[kBatchLanes];
  float point_count[kBatchLanes];  ///< the manifold's points (0 for an empty lane)
  float normal[3][kBatchLanes];
  float tangent1[3][kBatchLanes];
  float tangent2[3][kBatchLanes];
  float friction[kBatchLanes];
  float push_rate[kBatchLanes];        ///< the softness's bias rate, 1/s
  float push_mass_scale[kBatchLanes];  ///< the softness's mass scale
  struct Point {
    // The Jacobian's angular parts (anchor x axis) are derived in
    // registers from the anchors and axes, as the scalar code computes
    // them; what a unit impulse along them does to each body's angular
    // velocity (inverse inertia times them) is kept for the step, since
    // deriving it would need each body's inertia gathered on every pass.
    float anchor_a[3][kBatchLanes];
    float anchor_b[3][kBatchLanes];
    float in_a[3][kBatchLanes];
    float in_b[3][kBatchLanes];
    float it1_a[3][kBatchLanes];
    float it1_b[3][kBatchLanes];
    float it2_a[3][kBatchLanes];
    float it2_b[3][kBatchLanes];
    float base_separation[kBatchLanes];
    float separation[kBatchLanes];
    float normal_mass[kBatchLanes];
    float tangent_mass1[kBatchLanes];
    float tangent_mass2[kBatchLanes];
    float normal_impulse[kBatchLanes];
    float tangent_impulse1[kBatchLanes];
    float tangent_impulse2[kBatchLanes];
    float max_normal_impulse[kBatchLanes];
    /// The normal impulse the tick's substeps applied so far: the warm
    /// starts of substeps 2..n (less the first's, last tick's), completed
    /// with the last substep's when unpacked (events, rolling resistance).
    float tick_normal_impulse[kBatchLanes];
    float push_impulse[kBatchLanes];  ///< accumulated push-out impulse of this tick
  } points[kMaxManifoldPoints];
  float coupling[kMaxManifoldPoints][kMaxManifoldPoints][kBatchLanes];
  /// 1 where the lane's body can move (the passes write back only those).
  /// Last, so every float field above stays 32-byte aligned.
  uint8_t movable_a[kBatchLanes];
  uint8_t movable_b[kBatchLanes];
  /// 1 when a point of some lane overlaps past the slop, as of the last
  /// separation update: a batch without one whose bodies are not being
  /// pushed has nothing to push out.
  uint8_t overlapping;
  /// Lanes holding a constraint; they are the first ones.
  uint8_t lanes_used;
  /// The most points any lane holds (1 to kMaxManifoldPoints): the passes
  /// run that many. Constraints are packed by point count within a colour,
  /// so most batches are full of manifolds of one size.
  uint32_t point_bound;
};
// The eight-lane passes load and store every float field with aligned
// 32-byte accesses.
static_assert(offsetof(ContactBatch, normal) % 32 == 0 &&
              offsetof(ContactBatch, points) % 32 == 0 && sizeof(ContactBatch::Point) % 32 == 0 &&
              offsetof(ContactBatch, coupling) % 32 == 0);

/// What the lanes' push-out pass needs of the world's settings.
struct PushSettings {
  float inv_h;       ///< 1 / substep, 1/s
  float slop;        ///< overlap allowed, m
  float max_speed;   ///< push speed cap, m/s
  float deep_limit;  ///< depths below this were pushed out one by one, m
};

/// Colours scratch.constraints and packs them into scratch.batches.
void build_batches(WorldScratch& scratch);
/// Applies every batch's impulses of the last substep to its bodies.
void warm_start_batches(WorldScratch& scratch);
/// One pass on the real velocities: each manifold's normal impulses as a
/// block (a gap may close within the substep, no more), then friction point
/// by point.
void solve_batches(WorldScratch& scratch, float inv_h);
/// Each point's separation from the motion since the tick began, into the
/// batches and the scalar constraints (the push-out reads those); sets
/// scratch.overlapping when a point overlaps more than `slop` (m), and
/// scratch.deep_overlap when more than kDeepOverlapSlops slops past it.
void update_separations(WorldScratch& scratch, float slop);
/// update_separations and then one solve_batches, in one pass over the
/// batches (a batch's separations depend only on the bodies' motion so
/// far, which solving other batches does not change).
void update_separations_and_relax(WorldScratch& scratch, float slop, float inv_h);
/// One pass of the push-out over every shallow overlap (at most
/// kDeepOverlapSlops slops past the slop), in the batches' order; the deep
/// ones were pushed out from the ground up before it (contact_solver.cpp).
void push_batches(WorldScratch& scratch, const WorldConfig& config, float inv_h);
/// Copies the impulses back to scratch.constraints.
void unpack_batches(WorldScratch& scratch);

}  // namespace rwd::sim::d3
