// SPDX-License-Identifier: MIT
// The 2D world's queries: analytic ray hits on every shape type, filters,
// ordering, overlap and AABB results, shape casts landing where geometry
// says, nearest and signed distances, no allocation once warm and no change
// to the state.
#include <optional>
#include <vector>

// GCC sees the counter's malloc-backed operator new inlined next to the
// vectors' frees here and warns of a mismatch that is not one.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
#include "allocation_counter.h"
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using testing::add_body;

// Results are rounded once to Fx; allow a few ulps (2^-16 m each).
constexpr int32_t kUlps = 3;

void expect_near(Vec2 got, Vec2 want, int32_t ulps = kUlps) {
  EXPECT_NEAR(got.x.raw(), want.x.raw(), ulps) << "x";
  EXPECT_NEAR(got.y.raw(), want.y.raw(), ulps) << "y";
}
void expect_near(Fx got, Fx want, int32_t ulps = kUlps) {
  EXPECT_NEAR(got.raw(), want.raw(), ulps);
}

TEST(World2DQuery, RayHitsCircleBoxCapsuleSegmentAnalytically) {
  World2D world;
  const BodyId2D circle = add_body(world, BodyKind2D::kStatic, make_circle(1_fx), {5_fx, Fx()});
  const BodyId2D box = add_body(world, BodyKind2D::kStatic, make_box(1_fx, 0.5_fx), {Fx(), 5_fx});
  const BodyId2D capsule = add_body(
      world, BodyKind2D::kStatic, make_capsule({-1_fx, Fx()}, {1_fx, Fx()}, 0.5_fx), {Fx(), -5_fx});
  const BodyId2D segment = add_body(world, BodyKind2D::kStatic,
                                    make_segment({Fx(), -1_fx}, {Fx(), 1_fx}), {-5_fx, Fx()});

  auto h = world.raycast({}, {10_fx, Fx()});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->body, circle);
  expect_near(h->point, {4_fx, Fx()});
  expect_near(h->normal, {-1_fx, Fx()});
  expect_near(h->distance, 4_fx);
  expect_near(h->fraction, 0.4_fx);

  h = world.raycast({}, {Fx(), 10_fx});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->body, box);
  expect_near(h->point, {Fx(), 4.5_fx});
  expect_near(h->normal, {Fx(), -1_fx});
  expect_near(h->distance, 4.5_fx);

  // The capsule's flat side, then its round end from the side, then the
  // round end at 45 degrees: the hit lies on the cap circle.
  h = world.raycast({}, {Fx(), -10_fx});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->body, capsule);
  expect_near(h->point, {Fx(), -4.5_fx});
  expect_near(h->normal, {Fx(), 1_fx});
  h = world.raycast({3_fx, -5_fx}, {-4_fx, Fx()});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->body, capsule);
  expect_near(h->point, {1.5_fx, -5_fx});
  expect_near(h->normal, {1_fx, Fx()});
  h = world.raycast({1.3_fx, Fx()}, {Fx(), -10_fx});
  ASSERT_TRUE(h);
  // x = 1.3 meets the cap circle (centre (1, -5), r 0.5) at y = -5 + 0.4.
  expect_near(h->point, {1.3_fx, -4.6_fx});
  expect_near(h->normal, {0.6_fx, 0.8_fx});

  // The segment is two-sided.
  h = world.raycast({}, {-10_fx, Fx()});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->body, segment);
  expect_near(h->point, {-5_fx, Fx()});
  expect_near(h->normal, {1_fx, Fx()});
  h = world.raycast({-8_fx, 0.5_fx}, {10_fx, Fx()});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->body, segment);
  expect_near(h->point, {-5_fx, 0.5_fx});
  expect_near(h->normal, {-1_fx, Fx()});

  // Too short, zero length, and from inside: no hit.
  EXPECT_FALSE(world.raycast({}, {3.9_fx, Fx()}));
  EXPECT_FALSE(world.raycast({}, {}));
  EXPECT_FALSE(world.raycast({5_fx, Fx()}, {0.5_fx, Fx()}));
  EXPECT_FALSE(world.raycast({Fx(), 5_fx}, {0.2_fx, 0.2_fx}));
}

