// SPDX-License-Identifier: MIT
// The separating face a hull pair names (Manifold::separating_axis) and
// hull_axis_separates, which the narrowphase uses to skip a pair whose
// last separating face still keeps it apart: the face it names separates,
// and wherever that face alone says "apart", collide_hulls finds no points
// either, so skipping the pair never changes a result.
#include <gtest/gtest.h>

#include "d3/manifold.h"
#include "d3/manifold_hull_sat.h"
#include "hull_sat_test_shapes.h"
#include "rewind/core/det_math.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

using namespace hull_sat_test;

constexpr float kSpeculative = 0.02f;

struct Pose {
  Vec3 position;
  Mat3 axes;
};

Pose random_pose(test::Rng& rng, Vec3 around, float reach) {
  const Vec3 dir = normalize_or_zero({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
  return {around + dir * (reach * rng.uniform(0.3f, 1.2f)), mat3_from_quat(rng.rotation())};
}

TEST(HullSeparatingAxis, ANamedFaceSeparatesAndOnlySkipsPairsWithoutPoints) {
  const Hull hulls[] = {make_box({0.5f, 0.3f, 0.4f}), make_prism(), make_tetrahedron(),
                        make_ngon_prism(7, 0.5f, 0.6f), make_pyramid(5, 0.6f, 0.8f)};
  test::Rng rng{0x5EBA7A7Eull};
  int named = 0;
  int named_by_b = 0;
  int still_apart = 0;
  for (int i = 0; i < 6000; ++i) {
    SCOPED_TRACE(i);
    const Hull& a = hulls[rng.next() % 5];
    const Hull& b = hulls[rng.next() % 5];
    const Pose pa{{rng.uniform(-50, 50), rng.uniform(-5, 5), rng.uniform(-50, 50)},
                  mat3_from_quat(rng.rotation())};
    const Pose pb = random_pose(rng, pa.position, 1.6f);
    Manifold m;
    collide_hulls(a, pa.position, pa.axes, b, pb.position, pb.axes, kSpeculative, m);
    if (m.separating_axis == kNoSeparatingAxis) continue;
    ++named;
    if (m.separating_axis >= kHullFaceAxisB) ++named_by_b;
    EXPECT_EQ(m.point_count, 0u);
    ASSERT_TRUE(hull_axis_separates(hull_view(a), pa.position, pa.axes, hull_view(b), pb.position,
                                    pb.axes, m.separating_axis, kSpeculative));
    // The next step: B moved a little. Where the face still separates, the
    // full test finds no points.
    const Pose moved{pb.position + Vec3{rng.uniform(-0.05f, 0.05f), rng.uniform(-0.05f, 0.05f),
                                        rng.uniform(-0.05f, 0.05f)},
                     pb.axes};
    Manifold next;
    collide_hulls(a, pa.position, pa.axes, b, moved.position, moved.axes, kSpeculative, next);
    if (hull_axis_separates(hull_view(a), pa.position, pa.axes, hull_view(b), moved.position,
                            moved.axes, m.separating_axis, kSpeculative)) {
      ++still_apart;
      EXPECT_EQ(next.point_count, 0u);
    }
  }
  EXPECT_GT(named, 1000);
  EXPECT_GT(named_by_b, 50);
  EXPECT_GT(still_apart, 500);
}

TEST(HullSeparatingAxis, AFaceNumberTheHullDoesNotHaveSeparatesNothing) {
  const Hull box = make_box({0.5f, 0.5f, 0.5f});
  const Mat3 identity{};
  // Far apart, but face 100 of a box and face 200 - kHullFaceAxisB of B do
  // not exist: the test answers false rather than reading past the faces.
  EXPECT_FALSE(hull_axis_separates(hull_view(box), {0, 0, 0}, identity, hull_view(box), {10, 0, 0},
                                   identity, 100, kSpeculative));
  EXPECT_FALSE(hull_axis_separates(hull_view(box), {0, 0, 0}, identity, hull_view(box), {10, 0, 0},
                                   identity, 200, kSpeculative));
  // Face 1 of A is its +x face (BoxHull numbering: 2k + 1 is +k).
  EXPECT_TRUE(hull_axis_separates(hull_view(box), {0, 0, 0}, identity, hull_view(box), {10, 0, 0},
                                  identity, 1, kSpeculative));
}

}  // namespace
}  // namespace rwd::sim::d3
