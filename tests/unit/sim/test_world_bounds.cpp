// SPDX-License-Identifier: MIT
// The edge of the world: bodies that leave WorldConfig's bounds are disabled
// where they crossed and reported once; disabled bodies are out of pairs,
// contacts and queries; the game can bring them back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <vector>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

WorldConfig small_world(float half) {
  WorldConfig c;
  c.bounds_lower = {-half, -half, -half};
  c.bounds_upper = {half, half, half};
  return c;
}

uint64_t round_trip_checksum(const World3D& world) {
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  World3D copy;
  Status s = copy.deserialize(bytes);
  EXPECT_TRUE(s.ok()) << s.message();
  return copy.checksum();
}

TEST(WorldBounds, DefaultBoundsAreFiniteAndValid) {
  WorldConfig c;
  EXPECT_TRUE(World3D::validate_config(c).ok());
  EXPECT_EQ(c.bounds_lower.x, -5000.0f);
  EXPECT_EQ(c.bounds_upper.y, 5000.0f);
}

TEST(WorldBounds, InvalidBoundsAreRefusedAndReplaced) {
  WorldConfig c;
  c.bounds_lower = {1.0f, -1.0f, -1.0f};
  c.bounds_upper = {-1.0f, 1.0f, 1.0f};  // inverted on x
  EXPECT_EQ(World3D::validate_config(c).code(), ErrorCode::kInvalidArgument);
  c.bounds_upper = {2e5f, 1.0f, 1.0f};  // beyond 1e5
  c.bounds_lower = {-1.0f, -1.0f, -1.0f};
  EXPECT_FALSE(World3D::validate_config(c).ok());
  c.bounds_upper.x = std::numeric_limits<float>::infinity();
  EXPECT_FALSE(World3D::validate_config(c).ok());
  World3D world(c);
  EXPECT_EQ(world.config().bounds_upper.x, WorldConfig{}.bounds_upper.x);
  EXPECT_EQ(world.config().bounds_lower.x, WorldConfig{}.bounds_lower.x);
}

TEST(WorldBounds, ConfigThatQuantizesOutOfRangeFallsBackToValidValues) {
  // Valid as given, but 1e-7 s rounds to 0 on the canonical grid, and corners
  // 1e-7 m apart collapse onto one point: the world must still hold a config
  // its own snapshots load with.
  WorldConfig c;
  c.tick_seconds = 1e-7f;
  c.bounds_lower = {0.0f, 0.0f, 0.0f};
  c.bounds_upper = {1e-7f, 1.0f, 1.0f};
  ASSERT_TRUE(World3D::validate_config(c).ok());
  World3D world(c);
  EXPECT_TRUE(World3D::validate_config(world.config()).ok());
  EXPECT_GT(world.config().tick_seconds, 0.0f);
  EXPECT_EQ(world.config().bounds_upper.x, WorldConfig{}.bounds_upper.x);
  EXPECT_EQ(round_trip_checksum(world), world.checksum());
}

TEST(WorldBounds, BodiesCannotBeCreatedOrPlacedOutside) {
  World3D world(small_world(10.0f));
  BodyDef def;
  def.position = {10.5f, 0.0f, 0.0f};
  EXPECT_EQ(world.create_body(def).status().code(), ErrorCode::kInvalidArgument);
  def.position = {10.0f, 0.0f, 0.0f};  // on the face: inside
  auto id = world.create_body(def);
  ASSERT_TRUE(id.ok());
  const uint64_t before = world.checksum();
  EXPECT_EQ(world.set_transform(*id, {0.0f, -11.0f, 0.0f}, {}).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.checksum(), before);
}

TEST(WorldBounds, FallingBodyIsDisabledOnTheBoundAndReportedOnce) {
  World3D world(small_world(50.0f));
  BodyId ball = test::add_sphere(world, {1.0f, 0.0f, 2.0f});
  int events = 0;
  int steps = 0;
  while (world.is_enabled(ball) && steps < 2000) {
    world.step();
    ++steps;
    for (const BodyEvent& e : world.body_events()) {
      ++events;
      EXPECT_EQ(e.type, BodyEventType::kLeftBounds);
      EXPECT_EQ(e.body, ball);
      EXPECT_EQ(e.position.y, -50.0f);
    }
    ASSERT_EQ(round_trip_checksum(world), world.checksum()) << "step " << steps;
  }
  ASSERT_FALSE(world.is_enabled(ball));
  EXPECT_EQ(events, 1);
  // Frozen where it crossed: on the bound, x and z kept, not moving.
  EXPECT_EQ(world.position(ball).y, -50.0f);
  EXPECT_EQ(world.position(ball).x, 1.0f);
  EXPECT_EQ(world.position(ball).z, 2.0f);
  EXPECT_EQ(world.linear_velocity(ball), Vec3{});
  EXPECT_FALSE(world.is_awake(ball));
  // It stays there, reported only once, for as long as nobody moves it.
  const Vec3 frozen = world.position(ball);
  for (int i = 0; i < 120; ++i) {
    world.step();
    EXPECT_TRUE(world.body_events().empty());
  }
  EXPECT_EQ(world.position(ball), frozen);
  EXPECT_EQ(round_trip_checksum(world), world.checksum());
}