TEST(World2DQuery, RayHitsRoundedAndTurnedPolygons) {
  World2D world;
  const Vec2 square[] = {{-1_fx, -1_fx}, {1_fx, -1_fx}, {1_fx, 1_fx}, {-1_fx, 1_fx}};
  add_body(world, BodyKind2D::kStatic, make_polygon(square, 0.25_fx), {5_fx, Fx()});
  auto h = world.raycast({}, {10_fx, Fx()});
  ASSERT_TRUE(h);
  expect_near(h->point, {3.75_fx, Fx()});
  expect_near(h->normal, {-1_fx, Fx()});
  // The rounded corner: a ray along y = 1.2 meets the disc at (1-, 1) + r.
  h = world.raycast({Fx(), 1.2_fx}, {10_fx, Fx()});
  ASSERT_TRUE(h);
  expect_near(h->point, {3.85_fx, 1.2_fx});
  expect_near(h->normal, {-0.6_fx, 0.8_fx});

  World2D turned;
  add_body(turned, BodyKind2D::kStatic, make_box(1_fx, 1_fx), {5_fx, Fx()}, fixed::Fx::pi() / 4);
  h = turned.raycast({}, {10_fx, Fx()});
  ASSERT_TRUE(h);
  // The corner at 5 - sqrt(2).
  expect_near(h->point, {Fx::from_raw(234998), Fx()}, 8);
  EXPECT_NEAR(fixed::abs(h->normal.x).raw(), 46341, 8);
  EXPECT_NEAR(fixed::abs(h->normal.y).raw(), 46341, 8);
}

TEST(World2DQuery, FiltersLayersSensorsKindsAndDisabledBodies) {
  World2D world;
  BodyDef2D def;
  def.kind = BodyKind2D::kStatic;
  def.shape = *make_circle(0.5_fx);
  def.position = {2_fx, Fx()};
  def.layer = 2;
  const BodyId2D layered = *world.create_body(def);
  def.position = {4_fx, Fx()};
  def.layer = 1;
  def.sensor = true;
  const BodyId2D sensor = *world.create_body(def);
  def.position = {6_fx, Fx()};
  def.sensor = false;
  def.kind = BodyKind2D::kDynamic;
  const BodyId2D dynamic = *world.create_body(def);

  EXPECT_EQ(world.raycast({}, {10_fx, Fx()})->body, layered);
  QueryFilter2D f;
  f.layer_mask = 1;
  EXPECT_EQ(world.raycast({}, {10_fx, Fx()}, f)->body, dynamic);
  f.include_sensors = true;
  EXPECT_EQ(world.raycast({}, {10_fx, Fx()}, f)->body, sensor);
  f.include_dynamic = false;
  f.include_sensors = false;
  EXPECT_FALSE(world.raycast({}, {10_fx, Fx()}, f));
  QueryFilter2D ignore;
  ignore.ignore = layered;
  EXPECT_EQ(world.raycast({}, {10_fx, Fx()}, ignore)->body, dynamic);
  ASSERT_TRUE(world.set_enabled(layered, false).ok());
  EXPECT_EQ(world.raycast({}, {10_fx, Fx()})->body, dynamic);

  std::vector<BodyId2D> ids;
  world.query_aabb({-10_fx, -10_fx}, {10_fx, 10_fx}, {}, ids);
  EXPECT_EQ(ids, (std::vector<BodyId2D>{dynamic}));
  QueryFilter2D all;
  all.include_sensors = true;
  world.query_aabb({-10_fx, -10_fx}, {10_fx, 10_fx}, all, ids);
  EXPECT_EQ(ids, (std::vector<BodyId2D>{sensor, dynamic}));
}

