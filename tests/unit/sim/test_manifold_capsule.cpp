// SPDX-License-Identifier: MIT
// Capsules: manifolds against spheres, capsules and boxes (points, normals
// and depths against hand-computed cases; reversed pairs through the
// collide table), mass properties against the analytic ones, rays, the
// shape rule, snapshots, and capsules resting on the ground and on each
// other. Tolerance 1e-5 m unless stated.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "d3/manifold.h"
#include "d3/shape_ops.h"
#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim::d3 {
namespace {

constexpr float kTol = 1e-5f;
constexpr float kSpec = 0.02f;

// A capsule lying along x: its local y turned onto world x.
Quat lying_along_x() {
  const float h = std::sqrt(0.5f);
  return Quat{0.0f, 0.0f, -h, h};  // -90 degrees about z: y -> x
}

Manifold collide(const Shape& a, Vec3 pa, Quat qa, const Shape& b, Vec3 pb, Quat qb) {
  Manifold m;
  collide_shapes(a, pa, qa, b, pb, qb, kSpec, m);
  return m;
}

TEST(ManifoldCapsule, SphereAgainstTheSideAndTheCap) {
  const Shape cap = Shape::make_capsule(0.5f, 1.0f);
  const Shape ball = Shape::make_sphere(0.25f);
  // Beside the middle of the segment, 0.7 m out: 0.05 m overlap.
  Manifold m = collide(cap, {}, {}, ball, {0.7f, 0.3f, 0.0f}, {});
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.normal.x, 1.0f, kTol);
  EXPECT_NEAR(m.points[0].separation, -0.05f, kTol);
  EXPECT_NEAR(m.points[0].point.x, 0.475f, kTol);  // midway between 0.5 and 0.45
  EXPECT_NEAR(m.points[0].point.y, 0.3f, kTol);
  // Above the top cap: centre 1.0 + 0.5 + 0.25 + 0.01 up, 1 cm apart.
  m = collide(cap, {}, {}, ball, {0.0f, 1.76f, 0.0f}, {});
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  EXPECT_NEAR(m.points[0].separation, 0.01f, kTol);
  // Reversed through the table: the normal still runs from A to B.
  m = collide(ball, {0.7f, 0.3f, 0.0f}, {}, cap, {}, {});
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.normal.x, -1.0f, kTol);
  EXPECT_NEAR(m.points[0].separation, -0.05f, kTol);
  // Out of reach.
  m = collide(cap, {}, {}, ball, {0.0f, 2.0f, 0.0f}, {});
  EXPECT_EQ(m.point_count, 0u);
}

TEST(ManifoldCapsule, CrossedCapsulesTouchAtOnePoint) {
  const Shape cap = Shape::make_capsule(0.2f, 1.0f);
  // A along x at the origin, B along z resting 0.39 m above: 1 cm overlap.
  const Manifold m = collide(cap, {}, lying_along_x(), cap, {0.1f, 0.39f, 0.3f},
                             Quat{det_sin(0.25f * kPi), 0.0f, 0.0f, det_cos(0.25f * kPi)});
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  EXPECT_NEAR(m.points[0].separation, -0.01f, kTol);
  EXPECT_NEAR(m.points[0].point.x, 0.1f, kTol);
  EXPECT_NEAR(m.points[0].point.z, 0.0f, kTol);
}

TEST(ManifoldCapsule, ParallelCapsulesTouchAtTwoPoints) {
  const Shape cap = Shape::make_capsule(0.2f, 1.0f);
  // Both along x, B shifted 0.5 m along and 0.395 m up: they overlap on
  // x in [-0.5, 1.0] of A's segment.
  const Manifold m = collide(cap, {}, lying_along_x(), cap, {0.5f, 0.395f, 0.0f}, lying_along_x());
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  for (uint32_t i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].separation, -0.005f, kTol);
  EXPECT_NEAR(m.points[0].point.x, -0.5f, kTol);
  EXPECT_NEAR(m.points[1].point.x, 1.0f, kTol);
  EXPECT_NE(m.points[0].feature_id, m.points[1].feature_id);
}

