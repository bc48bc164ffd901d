// SPDX-License-Identifier: MIT
// The World3D API: ids, validation, setters, quantization, mass.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(World3D, IdsAreLowestFreeSlotWithGenerations) {
  World3D world;
  BodyId a = test::add_box(world, {0.0f, 0.0f, 0.0f});
  BodyId b = test::add_box(world, {3.0f, 0.0f, 0.0f});
  BodyId c = test::add_box(world, {6.0f, 0.0f, 0.0f});
  EXPECT_EQ(a, (BodyId{0, 1}));
  EXPECT_EQ(b, (BodyId{1, 1}));
  EXPECT_EQ(c, (BodyId{2, 1}));
  ASSERT_TRUE(world.destroy_body(c).ok());
  ASSERT_TRUE(world.destroy_body(a).ok());
  EXPECT_FALSE(world.is_valid(a));
  EXPECT_EQ(world.destroy_body(a).code(), ErrorCode::kNotFound);
  BodyId d = test::add_box(world, {0.0f, 0.0f, 0.0f});
  EXPECT_EQ(d, (BodyId{0, 2}));  // lowest free slot, next generation
  BodyId e = test::add_box(world, {0.0f, 0.0f, 0.0f});
  EXPECT_EQ(e, (BodyId{2, 2}));
  EXPECT_EQ(world.body_count(), 3u);
  std::vector<BodyId> ids;
  world.body_ids(ids);
  ASSERT_EQ(ids.size(), 3u);
  EXPECT_EQ(ids[0], d);
  EXPECT_EQ(ids[1], b);
  EXPECT_EQ(ids[2], e);
  // Stale ids read as zero values.
  EXPECT_EQ(world.position(a), Vec3{});
  EXPECT_EQ(world.shape(a), nullptr);
}

TEST(World3D, MassFromDensityAndVolume) {
  World3D world;
  BodyDef box;
  box.shape = Shape::make_box({0.5f, 1.0f, 1.5f});
  box.density = 2.0f;
  EXPECT_NEAR(world.mass(*world.create_body(box)), 2.0f * 1.0f * 2.0f * 3.0f, 1e-4f);
  BodyDef ball;
  ball.shape = Shape::make_sphere(0.5f);
  ball.density = 3.0f;
  EXPECT_NEAR(world.mass(*world.create_body(ball)), 3.0f * 4.0f / 3.0f * kPi * 0.125f, 1e-4f);
  ball.kind = BodyKind::kKinematic;
  EXPECT_EQ(world.mass(*world.create_body(ball)), 0.0f);
}

TEST(World3D, BadCreateArgumentsAreRejectedWithoutChange) {
  World3D world;
  test::add_box(world, {0.0f, 0.0f, 0.0f});
  const uint64_t before = world.checksum();
  auto reject = [&](BodyDef def, const char* what) {
    auto r = world.create_body(def);
    EXPECT_FALSE(r.ok()) << what;
    if (!r.ok()) {
      EXPECT_EQ(r.status().code(), ErrorCode::kInvalidArgument) << what;
    }
  };
  BodyDef d;
  d.position.x = kNan;
  reject(d, "nan position");
  d = {};
  d.position.y = 1e6f;
  reject(d, "far position");
  d = {};
  d.rotation = {0.0f, 0.0f, 0.0f, 0.0f};
  reject(d, "zero rotation");
  d = {};
  d.rotation.w = kInf;
  reject(d, "inf rotation");
  d = {};
  d.shape = Shape::make_sphere(0.0f);
  reject(d, "zero radius");
  d.shape = Shape::make_sphere(1001.0f);
  reject(d, "huge radius");
  d.shape = Shape::make_box({0.5f, -1.0f, 0.5f});
  reject(d, "negative extent");
  d = {};
  d.density = 0.0f;
  reject(d, "zero density");
  d = {};
  d.linear_damping = -1.0f;
  reject(d, "negative damping");
  d = {};
  d.material.friction = 11.0f;
  reject(d, "friction");
  d = {};
  d.material.restitution = 1.5f;
  reject(d, "restitution");
  d = {};
  d.linear_velocity.z = kNan;
  reject(d, "nan velocity");
  d = {};
  d.kind = static_cast<BodyKind>(7);
  reject(d, "kind");
  EXPECT_EQ(world.checksum(), before);
  EXPECT_EQ(world.body_count(), 1u);
}

TEST(World3D, CapacityIsEnforced) {
  WorldConfig config;
  config.max_bodies = 2;
  World3D world(config);
  test::add_box(world, {0.0f, 0.0f, 0.0f});
  test::add_box(world, {2.0f, 0.0f, 0.0f});
  auto r = world.create_body(BodyDef{});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), ErrorCode::kCapacity);
}