TEST(World2DQuery, RaycastAllNearToFarTiesByIndex) {
  World2D world;
  const BodyId2D far = add_body(world, BodyKind2D::kStatic, make_circle(0.5_fx), {8_fx, Fx()});
  const BodyId2D near = add_body(world, BodyKind2D::kStatic, make_circle(0.5_fx), {2_fx, Fx()});
  const BodyId2D mid_a =
      add_body(world, BodyKind2D::kStatic, make_box(0.5_fx, 0.5_fx), {5_fx, Fx()});
  const BodyId2D mid_b = add_body(world, BodyKind2D::kStatic, make_circle(0.5_fx), {5_fx, Fx()});
  add_body(world, BodyKind2D::kStatic, make_circle(0.5_fx), {5_fx, 3_fx});  // off the ray
  std::vector<RayHit2D> hits;
  world.raycast_all({}, {10_fx, Fx()}, {}, hits);
  ASSERT_EQ(hits.size(), 4u);
  EXPECT_EQ(hits[0].body, near);
  EXPECT_EQ(hits[1].body, mid_a);
  EXPECT_EQ(hits[2].body, mid_b);
  EXPECT_EQ(hits[3].body, far);
  expect_near(hits[1].distance, 4.5_fx);
  expect_near(hits[2].distance, 4.5_fx);
  // The closest-hit ray agrees, and equal hits go to the lower index.
  EXPECT_EQ(world.raycast({3_fx, Fx()}, {10_fx, Fx()})->body, mid_a);
  // Cleared, not appended to.
  world.raycast_all({}, {Fx(), 10_fx}, {}, hits);
  EXPECT_TRUE(hits.empty());
}

TEST(World2DQuery, AabbAndExactOverlap) {
  World2D world;
  const BodyId2D a = add_body(world, BodyKind2D::kStatic, make_box(1_fx, 1_fx), {});
  const BodyId2D b = add_body(world, BodyKind2D::kDynamic, make_circle(1_fx), {3_fx, Fx()});
  const BodyId2D c =
      add_body(world, BodyKind2D::kStatic, make_box(1_fx, 1_fx), {Fx(), 3_fx}, fixed::Fx::pi() / 4);
  std::vector<BodyId2D> ids;
  world.query_aabb({0.5_fx, -0.5_fx}, {2_fx, 0.5_fx}, {}, ids);
  EXPECT_EQ(ids, (std::vector<BodyId2D>{a, b}));
  // Touching bounds count.
  world.query_aabb({-3_fx, 0.5_fx}, {-1_fx, 1.2_fx}, {}, ids);
  EXPECT_EQ(ids, (std::vector<BodyId2D>{a}));

  // A small circle in the corner between the box and the disc: inside both
  // bounds, overlapping neither.
  const Shape2D probe = *make_circle(0.2_fx);
  world.overlap(probe, {1.5_fx, 0.9_fx}, Fx(), {}, ids);
  EXPECT_TRUE(ids.empty());
  world.overlap(probe, {1.1_fx, 0.5_fx}, Fx(), {}, ids);
  EXPECT_EQ(ids, (std::vector<BodyId2D>{a}));
  // The turned box's bounds reach (1.4, 1.6), its surface does not.
  world.overlap(probe, {0.95_fx, 1.8_fx}, Fx(), {}, ids);
  EXPECT_TRUE(ids.empty());
  const Shape2D wide = *make_capsule({-2_fx, Fx()}, {2_fx, Fx()}, 0.25_fx);
  world.overlap(wide, {1.5_fx, 1_fx}, Fx(), {}, ids);
  EXPECT_EQ(ids, (std::vector<BodyId2D>{a, b}));
  world.overlap(wide, {Fx(), 2_fx}, fixed::Fx::pi() / 2, {}, ids);
  EXPECT_EQ(ids, (std::vector<BodyId2D>{a, c}));
}