TEST(ManifoldCapsule, LyingOnABoxGivesTwoPoints) {
  const Shape ground = Shape::make_box({3.0f, 0.5f, 3.0f});
  const Shape cap = Shape::make_capsule(0.25f, 0.75f);
  // Box top at y = 0.5; the capsule's axis 0.74 up: 1 cm into the box.
  Manifold m = collide(ground, {}, {}, cap, {0.2f, 0.74f, -0.1f}, lying_along_x());
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  for (uint32_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.01f, kTol);
    EXPECT_NEAR(m.points[i].point.y, 0.495f, kTol);  // midway into the overlap
    EXPECT_NEAR(m.points[i].point.z, -0.1f, kTol);
  }
  EXPECT_NEAR(std::fabs(m.points[0].point.x - m.points[1].point.x), 1.5f, kTol);
  // Reversed: capsule first.
  m = collide(cap, {0.2f, 0.74f, -0.1f}, lying_along_x(), ground, {}, {});
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_NEAR(m.normal.y, -1.0f, kTol);
  // Hanging off the edge: only the part over the box is kept (clipped at
  // x = 3 plus the clip margin).
  m = collide(ground, {}, {}, cap, {2.7f, 0.74f, 0.0f}, lying_along_x());
  ASSERT_EQ(m.point_count, 2u);
  const float far_x = std::fmax(m.points[0].point.x, m.points[1].point.x);
  EXPECT_NEAR(far_x, 3.001f, 1e-4f);
}

TEST(ManifoldCapsule, StandingOnABoxGivesOnePointUnderTheCap) {
  const Shape ground = Shape::make_box({3.0f, 0.5f, 3.0f});
  const Shape cap = Shape::make_capsule(0.25f, 0.75f);
  // Upright: the lower cap's centre at 0.5 + 0.25 - 0.002 = 0.748.
  const Manifold m = collide(ground, {}, {}, cap, {0.0f, 0.748f + 0.75f, 0.0f}, {});
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  EXPECT_NEAR(m.points[0].separation, -0.002f, kTol);
  EXPECT_NEAR(m.points[0].point.y, 0.499f, kTol);
}

TEST(ManifoldCapsule, AgainstABoxEdgeAndCorner) {
  const Shape box = Shape::make_box({0.5f, 0.5f, 0.5f});
  const Shape cap = Shape::make_capsule(0.1f, 1.0f);
  // A capsule along z passing over the box's top +x edge, diagonally out:
  // its axis 0.1 + 0.01 from the edge (y = 0.5, x = 0.5) along (1,1)/sqrt2.
  const float d = 0.11f / std::sqrt(2.0f);
  const Quat along_z{det_sin(0.25f * kPi), 0.0f, 0.0f, det_cos(0.25f * kPi)};
  // Lying along the edge: two points, at the ends of the part beside it
  // (clipped at z = +-0.5 plus the clip margin), sharing the edge's normal.
  Manifold m = collide(box, {}, {}, cap, {0.5f + d, 0.5f + d, 0.0f}, along_z);
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_NEAR(m.normal.x, std::sqrt(0.5f), 1e-4f);
  EXPECT_NEAR(m.normal.y, std::sqrt(0.5f), 1e-4f);
  for (uint32_t i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].separation, 0.01f, 1e-5f);
  EXPECT_NEAR(m.points[0].point.z + m.points[1].point.z, 0.0f, 1e-5f);
  EXPECT_NEAR(std::fabs(m.points[0].point.z - m.points[1].point.z), 1.001f, 1e-4f);
  // The end cap beyond a corner: capsule along x, its lower end's centre
  // 0.105 m from the corner (0.5, 0.5, 0.5) along (1,1,1)/sqrt3.
  const float c = 0.105f / std::sqrt(3.0f);
  m = collide(box, {}, {}, cap, {0.5f + c + 1.0f, 0.5f + c, 0.5f + c}, lying_along_x());
  ASSERT_EQ(m.point_count, 1u);
  EXPECT_NEAR(m.points[0].separation, 0.005f, 1e-5f);
  EXPECT_NEAR(m.normal.z, std::sqrt(1.0f / 3.0f), 1e-4f);
}

