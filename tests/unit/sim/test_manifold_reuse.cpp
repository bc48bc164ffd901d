// SPDX-License-Identifier: MIT
// Manifold reuse (manifold_reuse.h) and the separating-axis retest: a
// carried manifold matches the one it was recorded from at the same pose,
// follows B's motion along the normal exactly and a small turn closely; the
// reuse bound holds on both sides; a resting box reuses its manifold and a
// kicked one does not; worlds that reuse restore and reload bit for bit;
// snapshots with a broken frame are refused; and a retested axis separates
// only where the full SAT finds no points. Tolerances are stated per test.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "d3/manifold.h"
#include "d3/manifold_reuse.h"
#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

constexpr float kSpec = 0.02f;

struct Pair {
  BodySim a;
  BodySim b;
  Shape shape_a = Shape::make_box({2.0f, 0.5f, 2.0f});
  Shape shape_b = Shape::make_box({0.5f, 0.5f, 0.5f});
};

// A 1 m box resting 2 mm into a ground slab, turned a little about y.
Pair resting_pair() {
  Pair p;
  p.a.position = {0.0f, 0.0f, 0.0f};
  p.b.position = {0.1f, 0.998f, -0.2f};
  p.b.rotation = Quat{0.0f, det_sin(0.05f), 0.0f, det_cos(0.05f)};
  return p;
}

Manifold collide(const Pair& p) {
  Manifold m;
  collide_shapes(p.shape_a, p.a.position, p.a.rotation, p.shape_b, p.b.position, p.b.rotation,
                 kSpec, m);
  return m;
}

// The record evaluate() keeps for a freshly computed manifold.
ContactRecord record_of(const Pair& p, const Manifold& m) {
  ContactRecord rec;
  rec.point_count = static_cast<uint8_t>(m.point_count);
  for (uint32_t i = 0; i < m.point_count; ++i) rec.points[i].feature_id = m.points[i].feature_id;
  const Mat3 axes_a = mat3_from_quat(p.a.rotation);
  record_frame(axes_a, relative_pose(p.a, axes_a, p.b), m, rec);
  return rec;
}

Manifold carry(const Pair& p, const ContactRecord& rec, bool* within = nullptr) {
  const Mat3 axes_a = mat3_from_quat(p.a.rotation);
  const RelativePose now = relative_pose(p.a, axes_a, p.b);
  const Quat turn = now.rotation * conjugate(rec.frame_rotation);
  if (within != nullptr) *within = within_reuse(rec, now, turn, length(p.shape_b.half_extents));
  Manifold m;
  carry_manifold(p.a, axes_a, p.b, rec, now, turn, m);
  return m;
}

const ManifoldPoint* find_id(const Manifold& m, uint32_t id) {
  for (uint32_t i = 0; i < m.point_count; ++i) {
    if (m.points[i].feature_id == id) return &m.points[i];
  }
  return nullptr;
}

TEST(ManifoldReuse, CarriedAtTheSamePoseIsTheRecordedManifold) {
  const Pair p = resting_pair();
  const Manifold fresh = collide(p);
  ASSERT_EQ(fresh.point_count, 4u);
  const ContactRecord rec = record_of(p, fresh);
  bool within = false;
  const Manifold carried = carry(p, rec, &within);
  EXPECT_TRUE(within);
  ASSERT_EQ(carried.point_count, fresh.point_count);
  EXPECT_NEAR(length(carried.normal - fresh.normal), 0.0f, 1e-6f);
  for (uint32_t i = 0; i < fresh.point_count; ++i) {
    EXPECT_EQ(carried.points[i].feature_id, fresh.points[i].feature_id);
    EXPECT_NEAR(carried.points[i].separation, fresh.points[i].separation, 1e-6f);
    EXPECT_NEAR(length(carried.points[i].point - fresh.points[i].point), 0.0f, 1e-6f);
    EXPECT_NEAR(length(carried.points[i].anchor_b - fresh.points[i].anchor_b), 0.0f, 1e-6f);
  }
}

TEST(ManifoldReuse, SeparationFollowsMotionAlongTheNormal) {
  Pair p = resting_pair();
  const Manifold fresh = collide(p);
  const ContactRecord rec = record_of(p, fresh);
  p.b.position.y += 0.0003f;  // 0.3 mm up: within the bound
  bool within = false;
  const Manifold carried = carry(p, rec, &within);
  EXPECT_TRUE(within);
  for (uint32_t i = 0; i < fresh.point_count; ++i) {
    EXPECT_NEAR(carried.points[i].separation, fresh.points[i].separation + 0.0003f, 2e-6f);
    // The point stays midway: half the motion.
    EXPECT_NEAR(carried.points[i].point.y, fresh.points[i].point.y + 0.00015f, 2e-6f);
  }
}