TEST(World2DQuery, ShapeCastLandsAtTheAnalyticDistance) {
  World2D world;
  const BodyId2D wall = add_body(world, BodyKind2D::kStatic, make_box(1_fx, 1_fx), {5_fx, Fx()});
  const BodyId2D ground = add_body(world, BodyKind2D::kStatic,
                                   make_segment({-20_fx, Fx()}, {20_fx, Fx()}), {Fx(), -3_fx});
  // A disc of radius 0.5 from x = 0 meets the wall face x = 4 at x = 3.5.
  auto h = world.shape_cast(*make_circle(0.5_fx), {}, Fx(), {10_fx, Fx()});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->body, wall);
  expect_near(h->fraction, 0.35_fx, 1);
  EXPECT_LE(h->fraction.raw(), (0.35_fx).raw());
  expect_near(h->normal, {-1_fx, Fx()});
  expect_near(h->point, {4_fx, Fx()});
  // A box falling onto the ground segment: its bottom (y = -0.5) reaches
  // y = -3 after 2.5 of 5 m.
  h = world.shape_cast(*make_box(0.5_fx, 0.5_fx), {-5_fx, Fx()}, Fx(), {Fx(), -5_fx});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->body, ground);
  expect_near(h->fraction, 0.5_fx, 1);
  expect_near(h->normal, {Fx(), 1_fx});
  // A capsule moving diagonally onto the wall's top-left corner (4, 1):
  // its lower cap centre (x, y - 0.5) touches it at distance 0.25.
  const Shape2D capsule = *make_capsule({Fx(), -0.5_fx}, {Fx(), 0.5_fx}, 0.25_fx);
  h = world.shape_cast(capsule, {2_fx, 3.5_fx}, Fx(), {4_fx, -4_fx});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->body, wall);
  // The cap centre runs (2, 3) + t (4, -4); at t = 0.5 - 0.25 / (4 sqrt 2)
  // it is 0.25 from the corner along (-1, 1) / sqrt 2.
  expect_near(h->fraction, Fx::from_raw(29872), 2);
  expect_near(h->normal, {Fx::from_raw(-46341), Fx::from_raw(46341)}, 40);
  // A turned box cast at a box: it stops when its corner meets the face.
  h = world.shape_cast(*make_box(0.5_fx, 0.5_fx), {Fx(), Fx()}, fixed::Fx::pi() / 4, {5_fx, Fx()});
  ASSERT_TRUE(h);
  // Corner at x = sqrt(0.5) reaches x = 4: fraction (4 - 0.70711) / 5.
  expect_near(h->fraction, Fx::from_raw(43161), 2);
  // Misses, and a body already touched but moved away from.
  EXPECT_FALSE(world.shape_cast(*make_circle(0.5_fx), {Fx(), 5_fx}, Fx(), {10_fx, Fx()}));
  EXPECT_FALSE(world.shape_cast(*make_circle(0.5_fx), {3.5_fx, Fx()}, Fx(), {-1_fx, Fx()}));
  h = world.shape_cast(*make_circle(0.5_fx), {3.5_fx, Fx()}, Fx(), {1_fx, Fx()});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->fraction, Fx());
}

TEST(World2DQuery, NearestBodyAndSignedDistance) {
  World2D world;
  const BodyId2D box = add_body(world, BodyKind2D::kStatic, make_box(2_fx, 1_fx), {});
  const BodyId2D disc = add_body(world, BodyKind2D::kStatic, make_circle(1_fx), {6_fx, Fx()});
  auto n = world.nearest_body({4_fx, Fx()}, 10_fx);
  ASSERT_TRUE(n);
  // 2 m from the box face, 1 m from the disc.
  EXPECT_EQ(n->body, disc);
  expect_near(n->distance, 1_fx);
  expect_near(n->point, {5_fx, Fx()});
  n = world.nearest_body({3_fx, Fx()}, 10_fx);
  ASSERT_TRUE(n);
  EXPECT_EQ(n->body, box);  // 1 m from both: the lower index
  EXPECT_FALSE(world.nearest_body({3_fx, 5_fx}, 3_fx));
  n = world.nearest_body({0.5_fx, 0.5_fx}, Fx());
  ASSERT_TRUE(n);
  EXPECT_EQ(n->body, box);
  EXPECT_EQ(n->distance, Fx());

  expect_near(world.signed_distance(box, {Fx(), 3_fx}), 2_fx);
  expect_near(world.signed_distance(box, {Fx(), 0.25_fx}), -0.75_fx);
  expect_near(world.signed_distance(box, {5_fx, 5_fx}), 5_fx);  // corner (2, 1): 3-4-5
  expect_near(world.signed_distance(disc, {6_fx, 0.5_fx}), -0.5_fx);
  expect_near(world.signed_distance({4_fx, Fx()}), 1_fx);
  expect_near(world.signed_distance({6_fx, Fx()}), -1_fx);
  EXPECT_EQ(world.signed_distance(BodyId2D{}, {}), Fx::max());
  EXPECT_EQ(World2D().signed_distance({}), Fx::max());
}