TEST(WorldBounds, FlungBodiesLeaveOnEveryFaceAndKinematicOnesToo) {
  World3D world(small_world(20.0f));
  const Vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<BodyId> ids;
  for (const Vec3& d : dirs) {
    BodyDef def;
    def.shape = Shape::make_sphere(0.25f);
    def.position = d * 2.0f;
    def.linear_velocity = d * 9000.0f;
    def.gravity_scale = 0.0f;
    ids.push_back(*world.create_body(def));
  }
  BodyDef kin;
  kin.kind = BodyKind::kKinematic;
  kin.position = {0.0f, 5.0f, 5.0f};
  kin.linear_velocity = {0.0f, 0.0f, 300.0f};
  ids.push_back(*world.create_body(kin));
  std::vector<BodyId> reported;
  for (int i = 0; i < 30; ++i) {
    world.step();
    for (const BodyEvent& e : world.body_events()) reported.push_back(e.body);
    ASSERT_EQ(round_trip_checksum(world), world.checksum());
  }
  ASSERT_EQ(reported.size(), ids.size());
  for (const BodyId id : ids) {
    EXPECT_FALSE(world.is_enabled(id));
    const Vec3 p = world.position(id);
    const float m = std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
    EXPECT_EQ(m, 20.0f);
  }
}