TEST(World3D, SettersValidateQuantizeAndWake) {
  World3D world;
  BodyId ground = test::add_ground(world);
  BodyId box = test::add_box(world, {0.0f, 0.5f, 0.0f});
  const uint64_t before = world.checksum();
  EXPECT_EQ(world.set_linear_velocity({9, 1}, {}).code(), ErrorCode::kNotFound);
  EXPECT_EQ(world.set_transform(box, {kNan, 0.0f, 0.0f}, Quat{}).code(),
            ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.set_transform(box, {}, Quat{0.0f, 0.0f, 0.0f, 0.0f}).code(),
            ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.set_angular_velocity(box, {0.0f, kInf, 0.0f}).code(),
            ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.apply_linear_impulse(ground, {1.0f, 0.0f, 0.0f}, {}).code(),
            ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.apply_force(ground, {1.0f, 0.0f, 0.0f}).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.set_linear_velocity(ground, {1.0f, 0.0f, 0.0f}).code(),
            ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.apply_force(box, {kNan, 0.0f, 0.0f}).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.checksum(), before);

  // Accepted values land on the 2^-20 grid.
  ASSERT_TRUE(world.set_linear_velocity(box, {0.1f, 0.0f, 0.0f}).ok());
  EXPECT_EQ(world.linear_velocity(box).x, quantize(0.1f));
  EXPECT_NE(world.linear_velocity(box).x, 0.1f);
  ASSERT_TRUE(world.set_transform(box, {0.0f, 3.0f, 0.0f}, Quat{0.0f, 0.0f, 0.0f, 2.0f}).ok());
  EXPECT_EQ(world.rotation(box), Quat{});  // normalized
  ASSERT_TRUE(world.set_user_data(box, 42).ok());
  EXPECT_EQ(world.user_data(box), 42u);

  // An impulse at the centre changes only the linear velocity: dv = J / m.
  ASSERT_TRUE(world.set_linear_velocity(box, {}).ok());
  ASSERT_TRUE(world.apply_linear_impulse(box, {0.0f, 0.0f, 500.0f}, world.position(box)).ok());
  EXPECT_NEAR(world.linear_velocity(box).z, 0.5f, 1e-6f);
  EXPECT_EQ(world.angular_velocity(box), Vec3{});
  // Off centre it also spins the box.
  ASSERT_TRUE(world
                  .apply_linear_impulse(box, {0.0f, 0.0f, 500.0f},
                                        world.position(box) + Vec3{0.5f, 0.0f, 0.0f})
                  .ok());
  EXPECT_LT(world.angular_velocity(box).y, 0.0f);
}

TEST(World3D, ForceActsForOneStepOnly) {
  WorldConfig config;
  config.gravity = {};
  World3D world(config);
  BodyId box = test::add_box(world, {0.0f, 0.0f, 0.0f});
  ASSERT_TRUE(world.apply_force(box, {1000.0f * 60.0f, 0.0f, 0.0f}).ok());
  world.step();
  // a = F/m = 60 m/s^2 for 1/60 s.
  EXPECT_NEAR(world.linear_velocity(box).x, 1.0f, 1e-4f);
  world.step();
  EXPECT_NEAR(world.linear_velocity(box).x, 1.0f, 1e-4f);
}

TEST(World3D, FreeFallMatchesKinematics) {
  World3D world;
  BodyId ball = test::add_sphere(world, {0.0f, 100.0f, 0.0f});
  test::step_seconds(world, 1.0f);
  // Semi-implicit Euler with 240 substeps of h: y drops g h^2 n(n+1)/2.
  const double h = 1.0 / 240.0;
  const double drop = 9.81 * h * h * 240.0 * 241.0 / 2.0;
  EXPECT_NEAR(world.position(ball).y, 100.0 - drop, 1e-3);
  EXPECT_NEAR(world.linear_velocity(ball).y, -9.81f, 1e-3f);
}

TEST(World3D, InvalidConfigIsReportedAndReplaced) {
  WorldConfig bad;
  bad.substeps = 0;
  bad.tick_seconds = kNan;
  EXPECT_EQ(World3D::validate_config(bad).code(), ErrorCode::kInvalidArgument);
  World3D world(bad);
  EXPECT_EQ(world.config().substeps, WorldConfig{}.substeps);
  EXPECT_EQ(world.config().tick_seconds, quantize(WorldConfig{}.tick_seconds));
  EXPECT_TRUE(World3D::validate_config(WorldConfig{}).ok());
}

TEST(World3D, CreateRefusesABadConfigInsteadOfRepairingIt) {
  WorldConfig bad;
  bad.substeps = 0;
  auto refused = World3D::create(bad);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(refused.status().message(), World3D::validate_config(bad).message());
  WorldConfig good;
  good.substeps = 8;
  auto made = World3D::create(good);
  ASSERT_TRUE(made.ok()) << made.status().message();
  EXPECT_EQ((*made)->config().substeps, 8u);
}