// A pole standing across a thin plank's face (the plank's height along the
// pole): two points, one at each end of the part of the pole beside the
// face, mirror images across the plank, whether the pole is clear of the
// face, touching it or leaning on it, so the push does not turn the plank
// about its long axis. (The nearest point of the pole lies where it
// crosses a side plane of the box, and rounding put it just beyond that
// plane: the one-point corner case, at one end of the face only.)
TEST(ManifoldCapsule, APoleAcrossAThinFacePushesItEvenly) {
  const Shape plank = Shape::make_box({1.0f, 0.05f, 0.02f});
  const Shape pole = Shape::make_capsule(0.025f, 1.0f);
  for (const float z : {-0.06f, -0.045f, -0.03f, -0.019f}) {
    SCOPED_TRACE(z);
    const Manifold m = collide(plank, {}, {}, pole, {0.647f, 0.0f, z}, {});
    ASSERT_EQ(m.point_count, 2u);
    EXPECT_NEAR(m.normal.z, -1.0f, kTol);
    EXPECT_NEAR(m.points[0].separation, m.points[1].separation, kTol);
    EXPECT_NEAR(m.points[0].point.y, -m.points[1].point.y, kTol);
    EXPECT_NEAR(m.points[0].point.x, m.points[1].point.x, kTol);
  }
  // Beside the plank's end (beyond x = 1 and the face): along the edge.
  const Manifold m = collide(plank, {}, {}, pole, {1.03f, 0.0f, -0.04f}, {});
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_NEAR(m.points[0].separation, m.points[1].separation, kTol);
  EXPECT_NEAR(m.points[0].point.y, -m.points[1].point.y, kTol);
  EXPECT_NEAR(m.normal.x, 0.03f / std::sqrt(0.0013f), 1e-4f);  // (0.03, -0.02) from the edge
  EXPECT_NEAR(m.normal.z, -0.02f / std::sqrt(0.0013f), 1e-4f);
  // Leaning toward the face, the pole's nearest point lies beyond the
  // face's side, by the plank's edge: one point there (the contact really
  // is at the edge), as hull-capsule gives.
  const float lean = 0.05f;
  const Quat leaning{det_sin(0.5f * lean), 0.0f, 0.0f, det_cos(0.5f * lean)};
  const Manifold l = collide(plank, {}, {}, pole, {0.5f, 0.0f, -0.05f}, leaning);
  ASSERT_EQ(l.point_count, 1u);
  EXPECT_NEAR(l.points[0].point.y, 0.05f, 1e-3f);
}

TEST(ManifoldCapsule, ReachingIntoABoxPushesOutTheShortWay) {
  const Shape box = Shape::make_box({1.0f, 0.5f, 1.0f});
  const Shape cap = Shape::make_capsule(0.1f, 0.3f);
  // Lying 0.1 m below the top face, inside: out through the top, 0.2 m
  // (0.1 to the face plus the radius).
  const Manifold m = collide(box, {}, {}, cap, {0.0f, 0.4f, 0.0f}, lying_along_x());
  ASSERT_EQ(m.point_count, 2u);
  EXPECT_NEAR(m.normal.y, 1.0f, kTol);
  for (uint32_t i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].separation, -0.2f, kTol);
}