TEST(WorldBounds, EventsOfOneStepAreInBodyOrder) {
  World3D world(small_world(5.0f));
  std::vector<BodyId> ids;
  for (int i = 0; i < 5; ++i) {
    BodyDef def;
    def.shape = Shape::make_sphere(0.1f);
    def.position = {static_cast<float>(i) - 2.0f, 4.9f, 0.0f};
    def.linear_velocity = {0.0f, 60.0f, 0.0f};
    ids.push_back(*world.create_body(def));
  }
  world.step();
  ASSERT_EQ(world.body_events().size(), ids.size());
  for (size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(world.body_events()[i].body, ids[i]);
}

TEST(WorldBounds, DisabledBodiesLeaveContactsAndQueries) {
  World3D world(small_world(30.0f));
  test::add_ground(world);
  BodyId box = test::add_box(world, {0.0f, 0.5f, 0.0f});
  test::step_seconds(world, 0.5f);
  Ray down{{0.0f, 5.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 10.0f};
  ASSERT_TRUE(world.raycast(down).has_value());
  EXPECT_EQ(world.raycast(down)->body, box);

  ASSERT_TRUE(world.set_enabled(box, false).ok());
  EXPECT_FALSE(world.is_enabled(box));
  EXPECT_FALSE(world.is_awake(box));
  EXPECT_EQ(world.set_linear_velocity(box, {1.0f, 0.0f, 0.0f}).code(), ErrorCode::kInvalidArgument);
  EXPECT_FALSE(world.apply_force(box, {0.0f, 10.0f, 0.0f}).ok());
  // The ray now reaches the ground instead.
  auto hit = world.raycast(down);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NE(hit->body, box);
  // Its ground contact ends with one exit event on the next step.
  world.step();
  int exits = 0;
  for (const ContactEvent& e : world.events()) {
    if (e.type == ContactEventType::kExit && (e.a == box || e.b == box)) ++exits;
    EXPECT_FALSE(e.type != ContactEventType::kExit && (e.a == box || e.b == box));
  }
  EXPECT_EQ(exits, 1);
  // Frozen: gravity does not move it.
  const Vec3 where = world.position(box);
  test::step_seconds(world, 0.5f);
  EXPECT_EQ(world.position(box), where);
  EXPECT_EQ(round_trip_checksum(world), world.checksum());
}

TEST(WorldBounds, RespawnedBodySimulatesAgain) {
  World3D world(small_world(20.0f));
  test::add_ground(world);
  BodyDef def;
  def.shape = Shape::make_sphere(0.5f);
  def.position = {0.0f, 3.0f, 0.0f};
  def.linear_velocity = {500.0f, 0.0f, 0.0f};
  BodyId ball = *world.create_body(def);
  for (int i = 0; i < 10 && world.is_enabled(ball); ++i) world.step();
  ASSERT_FALSE(world.is_enabled(ball));
  // Respawn: a disabled body may be moved, then enabled.
  ASSERT_TRUE(world.set_transform(ball, {0.0f, 2.0f, 0.0f}, {}).ok());
  EXPECT_FALSE(world.is_enabled(ball));
  ASSERT_TRUE(world.set_enabled(ball, true).ok());
  EXPECT_TRUE(world.is_awake(ball));
  test::step_seconds(world, 2.0f);
  EXPECT_TRUE(world.is_enabled(ball));
  EXPECT_NEAR(world.position(ball).y, 0.5f, 0.02f);  // came to rest on the ground
}

TEST(WorldBounds, RestoreAndReStepAcrossTheEdgeIsBitExact) {
  World3D world(small_world(15.0f));
  test::add_ground(world);
  for (int i = 0; i < 6; ++i) {
    BodyDef def;
    def.shape = i % 2 ? Shape::make_sphere(0.3f) : Shape::make_box({0.3f, 0.3f, 0.3f});
    def.position = {static_cast<float>(i) - 3.0f, 1.0f, 0.0f};
    def.linear_velocity = {40.0f * static_cast<float>(i % 3) - 40.0f, 8.0f, 3.0f};
    (void)world.create_body(def);
  }
  WorldState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<uint64_t> sums;
  size_t disabled_events = 0;
  for (int i = 0; i < 120; ++i) {
    world.step();
    disabled_events += world.body_events().size();
    sums.push_back(world.checksum());
  }
  ASSERT_GT(disabled_events, 0u);
  world.restore(saved);
  World3D loaded;
  ASSERT_TRUE(loaded.deserialize(bytes).ok());
  for (int i = 0; i < 120; ++i) {
    world.step();
    loaded.step();
    ASSERT_EQ(world.checksum(), sums[i]) << i;
    ASSERT_EQ(loaded.checksum(), sums[i]) << i;
  }
}

// Offsets into a snapshot: "RWD3" + version, the geometry count and digest,
// then the config; the bounds are its last 24 bytes (lower xyz, upper xyz).
constexpr size_t kConfigStart = 8 + 4 + 8;
constexpr size_t kBoundsLowerX = kConfigStart + 61;

void put_f32(std::vector<uint8_t>& bytes, size_t at, float v) {
  std::memcpy(&bytes[at], &v, 4);  // little-endian hosts only (x86-64, aarch64)
}

TEST(WorldBounds, SnapshotWithABodyOutsideItsBoundsIsRefusedByName) {
  World3D world(small_world(100.0f));
  (void)test::add_sphere(world, {0.0f, 0.0f, 0.0f});
  BodyId far = test::add_sphere(world, {60.0f, 0.0f, 0.0f});
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  // Shrink the recorded bounds to 50 m: body `far` is now outside them.
  for (int axis = 0; axis < 3; ++axis) {
    put_f32(bytes, kBoundsLowerX + 4 * axis, -50.0f);
    put_f32(bytes, kBoundsLowerX + 12 + 4 * axis, 50.0f);
  }
  World3D target;
  const uint64_t before = target.checksum();
  Status s = target.deserialize(bytes);
  EXPECT_EQ(s.code(), ErrorCode::kCorrupt);
  EXPECT_NE(s.message().find("body " + std::to_string(far.index)), std::string::npos)
      << s.message();
  EXPECT_NE(s.message().find("bounds"), std::string::npos) << s.message();
  EXPECT_EQ(target.checksum(), before);
}

TEST(WorldBounds, ConfigRoundTripsThroughItsCodec) {
  WorldConfig c = small_world(123.0f);
  c.substeps = 6;
  c.gravity = {0.0f, -3.0f, 1.0f};
  std::vector<uint8_t> bytes;
  World3D::encode_config(c, bytes);
  auto back = World3D::decode_config(bytes);
  ASSERT_TRUE(back.ok()) << back.status().message();
  std::vector<uint8_t> again;
  World3D::encode_config(*back, again);
  EXPECT_EQ(bytes, again);
  bytes.pop_back();
  EXPECT_EQ(World3D::decode_config(bytes).status().code(), ErrorCode::kCorrupt);
  World3D::encode_config(c, bytes);
  put_f32(bytes, 61, 500.0f);  // lower.x above upper.x
  EXPECT_EQ(World3D::decode_config(bytes).status().code(), ErrorCode::kCorrupt);
}

}  // namespace
}  // namespace rwd::sim
