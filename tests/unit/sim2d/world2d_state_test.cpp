// SPDX-License-Identifier: MIT
#include <vector>

#include "rewind/core/state_hasher.h"
#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using testing::add_body;

// A small heap of balls falling into a bowl of static circles.
void build_heap(World2D& world) {
  for (int i = -3; i <= 3; ++i) {
    add_body(world, BodyKind2D::kStatic, make_circle(1_fx), {Fx(i) * 2, Fx(std::abs(i)) - 1_fx});
  }
  for (int i = 0; i < 30; ++i) {
    BodyDef2D def;
    def.shape = *make_circle(0.25_fx + Fx::ratio(i % 3, 20));
    def.position = {Fx::ratio(i % 6 - 3, 2), 3_fx + Fx::ratio(i, 3)};
    def.material.restitution = Fx::ratio(i % 4, 10);
    ASSERT_TRUE(world.create_body(def).ok());
  }
}

TEST(World2DState, RestoreThenStepEqualsSteppingOn) {
  World2D world;
  build_heap(world);
  for (int i = 0; i < 30; ++i) world.step();
  World2DState saved;
  world.save(saved);
  std::vector<uint64_t> expected;
  for (int i = 0; i < 60; ++i) {
    world.step();
    expected.push_back(world.checksum());
  }
  world.restore(saved);
  for (int i = 0; i < 60; ++i) {
    world.step();
    ASSERT_EQ(world.checksum(), expected[static_cast<size_t>(i)]) << "tick " << i;
  }
}

TEST(World2DState, SerializeRoundTripsBitForBit) {
  World2D world;
  build_heap(world);
  for (int i = 0; i < 45; ++i) world.step();
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  World2D copy;
  ASSERT_TRUE(copy.deserialize(bytes).ok());
  EXPECT_EQ(copy.checksum(), world.checksum());
  for (int i = 0; i < 30; ++i) {
    world.step();
    copy.step();
  }
  EXPECT_EQ(copy.checksum(), world.checksum());
  std::vector<uint8_t> again;
  copy.serialize(again);
  world.serialize(bytes);
  EXPECT_EQ(again, bytes);
}

// The broadphase keeps its tree between steps while the same bodies are
// in it; bodies made, destroyed, disabled and enabled between steps must
// find the same pairs as a world whose step starts from nothing.
TEST(World2DState, BodiesComingAndGoingFindTheSamePairsAsAFreshWorld) {
  World2D world;
  build_heap(world);
  std::vector<BodyId2D> extra;
  std::vector<uint8_t> bytes;
  for (int tick = 0; tick < 120; ++tick) {
    if (tick % 7 == 3) {
      BodyDef2D def;
      def.shape = *make_box(0.2_fx, 0.2_fx);
      def.position = {Fx::ratio(tick % 5 - 2, 2), 4_fx};
      const auto made = world.create_body(def);
      ASSERT_TRUE(made.ok());
      extra.push_back(*made);
    }
    if (tick % 11 == 5 && !extra.empty()) {
      ASSERT_TRUE(world.destroy_body(extra.front()).ok());
      extra.erase(extra.begin());
    }
    if (tick % 13 == 6 && !extra.empty()) {
      ASSERT_TRUE(world.set_enabled(extra.back(), tick % 26 != 6).ok());
    }
    world.serialize(bytes);
    World2D fresh;
    ASSERT_TRUE(fresh.deserialize(bytes).ok());
    world.step();
    fresh.step();
    ASSERT_EQ(world.checksum(), fresh.checksum()) << "tick " << tick;
  }
}

TEST(World2DState, CorruptBytesAreRefusedAndChangeNothing) {
  World2D world;
  build_heap(world);
  world.step();
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  World2D target;
  add_body(target, BodyKind2D::kDynamic, make_circle(1_fx), {});
  const uint64_t before = target.checksum();
  // Every truncation, and a flipped byte in every position of the header
  // and first body, is refused or decodes to a valid world.
  for (size_t n = 0; n < bytes.size(); n += 7) {
    const Status s = target.deserialize(std::span(bytes).first(n));
    EXPECT_EQ(s.code(), ErrorCode::kCorrupt) << n;
    EXPECT_EQ(target.checksum(), before);
  }
  std::vector<uint8_t> flipped = bytes;
  flipped[0] ^= 1;
  EXPECT_EQ(target.deserialize(flipped).code(), ErrorCode::kCorrupt);
  EXPECT_EQ(target.checksum(), before);
}

TEST(World2DState, ChecksumSeesEveryStepAndNoPadding) {
  World2D a;
  World2D b;
  build_heap(a);
  build_heap(b);
  EXPECT_EQ(a.checksum(), b.checksum());
  a.step();
  EXPECT_NE(a.checksum(), b.checksum());
  b.step();
  EXPECT_EQ(a.checksum(), b.checksum());
  ASSERT_TRUE(a.perturb_for_drill());
  EXPECT_NE(a.checksum(), b.checksum());
}

// A heavy ball at the speed cap knocks a light one away (restitution 1,
// which after the solve would throw it faster than the cap): the step caps
// it, so every state it leaves loads.
TEST(World2DState, EveryStepLeavesAStateThatLoads) {
  World2DConfig config;
  config.gravity = {};
  config.max_linear_speed = 5_fx;
  World2D world(config);
  BodyDef2D heavy;
  heavy.shape = *make_circle(0.5_fx);
  heavy.density = 100_fx;
  heavy.linear_velocity = {5_fx, Fx()};
  heavy.material.restitution = 1_fx;
  ASSERT_TRUE(world.create_body(heavy).ok());
  BodyDef2D light = heavy;
  light.density = 1_fx;
  light.linear_velocity = {};
  light.position = {1.2_fx, Fx()};
  const BodyId2D struck = *world.create_body(light);
  std::vector<uint8_t> bytes;
  for (int t = 0; t < 30; ++t) {
    world.step();
    world.serialize(bytes);
    World2D copy;
    const Status loaded = copy.deserialize(bytes);
    ASSERT_TRUE(loaded.ok()) << "tick " << t << ": " << loaded.message();
  }
  EXPECT_GT(world.linear_velocity(struck).x, 4_fx);
  EXPECT_LE(world.linear_velocity(struck).x, 5_fx);
}

}  // namespace
}  // namespace rwd::sim2d