TEST(ManifoldReuse, SmallTurnMatchesAFreshManifold) {
  Pair p = resting_pair();
  const ContactRecord rec = record_of(p, collide(p));
  // Tilt B by 0.2 mrad about x (its corners move by under 0.2 mm) and
  // slide it 0.2 mm: within the bound, and a fresh SAT keeps the same ids.
  const float half = 0.0001f;
  p.b.rotation = normalize(Quat{det_sin(half), 0.0f, 0.0f, det_cos(half)} * p.b.rotation);
  p.b.position.x += 0.0002f;
  bool within = false;
  const Manifold carried = carry(p, rec, &within);
  EXPECT_TRUE(within);
  const Manifold fresh = collide(p);
  ASSERT_EQ(carried.point_count, fresh.point_count);
  for (uint32_t i = 0; i < fresh.point_count; ++i) {
    const ManifoldPoint* same = find_id(carried, fresh.points[i].feature_id);
    ASSERT_NE(same, nullptr);
    // 20 um: the carried normal stays fixed on A, the fresh one is A's face
    // normal too, so the points differ only by rounding and the slide.
    EXPECT_NEAR(same->separation, fresh.points[i].separation, 2e-5f);
  }
}

TEST(ManifoldReuse, BoundHoldsOnBothSides) {
  const Pair base = resting_pair();
  const ContactRecord rec = record_of(base, collide(base));
  const float extent = length(base.shape_b.half_extents);
  auto within_after = [&](Vec3 shift, float turn_m) {
    Pair p = base;
    p.b.position += shift;
    // A turn about z moving B's farthest point by turn_m metres.
    const float half_angle = 0.5f * turn_m / extent;
    p.b.rotation =
        normalize(Quat{0.0f, 0.0f, det_sin(half_angle), det_cos(half_angle)} * p.b.rotation);
    bool within = false;
    carry(p, rec, &within);
    return within;
  };
  EXPECT_TRUE(within_after({0.0004f, 0.0f, 0.0f}, 0.0f));
  EXPECT_FALSE(within_after({0.0006f, 0.0f, 0.0f}, 0.0f));
  EXPECT_FALSE(within_after({0.0f, 0.0f, -0.0006f}, 0.0f));
  EXPECT_TRUE(within_after({}, 0.0004f));
  EXPECT_FALSE(within_after({}, 0.0006f));
}

WorldConfig awake_config() {
  WorldConfig c;
  c.enable_sleep = false;
  return c;
}

TEST(ManifoldReuse, RestingBoxReusesAndAKickedOneRecomputes) {
  World3D world(awake_config());
  test::add_ground(world);
  const BodyId box = test::add_box(world, {0.0f, 0.5f, 0.0f});
  for (int i = 0; i < 60; ++i) world.step();
  uint32_t reused = 0;
  for (int i = 0; i < 60; ++i) {
    world.step();
    reused += world.stats().reused_manifolds;
  }
  EXPECT_GE(reused, 55u);  // the box has settled: nearly every step reuses
  ASSERT_EQ(world.state().contacts.size(), 1u);
  EXPECT_EQ(world.state().contacts[0].point_count, 4u);
  // Still resting within the slop plus a millimetre.
  EXPECT_GT(world.position(box).y, 0.5f - world.config().linear_slop_m - 0.001f);

  ASSERT_TRUE(world.set_linear_velocity(box, {1.0f, 0.0f, 0.0f}).ok());
  world.step();  // the kick moves the box during this step's solve
  world.step();  // ~17 mm from where its manifold was computed: collided again
  EXPECT_EQ(world.stats().reused_manifolds, 0u);
  ASSERT_EQ(world.state().contacts.size(), 1u);
  EXPECT_EQ(world.state().contacts[0].point_count, 4u);
}

// A settling pile: boxes falling onto each other, then resting, so steps
// mix computed, carried and separated pairs.
void build_pile(World3D& world) {
  test::add_ground(world);
  for (int i = 0; i < 27; ++i) {
    BodyDef def;
    def.shape = Shape::make_box({0.3f, 0.25f, 0.35f});
    def.position = {0.7f * static_cast<float>(i % 3) - 0.7f,
                    0.4f + 0.6f * static_cast<float>(i / 9),
                    0.8f * static_cast<float>((i / 3) % 3) - 0.8f};
    def.rotation = normalize(Quat{0.05f * static_cast<float>(i % 5), 0.1f, 0.0f, 1.0f});
    ASSERT_TRUE(world.create_body(def).ok());
  }
}

