// SPDX-License-Identifier: MIT
#include <algorithm>

#include "body_math2d.h"
#include "pipeline2d.h"

namespace rwd::sim2d::detail {

namespace {

bool layers_agree(const BodyRecord2D& a, const BodyRecord2D& b) {
  return (a.layer & b.mask) != 0 && (b.layer & a.mask) != 0;
}

}  // namespace

void find_pairs(const World2DState& state, StepScratch2D& scratch) {
  const W margin = w_from(state.config.speculative_distance) / 2;
  auto& sweep = scratch.sweep;
  sweep.clear();
  for (uint32_t i = 0; i < state.bodies.size(); ++i) {
    const BodyRecord2D& body = state.bodies[i];
    if (!(body.flags & kBodyLive) || !(body.flags & kBodyEnabled)) continue;
    Box2W box = shape_bounds(body.shape, origin_transform(body));
    box.lower -= V2{margin, margin};
    box.upper += V2{margin, margin};
    sweep.push_back({box, i, is_moving(body)});
  }
  // (lower x, index) is unique per body, so the order, and with it every
  // later order, depends on the state alone.
  std::sort(sweep.begin(), sweep.end(), [](const SweepEntry2D& a, const SweepEntry2D& b) {
    return a.box.lower.x != b.box.lower.x ? a.box.lower.x < b.box.lower.x : a.index < b.index;
  });

  // Joined bodies that must not collide (collide_connected off).
  auto& joined = scratch.joined_pairs;
  joined.clear();
  for (const JointRecord2D& j : state.joints) {
    if (!(j.flags & kJointLive) || (j.flags & (kJointBroken | kJointCollideConnected))) continue;
    joined.push_back((uint64_t{std::min(j.a, j.b)} << 32) | std::max(j.a, j.b));
  }
  std::sort(joined.begin(), joined.end());

  auto& pairs = scratch.pairs;
  pairs.clear();
  for (size_t i = 0; i < sweep.size(); ++i) {
    const SweepEntry2D& a = sweep[i];
    for (size_t j = i + 1; j < sweep.size() && sweep[j].box.lower.x <= a.box.upper.x; ++j) {
      const SweepEntry2D& b = sweep[j];
      if (!a.moves && !b.moves) continue;
      if (a.box.lower.y > b.box.upper.y || b.box.lower.y > a.box.upper.y) continue;
      if (!layers_agree(state.bodies[a.index], state.bodies[b.index])) continue;
      const uint32_t lo = std::min(a.index, b.index);
      const uint32_t hi = std::max(a.index, b.index);
      const uint64_t key = (uint64_t{lo} << 32) | hi;
      if (!joined.empty() && std::binary_search(joined.begin(), joined.end(), key)) continue;
      pairs.push_back(key);
    }
  }
  std::sort(pairs.begin(), pairs.end());
}

}  // namespace rwd::sim2d::detail