TEST(World2DQuery, WarmQueriesDoNotAllocateOrChangeTheState) {
  World2D world;
  testing::add_round_ground(world);
  for (int i = 0; i < 12; ++i) {
    add_body(world, BodyKind2D::kDynamic, make_box(0.4_fx, 0.4_fx), {Fx(i) - 6_fx, 0.5_fx});
    add_body(world, BodyKind2D::kDynamic, make_circle(0.3_fx), {Fx(i) - 6_fx, 2_fx});
  }
  for (int i = 0; i < 30; ++i) world.step();
  const uint64_t before = world.checksum();
  std::vector<RayHit2D> hits;
  std::vector<BodyId2D> ids;
  const Shape2D probe = *make_capsule({-1_fx, Fx()}, {1_fx, Fx()}, 0.3_fx);
  auto run = [&] {
    world.raycast_all({-10_fx, 0.5_fx}, {20_fx, Fx()}, {}, hits);
    world.query_aabb({-10_fx, -1_fx}, {10_fx, 3_fx}, {}, ids);
    world.overlap(probe, {Fx(), 1_fx}, 0.3_fx, {}, ids);
    EXPECT_TRUE(world.raycast({Fx(), 10_fx}, {Fx(), -20_fx}));
    EXPECT_TRUE(world.shape_cast(probe, {Fx(), 10_fx}, Fx(), {Fx(), -20_fx}));
    EXPECT_TRUE(world.nearest_body({Fx(), 5_fx}, 10_fx));
    EXPECT_LT(world.signed_distance({Fx(), 5_fx}), 5_fx);
  };
  run();  // grows the buffers
  EXPECT_EQ(hits.size(), 12u);
  EXPECT_FALSE(ids.empty());
  test::AllocationCounter::start();
  run();
  EXPECT_EQ(test::AllocationCounter::stop(), 0);
  EXPECT_EQ(world.checksum(), before);
  // After a step the tree is rebuilt into the buffers it already has.
  world.step();
  test::AllocationCounter::start();
  run();
  EXPECT_EQ(test::AllocationCounter::stop(), 0);
}

TEST(World2DQuery, SeesEveryEditStepAndRestore) {
  World2D world;
  const BodyId2D a = add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {5_fx, Fx()});
  EXPECT_EQ(world.raycast({}, {10_fx, Fx()})->body, a);
  World2DState saved;
  world.save(saved);
  ASSERT_TRUE(world.set_transform(a, {5_fx, 3_fx}, Fx()).ok());
  EXPECT_FALSE(world.raycast({}, {10_fx, Fx()}));
  world.restore(saved);
  EXPECT_EQ(world.raycast({}, {10_fx, Fx()})->body, a);
  ASSERT_TRUE(world.set_enabled(a, false).ok());
  EXPECT_FALSE(world.raycast({}, {10_fx, Fx()}));
  ASSERT_TRUE(world.set_enabled(a, true).ok());
  EXPECT_TRUE(world.raycast({}, {10_fx, Fx()}));
  ASSERT_TRUE(world.destroy_body(a).ok());
  EXPECT_FALSE(world.raycast({}, {10_fx, Fx()}));
  const BodyId2D b = add_body(world, BodyKind2D::kDynamic, make_circle(0.5_fx), {3_fx, 2_fx});
  EXPECT_FALSE(world.raycast({}, {10_fx, Fx()}));
  // Falling through the ray's line under gravity.
  for (int i = 0; i < 90 && !world.raycast({}, {10_fx, Fx()}); ++i) world.step();
  ASSERT_TRUE(world.raycast({}, {10_fx, Fx()}));
  EXPECT_EQ(world.raycast({}, {10_fx, Fx()})->body, b);
  std::vector<uint8_t> bytes;
  World2D other;
  other.serialize(bytes);
  ASSERT_TRUE(world.deserialize(bytes).ok());
  EXPECT_FALSE(world.raycast({}, {10_fx, Fx()}));
}