// A substep longer than 1/240 s is refused, whichever of the tick and the
// substeps makes it so; a 60 Hz tick cut in four is exactly at the limit.
TEST(World3D, SubstepsLongerThanA240thOfASecondAreRefused) {
  const auto config = [](float tick_seconds, int32_t substeps) {
    WorldConfig c;
    c.tick_seconds = tick_seconds;
    c.substeps = substeps;
    return c;
  };
  EXPECT_TRUE(World3D::validate_config(config(1.0f / 60.0f, 4)).ok());
  EXPECT_TRUE(World3D::validate_config(config(1.0f / 30.0f, 8)).ok());
  EXPECT_TRUE(World3D::validate_config(config(1.0f / 120.0f, 2)).ok());
  EXPECT_TRUE(World3D::validate_config(config(1.0f / 240.0f, 1)).ok());
  EXPECT_TRUE(World3D::validate_config(config(0.1f, 24)).ok());
  for (const WorldConfig& c :
       {config(1.0f / 60.0f, 1), config(1.0f / 60.0f, 2), config(1.0f / 60.0f, 3),
        config(1.0f / 30.0f, 7), config(1.0f / 120.0f, 1), config(1.0f / 200.0f, 1),
        config(0.1f, 23)}) {
    const Status s = World3D::validate_config(c);
    EXPECT_EQ(s.code(), ErrorCode::kInvalidArgument) << c.tick_seconds << " / " << c.substeps;
    EXPECT_NE(s.message().find("1/240 s"), std::string::npos) << s.message();
  }
  // Repaired as one value: a 30 Hz tick with 8 substeps keeps both, one
  // with 4 keeps neither (the tick needs more than the default substeps),
  // a 120 Hz tick with 2 keeps both, a 60 Hz tick with 2 keeps the tick.
  World3D both(config(1.0f / 30.0f, 8));
  EXPECT_EQ(both.config().tick_seconds, quantize(1.0f / 30.0f));
  EXPECT_EQ(both.config().substeps, 8);
  World3D neither(config(1.0f / 30.0f, 4));
  EXPECT_EQ(neither.config().tick_seconds, quantize(WorldConfig{}.tick_seconds));
  EXPECT_EQ(neither.config().substeps, WorldConfig{}.substeps);
  World3D fast(config(1.0f / 120.0f, 2));
  EXPECT_EQ(fast.config().tick_seconds, quantize(1.0f / 120.0f));
  EXPECT_EQ(fast.config().substeps, 2);
  World3D tick_only(config(1.0f / 60.0f, 2));
  EXPECT_EQ(tick_only.config().tick_seconds, quantize(1.0f / 60.0f));
  EXPECT_EQ(tick_only.config().substeps, WorldConfig{}.substeps);
}

TEST(World3D, LayerMasksFilterCollisions) {
  World3D world;
  BodyDef ground;
  ground.kind = BodyKind::kStatic;
  ground.shape = Shape::make_box({5.0f, 0.5f, 5.0f});
  ground.position = {0.0f, -0.5f, 0.0f};
  ground.layer = 1;
  ASSERT_TRUE(world.create_body(ground).ok());
  BodyDef ghost;
  ghost.position = {0.0f, 0.5f, 0.0f};
  ghost.mask = 2;  // does not collide with layer 1
  BodyId g = *world.create_body(ghost);
  test::step_seconds(world, 0.5f);
  EXPECT_LT(world.position(g).y, -0.5f);  // fell through
}

TEST(World3D, StageTimesAreDiagnosticsOnly) {
  // Two worlds, one timing its stages: same results bit for bit; times are
  // zero when off and add up to something when on.
  World3D timed;
  World3D plain;
  for (World3D* w : {&timed, &plain}) {
    test::add_ground(*w);
    for (int i = 0; i < 10; ++i) test::add_box(*w, {0.1f * i, 0.5f + 1.1f * i, 0.0f});
  }
  timed.set_stage_timing(true);
  double total = 0.0;
  for (int i = 0; i < 60; ++i) {
    timed.step();
    plain.step();
    ASSERT_EQ(timed.checksum(), plain.checksum());
    const StepStats::StageTimes& t = timed.stats().times;
    for (double v : {t.broadphase_us, t.narrowphase_us, t.events_us, t.solver_us, t.sleep_us}) {
      EXPECT_GE(v, 0.0);
      total += v;
    }
    EXPECT_EQ(plain.stats().times.solver_us, 0.0);
  }
  EXPECT_GT(total, 0.0);
  timed.set_stage_timing(false);
  timed.step();
  EXPECT_EQ(timed.stats().times.solver_us, 0.0);
}

}  // namespace
}  // namespace rwd::sim