TEST(ShapeCapsule, MassPropertiesAreTheAnalyticOnes) {
  const Shape cap = Shape::make_capsule(0.3f, 0.5f);
  const ShapeOps& ops = shape_ops(ShapeType::kCapsule);
  const GeometryStore store;
  const double r = 0.3;
  const double h = 0.5;
  const double pi = 3.14159265358979323846;
  const double v_c = pi * r * r * 2.0 * h;
  const double v_s = 4.0 / 3.0 * pi * r * r * r;
  EXPECT_NEAR(ops.volume(cap, store), v_c + v_s, 1e-6);
  EXPECT_NEAR(ops.extent(cap, store), 0.8f, 1e-6f);
  const double m = 10.0;
  const double m_c = m * v_c / (v_c + v_s);
  const double m_s = m - m_c;
  // Axial: cylinder m r^2/2 plus a solid sphere's 2/5 m r^2.
  const Vec3 i = ops.inertia(cap, store, 10.0f);
  EXPECT_NEAR(i.y, m_c * r * r / 2.0 + 0.4 * m_s * r * r, 1e-4);
  // Across, by integrating thin discs along the axis (independent of the
  // closed form): a disc of radius a, mass dm at height y contributes
  // dm (a^2 / 4 + y^2).
  double across = 0.0;
  const int n = 200000;
  const double density = m / (v_c + v_s);
  const double top = h + r;
  for (int k = 0; k < n; ++k) {
    const double y = -top + (k + 0.5) * (2.0 * top / n);
    const double dy = 2.0 * top / n;
    const double beyond = std::fabs(y) > h ? std::fabs(y) - h : 0.0;
    const double a2 = r * r - beyond * beyond;
    const double dm = density * pi * a2 * dy;
    across += dm * (a2 / 4.0 + y * y);
  }
  EXPECT_NEAR(i.x, across, 1e-3 * across);
  EXPECT_EQ(i.x, i.z);
}

