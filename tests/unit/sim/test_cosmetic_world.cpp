// SPDX-License-Identifier: MIT
// The cosmetic world: props fall on proxies of the authoritative world's
// bodies and are pushed by moving ones, proxies follow bodies made and
// destroyed, props retire by age and budget, and the authoritative world
// is never changed (state, checksum and bytes).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rewind/sim/cosmetic_world.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

std::unique_ptr<CosmeticWorld> cosmetic_of(const World3D& authority, CosmeticConfig config = {}) {
  config.world = authority.config();
  auto made = CosmeticWorld::create(config, authority.shared_geometry());
  EXPECT_TRUE(made.ok()) << made.status().message();
  return std::move(*made);
}

BodyDef prop_at(Vec3 position, float half = 0.1f) {
  BodyDef def;
  def.shape = Shape::make_box({half, half, half});
  def.position = position;
  return def;
}

TEST(CosmeticWorld, PropsRestOnProxiesAndTheAuthorityIsNeverChanged) {
  World3D authority;
  test::add_ground(authority);
  const BodyId crate = test::add_box(authority, {2.0f, 0.5f, 0.0f});
  std::vector<uint8_t> before;
  authority.serialize(before);
  const uint64_t checksum = authority.checksum();

  auto cosmetic = cosmetic_of(authority);
  cosmetic->sync(authority);
  ASSERT_TRUE(cosmetic->add_prop(prop_at({0.0f, 2.0f, 0.0f})).ok());
  // One on the crate: a dynamic body's proxy holds it up too.
  const auto on_crate = cosmetic->add_prop(prop_at({2.0f, 2.0f, 0.0f}));
  ASSERT_TRUE(on_crate.ok());
  for (int i = 0; i < 120; ++i) {
    cosmetic->sync(authority);
    cosmetic->step();
  }
  EXPECT_NEAR(cosmetic->world().position(on_crate->body).y, 1.1f, 0.02f);
  std::vector<uint8_t> after;
  authority.serialize(after);
  EXPECT_EQ(before, after);
  EXPECT_EQ(authority.checksum(), checksum);
  EXPECT_EQ(authority.body_count(), 2u);
  EXPECT_TRUE(authority.is_valid(crate));
  EXPECT_EQ(cosmetic->prop_count(), 2u);
  EXPECT_EQ(cosmetic->world().body_count(), 4u);  // two proxies, two props
}

TEST(CosmeticWorld, AMovingBodysProxyPushesProps) {
  World3D authority;
  test::add_ground(authority);
  BodyDef paddle;
  paddle.kind = BodyKind::kKinematic;
  paddle.shape = Shape::make_box({0.2f, 0.5f, 1.0f});
  paddle.position = {-2.0f, 0.5f, 0.0f};
  const BodyId id = *authority.create_body(paddle);
  ASSERT_TRUE(authority.set_linear_velocity(id, {2.0f, 0.0f, 0.0f}).ok());
  auto cosmetic = cosmetic_of(authority);
  cosmetic->sync(authority);
  const auto prop = cosmetic->add_prop(prop_at({0.0f, 0.1f, 0.0f}));
  ASSERT_TRUE(prop.ok());
  for (int i = 0; i < 90; ++i) {  // 1.5 s: the paddle passes x = 0 at 1 s
    authority.step();
    cosmetic->sync(authority);
    cosmetic->step();
  }
  // Pushed ahead of the paddle's face (at x = 1 - 0.2 by now), not left
  // inside or behind it.
  const float x = cosmetic->world().position(prop->body).x;
  EXPECT_GT(x, authority.position(id).x + 0.2f) << x;
}