TEST(ManifoldReuse, RestoreAndReloadStepOnBitForBit) {
  World3D world(awake_config());
  build_pile(world);
  for (int i = 0; i < 100; ++i) world.step();
  WorldState snapshot;
  world.save(snapshot);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<uint64_t> sums;
  uint32_t reused = 0;
  for (int i = 0; i < 120; ++i) {
    world.step();
    sums.push_back(world.checksum());
    reused += world.stats().reused_manifolds;
  }
  ASSERT_GT(reused, 100u);  // the window exercises reuse

  world.restore(snapshot);
  for (size_t i = 0; i < sums.size(); ++i) {
    world.step();
    ASSERT_EQ(world.checksum(), sums[i]) << "restored, step " << i;
  }
  World3D loaded(awake_config());
  ASSERT_TRUE(loaded.deserialize(bytes).ok());
  for (size_t i = 0; i < sums.size(); ++i) {
    loaded.step();
    ASSERT_EQ(loaded.checksum(), sums[i]) << "loaded, step " << i;
  }
}

TEST(ManifoldReuse, SnapshotsWithABrokenFrameAreRefused) {
  World3D world(awake_config());
  build_pile(world);
  for (int i = 0; i < 100; ++i) world.step();
  const uint64_t before = world.checksum();
  WorldState good;
  world.save(good);
  ASSERT_FALSE(good.contacts.empty());
  ASSERT_GT(good.contacts[0].point_count, 0u);
  auto refused = [&](auto&& corrupt) {
    WorldState bad = good;
    corrupt(bad.contacts[0]);
    World3D writer(awake_config());
    writer.restore(bad);  // restore copies; only loading judges
    std::vector<uint8_t> bytes;
    writer.serialize(bytes);
    const Status s = world.deserialize(bytes);
    return !s.ok() && s.code() == ErrorCode::kCorrupt;
  };
  EXPECT_TRUE(refused([](ContactRecord& r) { r.frame_rotation = Quat{0.0f, 0.0f, 0.0f, 2.0f}; }));
  EXPECT_TRUE(refused([](ContactRecord& r) { r.frame_normal = Vec3{0.0f, 0.0f, 0.0f}; }));
  EXPECT_TRUE(refused([](ContactRecord& r) { r.frame_position = Vec3{1e9f, 0.0f, 0.0f}; }));
  EXPECT_TRUE(refused([](ContactRecord& r) { r.points[0].local_a = Vec3{0.0f, 1e7f, 0.0f}; }));
  EXPECT_TRUE(refused([](ContactRecord& r) { r.points[0].separation = -1e7f; }));
  EXPECT_EQ(world.checksum(), before);  // every refusal left the world as it was
}

TEST(SeparatingAxis, RetestAgreesWithTheFullTest) {
  test::Rng rng{12345};
  const auto uniform = [&rng](float lo, float hi) { return rng.uniform(lo, hi); };
  int separated = 0;
  for (int n = 0; n < 20000; ++n) {
    const Vec3 half_a{uniform(0.05f, 1.0f), uniform(0.05f, 1.0f), uniform(0.05f, 1.0f)};
    const Vec3 half_b{uniform(0.05f, 1.0f), uniform(0.05f, 1.0f), uniform(0.05f, 1.0f)};
    const Quat qa = rng.rotation();
    // Every fourth pair face-aligned, where parallel edge axes are skipped.
    const Quat qb = n % 4 == 0 ? qa : rng.rotation();
    const Vec3 ca{uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f)};
    const Vec3 cb = ca + Vec3{uniform(-1.5f, 1.5f), uniform(-1.5f, 1.5f), uniform(-1.5f, 1.5f)};
    const Mat3 ra = mat3_from_quat(qa);
    const Mat3 rb = mat3_from_quat(qb);
    Manifold m;
    collide_boxes(ca, ra, half_a, cb, rb, half_b, kSpec, m);
    if (m.separating_axis != kNoSeparatingAxis) {
      ++separated;
      EXPECT_EQ(m.point_count, 0u);
      EXPECT_TRUE(box_axis_separates(ca, ra, half_a, cb, rb, half_b, m.separating_axis, kSpec))
          << "pair " << n << " axis " << int{m.separating_axis};
    }
    for (uint8_t axis = 0; axis < 15; ++axis) {
      if (box_axis_separates(ca, ra, half_a, cb, rb, half_b, axis, kSpec)) {
        EXPECT_EQ(m.point_count, 0u) << "pair " << n << " axis " << int{axis};
        EXPECT_NE(m.separating_axis, kNoSeparatingAxis);
      }
    }
  }
  EXPECT_GT(separated, 2000);  // both outcomes are well represented
  EXPECT_LT(separated, 18000);
}

}  // namespace
}  // namespace rwd::sim::d3