TEST(World2DQuery, TreeAgreesWithEveryBodyTestedAlone) {
  // Hundreds of bodies in a pseudo-random field: the tree-culled overlap and
  // nearest queries must agree with signed_distance() asked of each body.
  World2D world;
  uint32_t seed = 12345;
  auto next = [&](int32_t range) {
    seed = seed * 1664525u + 1013904223u;
    return Fx::from_raw(static_cast<int32_t>((seed >> 8) % static_cast<uint32_t>(range)));
  };
  std::vector<BodyId2D> bodies;
  for (int i = 0; i < 300; ++i) {
    const Vec2 at{next(40 << 16) - 20_fx, next(40 << 16) - 20_fx};
    const Fx size = next(1 << 16) / 2 + 0.1_fx;
    const Result<Shape2D> shape = i % 3 == 0 ? make_circle(size)
                                  : i % 3 == 1
                                      ? make_box(size, size / 2)
                                      : make_capsule({-size, Fx()}, {size, Fx()}, size / 3);
    bodies.push_back(add_body(world, BodyKind2D::kStatic, shape, at, next(6 << 16)));
  }
  std::vector<BodyId2D> got;
  auto check = [&](int queries) {
    for (int q = 0; q < queries; ++q) {
      const Vec2 p{next(44 << 16) - 22_fx, next(44 << 16) - 22_fx};
      const Fx r = next(3 << 16) + 0.05_fx;
      world.overlap(*make_circle(r), p, Fx(), {}, got);
      std::vector<BodyId2D> want;
      Fx nearest = Fx::max();
      for (const BodyId2D id : bodies) {
        const Fx d = world.signed_distance(id, p);
        if (d < r) want.push_back(id);
        nearest = fixed::min(nearest, d);
      }
      // Overlap is decided in Q32.32, signed_distance() rounds to Fx: drop
      // bodies within an ulp of touching from the comparison.
      auto near_touch = [&](BodyId2D id) {
        return fixed::abs(world.signed_distance(id, p) - r).raw() <= 1;
      };
      std::erase_if(got, near_touch);
      std::erase_if(want, near_touch);
      EXPECT_EQ(got, want) << q;
      EXPECT_EQ(world.signed_distance(p), nearest) << q;
      const auto n = world.nearest_body(p, 100_fx);
      ASSERT_TRUE(n);
      EXPECT_EQ(n->distance, fixed::max(nearest, Fx())) << q;
    }
  };
  check(40);
  // Every body teleported: the tree is refitted, not rebuilt, and must
  // still agree; then one body at a time, past the refit limit.
  for (const BodyId2D id : bodies) {
    ASSERT_TRUE(
        world.set_transform(id, {next(40 << 16) - 20_fx, next(40 << 16) - 20_fx}, Fx()).ok());
  }
  check(20);
  for (int i = 0; i < 40; ++i) {
    ASSERT_TRUE(
        world
            .set_transform(bodies[static_cast<size_t>(i) * 7], {next(40 << 16) - 20_fx, Fx()}, Fx())
            .ok());
    check(2);
  }
}

}  // namespace
}  // namespace rwd::sim2d
