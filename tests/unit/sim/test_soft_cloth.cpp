// SPDX-License-Identifier: MIT
// The particle solver's first pieces on their own: a cloth sheet's links and
// their colours, and XPBD passes over them: a sheet hung from its top row
// keeps its links near their rest length, and a colour's links give the same
// bits in any order (what lets threads share a colour).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <set>
#include <vector>

#include "soft/cloth_links.h"
#include "soft/xpbd.h"

namespace rwd::sim::soft {
namespace {

struct Sheet {
  uint32_t columns = 0;
  uint32_t rows = 0;
  std::vector<Vec3> x, previous, v;
  std::vector<float> inverse_mass;
  ClothLinks links;
  std::vector<float> lambda;
};

// A sheet in the x-z plane hung by its first row, `mass` kg in all.
Sheet hung_sheet(uint32_t columns, uint32_t rows, float spacing, float mass) {
  Sheet s;
  s.columns = columns;
  s.rows = rows;
  EXPECT_TRUE(build_cloth_links(columns, rows, spacing, s.links).ok());
  const uint32_t n = columns * rows;
  s.x.resize(n);
  s.previous.resize(n);
  s.v.resize(n);
  s.inverse_mass.assign(n, static_cast<float>(n) / mass);
  for (uint32_t r = 0; r < rows; ++r) {
    for (uint32_t c = 0; c < columns; ++c) {
      s.x[r * columns + c] = {static_cast<float>(c) * spacing, 2.0f,
                              static_cast<float>(r) * spacing};
    }
  }
  for (uint32_t c = 0; c < columns; ++c) s.inverse_mass[c] = 0.0f;  // pinned
  s.lambda.assign(s.links.links.size(), 0.0f);
  return s;
}

void step(Sheet& s, float dt, int substeps, int iterations, const float (&compliance)[3]) {
  const float h = dt / static_cast<float>(substeps);
  for (int sub = 0; sub < substeps; ++sub) {
    predict(s.x, s.previous, s.v, s.inverse_mass, {0.0f, -9.81f, 0.0f}, h);
    std::fill(s.lambda.begin(), s.lambda.end(), 0.0f);
    for (int it = 0; it < iterations; ++it) {
      solve_distance(s.x, s.inverse_mass, s.links.links, s.lambda, compliance, h);
    }
    update_velocities(s.x, s.previous, s.v, h);
  }
}

float worst_edge_stretch(const Sheet& s) {
  float worst = 0.0f;
  for (const DistanceLink& link : s.links.links) {
    if (link.kind != LinkKind::kEdge) continue;
    worst = std::max(worst, length(s.x[link.a] - s.x[link.b]) / link.rest - 1.0f);
  }
  return worst;
}

TEST(ClothLinks, EveryEdgeShearAndBendOnceInColoursThatShareNoParticle) {
  const uint32_t columns = 7;
  const uint32_t rows = 5;
  ClothLinks links;
  ASSERT_TRUE(build_cloth_links(columns, rows, 0.1f, links).ok());
  size_t edges = 0, shears = 0, bends = 0;
  for (const DistanceLink& link : links.links) {
    edges += link.kind == LinkKind::kEdge;
    shears += link.kind == LinkKind::kShear;
    bends += link.kind == LinkKind::kBend;
  }
  EXPECT_EQ(edges, (columns - 1) * rows + columns * (rows - 1));
  EXPECT_EQ(shears, 2u * (columns - 1) * (rows - 1));
  EXPECT_EQ(bends, (columns - 2) * rows + columns * (rows - 2));
  ASSERT_EQ(links.colour_starts.back(), links.links.size());
  std::set<std::pair<uint32_t, uint32_t>> seen;
  for (uint32_t c = 0; c < links.colours(); ++c) {
    std::set<uint32_t> used;
    for (uint32_t k = links.colour_starts[c]; k < links.colour_starts[c + 1]; ++k) {
      const DistanceLink& link = links.links[k];
      EXPECT_TRUE(used.insert(link.a).second) << "colour " << c << " shares particle " << link.a;
      EXPECT_TRUE(used.insert(link.b).second) << "colour " << c << " shares particle " << link.b;
      EXPECT_TRUE(seen.insert({std::min(link.a, link.b), std::max(link.a, link.b)}).second);
    }
  }
}

TEST(ClothLinks, ABadSheetIsRefusedAndNothingChanges) {
  ClothLinks links;
  ASSERT_TRUE(build_cloth_links(3, 3, 0.5f, links).ok());
  const size_t before = links.links.size();
  EXPECT_EQ(build_cloth_links(1, 9, 0.5f, links).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(build_cloth_links(4, 4, 0.0f, links).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(build_cloth_links(4, 4, -1.0f, links).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(build_cloth_links(4, 4, std::nanf(""), links).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(build_cloth_links(300, 300, 0.1f, links).message(),
            "cloth: 90000 particles, more than 65536");
  EXPECT_EQ(links.links.size(), before);
}

TEST(XpbdCloth, ASheetHungFromItsTopRowStaysNearItsRestLength) {
  // 16 x 12 particles 10 cm apart: 1.1 m from the pinned row to the free one.
  Sheet s = hung_sheet(16, 12, 0.1f, 0.5f);
  const float rigid[3] = {0.0f, 0.0f, 0.0f};
  float lowest = 2.0f;
  float worst = 0.0f;
  for (int t = 0; t < 120; ++t) {
    step(s, 1.0f / 60.0f, 4, 4, rigid);
    lowest = std::min(lowest, s.x[(s.rows - 1) * s.columns].y);
    worst = std::max(worst, worst_edge_stretch(s));
  }
  // It swings down to hang its full length below the pinned row...
  EXPECT_LT(lowest, 2.0f - 1.05f);
  EXPECT_GT(lowest, 2.0f - 1.1f * 1.05f);
  // ...the pinned row has not moved, and no edge ever stretched by more
  // than 5% at 4 substeps x 4 iterations, even at the bottom of the swing.
  EXPECT_EQ(s.x[0].y, 2.0f);
  EXPECT_LT(worst, 0.05f);
  for (const Vec3& p : s.x) EXPECT_TRUE(std::isfinite(p.x + p.y + p.z));
}

TEST(XpbdCloth, SofterLinksStretchMore) {
  Sheet stiff = hung_sheet(10, 10, 0.1f, 0.5f);
  Sheet soft = stiff;
  const float rigid[3] = {0.0f, 0.0f, 0.0f};
  // 0.2 m/N: the top links carry most of the sheet's 5 N and give way by a
  // large part of their length; rigid links only by the solver's residual.
  const float softer[3] = {0.2f, 0.2f, 0.2f};
  float worst_stiff = 0.0f;
  float worst_soft = 0.0f;
  for (int t = 0; t < 90; ++t) {
    step(stiff, 1.0f / 60.0f, 4, 4, rigid);
    step(soft, 1.0f / 60.0f, 4, 4, softer);
    worst_stiff = std::max(worst_stiff, worst_edge_stretch(stiff));
    worst_soft = std::max(worst_soft, worst_edge_stretch(soft));
  }
  EXPECT_GT(worst_soft, 2.0f * worst_stiff);
}

TEST(XpbdCloth, AColoursLinksGiveTheSameBitsInAnyOrder) {
  Sheet forward = hung_sheet(9, 9, 0.1f, 0.4f);
  Sheet reversed = forward;
  // Within each colour, the links in reverse order: no two share a particle,
  // so the corrections commute exactly.
  for (uint32_t c = 0; c < reversed.links.colours(); ++c) {
    std::reverse(reversed.links.links.begin() + reversed.links.colour_starts[c],
                 reversed.links.links.begin() + reversed.links.colour_starts[c + 1]);
  }
  const float compliance[3] = {1e-6f, 1e-5f, 1e-4f};
  for (int t = 0; t < 30; ++t) {
    step(forward, 1.0f / 60.0f, 4, 4, compliance);
    step(reversed, 1.0f / 60.0f, 4, 4, compliance);
  }
  ASSERT_EQ(forward.x.size(), reversed.x.size());
  EXPECT_EQ(std::memcmp(forward.x.data(), reversed.x.data(), forward.x.size() * sizeof(Vec3)), 0);
  EXPECT_EQ(std::memcmp(forward.v.data(), reversed.v.data(), forward.v.size() * sizeof(Vec3)), 0);
}

}  // namespace
}  // namespace rwd::sim::soft