TEST(CosmeticWorld, ProxiesFollowBodiesMadeAndDestroyed) {
  World3D authority;
  test::add_ground(authority);
  const BodyId crate = test::add_box(authority, {0.0f, 0.5f, 0.0f});
  auto cosmetic = cosmetic_of(authority);
  cosmetic->sync(authority);
  EXPECT_EQ(cosmetic->world().body_count(), 2u);
  ASSERT_TRUE(authority.destroy_body(crate).ok());
  cosmetic->sync(authority);
  EXPECT_EQ(cosmetic->world().body_count(), 1u);
  test::add_box(authority, {3.0f, 0.5f, 0.0f});  // takes the freed slot, a new generation
  test::add_sphere(authority, {5.0f, 0.5f, 0.0f});
  cosmetic->sync(authority);
  EXPECT_EQ(cosmetic->world().body_count(), 3u);
  ASSERT_TRUE(authority.set_enabled(BodyId{1, authority.state().infos[1].generation}, false).ok());
  cosmetic->sync(authority);
  EXPECT_EQ(cosmetic->world().body_count(), 2u);

  CosmeticConfig statics_only;
  statics_only.proxy_dynamic_bodies = false;
  auto only = cosmetic_of(authority, statics_only);
  only->sync(authority);
  EXPECT_EQ(only->world().body_count(), 1u);
}

TEST(CosmeticWorld, PropsRetireByAgeAndBudget) {
  World3D authority;
  CosmeticConfig config;
  config.max_props = 3;
  config.prop_lifetime_s = 0.5f;
  auto cosmetic = cosmetic_of(authority, config);
  std::vector<PropId> props;
  for (int i = 0; i < 4; ++i) {
    props.push_back(*cosmetic->add_prop(prop_at({static_cast<float>(i), 5.0f, 0.0f})));
  }
  EXPECT_EQ(cosmetic->prop_count(), 3u);
  EXPECT_FALSE(cosmetic->is_prop(props[0]));  // the oldest went
  EXPECT_TRUE(cosmetic->is_prop(props[3]));
  EXPECT_TRUE(cosmetic->remove_prop(props[2]).ok());
  EXPECT_EQ(cosmetic->remove_prop(props[2]).code(), ErrorCode::kNotFound);
  for (int i = 0; i < 29; ++i) cosmetic->step();
  EXPECT_EQ(cosmetic->prop_count(), 2u);
  // Half a second is 30 ticks of 1/60 s; the tick on the canonical grid is
  // a hair shorter, so the props go after the 31st.
  cosmetic->step();
  cosmetic->step();
  EXPECT_EQ(cosmetic->prop_count(), 0u);
  ASSERT_TRUE(cosmetic->add_prop(prop_at({0.0f, 5.0f, 0.0f})).ok());
  cosmetic->clear_props();
  EXPECT_EQ(cosmetic->world().body_count(), 0u);
}

TEST(CosmeticWorld, BadInputIsRefused) {
  World3D authority;
  CosmeticConfig config;
  config.prop_lifetime_s = 0.0f;
  EXPECT_FALSE(CosmeticWorld::create(config, authority.shared_geometry()).ok());
  config = {};
  config.max_props = 0;
  EXPECT_FALSE(CosmeticWorld::create(config, authority.shared_geometry()).ok());
  config = {};
  config.world.tick_seconds = -1.0f;
  EXPECT_FALSE(CosmeticWorld::create(config, authority.shared_geometry()).ok());
  auto cosmetic = cosmetic_of(authority);
  BodyDef fixed = prop_at({});
  fixed.kind = BodyKind::kStatic;
  EXPECT_FALSE(cosmetic->add_prop(fixed).ok());
  BodyDef broken = prop_at({});
  broken.shape.half_extents.x = std::nanf("");
  EXPECT_FALSE(cosmetic->add_prop(broken).ok());
  EXPECT_EQ(cosmetic->prop_count(), 0u);
}

TEST(CosmeticWorld, DrawsItsPropsOnly) {
  World3D authority;
  test::add_ground(authority);
  auto cosmetic = cosmetic_of(authority);
  cosmetic->sync(authority);
  ASSERT_TRUE(cosmetic->add_prop(prop_at({0.0f, 1.0f, 0.0f})).ok());
  DebugDrawBuffers out;
  cosmetic->draw_props({}, 0xABCDEFFFu, out);
  EXPECT_EQ(out.lines.size(), 24u);  // one box's twelve edges
  for (const DrawVertex& v : out.lines) {
    EXPECT_EQ(v.color, 0xABCDEFFFu);
    EXPECT_NEAR(v.y, 1.0f, 0.11f);
  }
}

}  // namespace
}  // namespace rwd::sim
