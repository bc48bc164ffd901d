// SPDX-License-Identifier: MIT
// Broadphase: the candidate pairs match a brute-force reference, sorted by
// (lower, higher) index, with static-static pairs skipped.
#include <algorithm>

#include <gtest/gtest.h>

#include "d3/body_storage.h"
#include "d3/pipeline.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

TEST(Broadphase, MatchesBruteForceAndIsSorted) {
  World3D world;
  // A deterministic scatter of static and dynamic shapes, some overlapping.
  uint32_t seed = 12345;
  auto next = [&]() {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / 16777216.0f;
  };
  for (int i = 0; i < 80; ++i) {
    BodyDef def;
    def.kind = i % 4 == 0 ? BodyKind::kStatic : BodyKind::kDynamic;
    def.position = {next() * 10.0f, next() * 10.0f, next() * 10.0f};
    def.shape = i % 2 == 0 ? Shape::make_sphere(0.3f + next())
                           : Shape::make_box({0.2f + next(), 0.2f + next(), 0.2f + next()});
    def.rotation = normalize(Quat{next(), next(), next(), 1.0f});
    ASSERT_TRUE(world.create_body(def).ok());
  }
  const WorldState& state = world.state();
  WorldScratch scratch;
  find_pairs(state, scratch);

  // Reference: every pair of live bodies, same bounds and rules.
  std::vector<BodyPair> expected;
  const float margin = state.config.speculative_distance_m;
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  for (uint32_t a = 0; a < n; ++a) {
    for (uint32_t b = a + 1; b < n; ++b) {
      const BodyInfo& ia = state.infos[a];
      const BodyInfo& ib = state.infos[b];
      if (ia.kind == BodyKind::kStatic && ib.kind == BodyKind::kStatic) continue;
      Aabb x = shape_aabb(ia.shape, state.sims[a].position, state.sims[a].rotation);
      Aabb y = shape_aabb(ib.shape, state.sims[b].position, state.sims[b].rotation);
      float ma = is_active(ia) ? margin : 0.0f;
      float mb = is_active(ib) ? margin : 0.0f;
      bool overlap = x.lower.x - ma <= y.upper.x + mb && y.lower.x - mb <= x.upper.x + ma &&
                     x.lower.y - ma <= y.upper.y + mb && y.lower.y - mb <= x.upper.y + ma &&
                     x.lower.z - ma <= y.upper.z + mb && y.lower.z - mb <= x.upper.z + ma;
      if (overlap) expected.push_back({a, b});
    }
  }
  ASSERT_GT(expected.size(), 10u);
  ASSERT_EQ(scratch.pairs.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(scratch.pairs[i].a, expected[i].a) << i;
    EXPECT_EQ(scratch.pairs[i].b, expected[i].b) << i;
  }
}

}  // namespace
}  // namespace rwd::sim::d3