TEST(ShapeCapsule, RaysHitTheSideAndTheCaps) {
  World3D world;
  BodyDef def;
  def.kind = BodyKind::kStatic;
  def.shape = Shape::make_capsule(0.5f, 1.0f);
  def.position = {0.0f, 2.0f, 0.0f};
  const BodyId id = *world.create_body(def);
  // From the side, at the height of the segment: the cylinder at x = -0.5.
  auto hit = world.raycast({{-5.0f, 2.5f, 0.0f}, {1.0f, 0.0f, 0.0f}, 100.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body.index, id.index);
  EXPECT_NEAR(hit->distance, 4.5f, 1e-5f);
  EXPECT_NEAR(hit->normal.x, -1.0f, 1e-5f);
  // From above: the top cap's pole at y = 2 + 1 + 0.5.
  hit = world.raycast({{0.0f, 10.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 100.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance, 6.5f, 1e-5f);
  EXPECT_NEAR(hit->normal.y, 1.0f, 1e-5f);
  // Past the cap, beside the pole: misses.
  EXPECT_FALSE(world.raycast({{0.6f, 10.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 100.0f}).has_value());
  // From inside: distance 0, the normal facing back.
  hit = world.raycast({{0.0f, 2.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 100.0f});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->distance, 0.0f);
}

TEST(ShapeCapsule, TheRuleRefusesBadSizes) {
  World3D world;
  BodyDef def;
  def.shape = Shape::make_capsule(0.0f, 1.0f);
  EXPECT_FALSE(world.create_body(def).ok());
  def.shape = Shape::make_capsule(0.5f, -1.0f);
  EXPECT_FALSE(world.create_body(def).ok());
  def.shape = Shape::make_capsule(0.5f, std::nanf(""));
  EXPECT_FALSE(world.create_body(def).ok());
  def.shape = Shape::make_capsule(0.5f, 2000.0f);
  EXPECT_FALSE(world.create_body(def).ok());
  EXPECT_EQ(world.body_count(), 0u);
  def.shape = Shape::make_capsule(0.5f, 1.0f);
  def.shape.half_extents = {9.0f, 9.0f, 9.0f};  // not a capsule's: cleared
  const BodyId id = *world.create_body(def);
  EXPECT_EQ(world.shape(id)->half_extents.x, 0.0f);
  EXPECT_EQ(world.shape(id)->half_height, 1.0f);
}

WorldConfig awake() {
  WorldConfig c;
  c.enable_sleep = false;
  return c;
}

TEST(ShapeCapsule, LyingCapsuleRestsWithoutRolling) {
  World3D world(awake());
  test::add_ground(world);
  BodyDef def;
  def.shape = Shape::make_capsule(0.25f, 0.75f);
  def.position = {0.0f, 0.3f, 0.0f};
  def.rotation = lying_along_x();
  const BodyId id = *world.create_body(def);
  test::step_seconds(world, 3.0f);
  EXPECT_NEAR(world.position(id).y, 0.25f, world.config().linear_slop_m + 0.001f);
  EXPECT_LT(std::fabs(world.position(id).z), 0.001f);
  EXPECT_LT(length(world.angular_velocity(id)), 0.01f);
  EXPECT_LT(length(world.linear_velocity(id)), 0.01f);
}

TEST(ShapeCapsule, LogCabinOfCapsulesStands) {
  // Layers of two parallel logs, each layer across the one below, so every
  // log rests on two crossings (a crossing is a single contact point).
  World3D world(awake());
  test::add_ground(world);
  std::vector<BodyId> ids;
  std::vector<Vec3> starts;
  const Quat along_z{det_sin(0.25f * kPi), 0.0f, 0.0f, det_cos(0.25f * kPi)};
  for (int layer = 0; layer < 5; ++layer) {
    for (int side = 0; side < 2; ++side) {
      BodyDef def;
      def.shape = Shape::make_capsule(0.2f, 0.8f);
      const float offset = side == 0 ? -0.6f : 0.6f;
      const float y = 0.2f + 0.4f * static_cast<float>(layer);
      def.position = layer % 2 == 0 ? Vec3{0.0f, y, offset} : Vec3{offset, y, 0.0f};
      def.rotation = layer % 2 == 0 ? lying_along_x() : along_z;
      ids.push_back(*world.create_body(def));
      starts.push_back(def.position);
    }
  }
  test::step_seconds(world, 10.0f);
  for (size_t i = 0; i < ids.size(); ++i) {
    const Vec3 p = world.position(ids[i]);
    const int layer = static_cast<int>(i / 2);
    // Round logs on round logs are in neutral balance (nothing resists
    // rolling yet), so they may creep a little; they must not come apart.
    EXPECT_LT(std::fabs(p.x - starts[i].x) + std::fabs(p.z - starts[i].z), 0.05f) << "log " << i;
    // Within the slop plus a millimetre per contact below it.
    EXPECT_NEAR(p.y, starts[i].y,
                (world.config().linear_slop_m + 0.001f) * static_cast<float>(layer + 1))
        << "log " << i;
  }
}

TEST(ShapeCapsule, SnapshotsKeepCapsulesAndStepOnBitForBit) {
  World3D world(awake());
  test::add_ground(world);
  for (int i = 0; i < 8; ++i) {
    BodyDef def;
    def.shape = i % 2 == 0 ? Shape::make_capsule(0.2f, 0.4f) : Shape::make_box({0.3f, 0.2f, 0.3f});
    def.position = {0.3f * static_cast<float>(i % 3), 0.5f + 0.7f * static_cast<float>(i), 0.1f};
    def.rotation = normalize(Quat{0.1f * static_cast<float>(i), 0.3f, 0.0f, 1.0f});
    ASSERT_TRUE(world.create_body(def).ok());
  }
  for (int i = 0; i < 90; ++i) world.step();
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  WorldState saved;
  world.save(saved);
  std::vector<uint64_t> sums;
  for (int i = 0; i < 90; ++i) {
    world.step();
    sums.push_back(world.checksum());
  }
  World3D loaded(awake());
  ASSERT_TRUE(loaded.deserialize(bytes).ok());
  world.restore(saved);
  for (size_t i = 0; i < sums.size(); ++i) {
    loaded.step();
    world.step();
    ASSERT_EQ(loaded.checksum(), sums[i]) << "loaded, step " << i;
    ASSERT_EQ(world.checksum(), sums[i]) << "restored, step " << i;
  }
}

}  // namespace
}  // namespace rwd::sim::d3
