// SPDX-License-Identifier: MIT
// Scheduled queries: pre-physics ones see the world as the step finds it,
// post-physics ones as it leaves it; answers come in scheduling order with
// their tickets and tags; one-shot schedules run once, repeating ones until
// cancelled; schedules are state (restore, snapshots, checksum) and replay
// bit for bit; they never change the simulation; bad input is refused with
// the world unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using test::add_box;
using test::add_ground;
using test::add_sphere;

const QueryFilter kAll{};

QueryFilter without_static() {
  QueryFilter f;
  f.include_static = false;
  return f;
}

// A downward ray from high above x = `x`.
Ray down_at(float x) {
  Ray r;
  r.origin = {x, 40.0f, 0.0f};
  r.direction = {0.0f, -1.0f, 0.0f};
  r.max_distance = 100.0f;
  return r;
}

uint32_t bits(float v) {
  uint32_t b = 0;
  std::memcpy(&b, &v, 4);
  return b;
}

// Every bit of a step's answers, as text, to compare runs exactly.
std::string answers(const World3D& world) {
  std::string out;
  for (const ScheduledQueryResult& r : world.step_queries()) {
    out += std::to_string(r.ticket.id) + ":" + std::to_string(r.user_tag) + ":" +
           std::to_string(static_cast<int>(r.kind)) + std::to_string(static_cast<int>(r.phase));
    for (const RayHit& h : r.ray_hits) {
      out += " r" + std::to_string(h.body.index) + "," + std::to_string(bits(h.distance)) + "," +
             std::to_string(bits(h.point.y)) + "," + std::to_string(bits(h.normal.y));
    }
    for (const BodyId b : r.bodies) out += " b" + std::to_string(b.index);
    out += ";";
  }
  return out;
}

TEST(ScheduledQueries, PreSeesTheWorldBeforeTheStepAndPostAfter) {
  WorldConfig c;
  c.gravity = {0.0f, -9.81f, 0.0f};
  World3D world(c);
  BodyDef def;
  def.shape = Shape::make_sphere(0.5f);
  def.position = {0.0f, 10.0f, 0.0f};
  def.linear_velocity = {0.0f, -6.0f, 0.0f};
  const BodyId ball = *world.create_body(def);
  const auto pre = world.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 11);
  const auto post = world.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPostPhysics, 22);
  ASSERT_TRUE(pre.ok()) << pre.status().message();
  ASSERT_TRUE(post.ok()) << post.status().message();
  EXPECT_EQ(pre->id, 1u);
  EXPECT_EQ(post->id, 2u);
  EXPECT_EQ(world.scheduled_query_count(), 2u);
  // What an immediate query says before and after the step, by hand.
  const std::optional<RayHit> before = world.raycast(down_at(0.0f));
  ASSERT_TRUE(before.has_value());
  world.step();
  const std::optional<RayHit> after = world.raycast(down_at(0.0f));
  ASSERT_TRUE(after.has_value());

  const auto results = world.step_queries();
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].ticket, *pre);
  EXPECT_EQ(results[0].user_tag, 11u);
  EXPECT_EQ(results[0].phase, QueryPhase::kPrePhysics);
  EXPECT_EQ(results[0].kind, ScheduledQueryKind::kRaycast);
  EXPECT_EQ(results[1].ticket, *post);
  EXPECT_EQ(results[1].user_tag, 22u);
  EXPECT_EQ(results[1].phase, QueryPhase::kPostPhysics);
  ASSERT_EQ(results[0].ray_hits.size(), 1u);
  ASSERT_EQ(results[1].ray_hits.size(), 1u);
  const RayHit& h0 = results[0].ray_hits[0];
  const RayHit& h1 = results[1].ray_hits[0];
  EXPECT_EQ(h0.body, ball);
  EXPECT_EQ(h1.body, ball);
  // The ball fell during the step: the pre ray hit it higher.
  EXPECT_GT(h0.point.y, h1.point.y + 0.05f);
  // Bit for bit what the game would have got by asking at those moments.
  EXPECT_EQ(bits(h0.distance), bits(before->distance));
  EXPECT_EQ(bits(h1.distance), bits(after->distance));
  EXPECT_TRUE(results[0].bodies.empty());
  // One-shot schedules are gone after their step.
  EXPECT_EQ(world.scheduled_query_count(), 0u);
  EXPECT_FALSE(world.is_scheduled(*pre));
  EXPECT_EQ(world.cancel_query(*pre).code(), ErrorCode::kNotFound);
  world.step();
  EXPECT_TRUE(world.step_queries().empty());
}

TEST(ScheduledQueries, AnswersComeInSchedulingOrderWhateverTheirPhase) {
  World3D world;
  add_ground(world);
  const BodyId box = add_box(world, {0.0f, 0.5f, 0.0f});
  const BodyId ball = add_sphere(world, {3.0f, 0.5f, 0.0f});
  const auto t1 = world.schedule_raycast(down_at(3.0f), kAll, QueryPhase::kPostPhysics, 100);
  const auto t2 = world.schedule_overlap(Shape::make_box({4.0f, 2.0f, 1.0f}), {1.5f, 0.5f, 0.0f},
                                         Quat{}, without_static(), QueryPhase::kPrePhysics, 200);
  Ray across;
  across.origin = {-5.0f, 0.5f, 0.0f};
  across.direction = {1.0f, 0.0f, 0.0f};
  across.max_distance = 20.0f;
  const auto t3 = world.schedule_raycast_all(across, kAll, QueryPhase::kPrePhysics, 300);
  const auto t4 =
      world.schedule_raycast(down_at(30.0f), without_static(), QueryPhase::kPostPhysics, 400);
  ASSERT_TRUE(t1.ok() && t2.ok() && t3.ok() && t4.ok());
  world.step();
  const auto r = world.step_queries();
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r[0].ticket, *t1);
  EXPECT_EQ(r[1].ticket, *t2);
  EXPECT_EQ(r[2].ticket, *t3);
  EXPECT_EQ(r[3].ticket, *t4);
  EXPECT_EQ(r[0].user_tag, 100u);
  EXPECT_EQ(r[1].user_tag, 200u);
  EXPECT_EQ(r[2].user_tag, 300u);
  EXPECT_EQ(r[3].user_tag, 400u);
  ASSERT_EQ(r[0].ray_hits.size(), 1u);
  EXPECT_EQ(r[0].ray_hits[0].body, ball);
  EXPECT_EQ(r[1].kind, ScheduledQueryKind::kOverlap);
  ASSERT_EQ(r[1].bodies.size(), 2u);  // the ground left out by the filter
  EXPECT_EQ(r[1].bodies[0], box);
  EXPECT_EQ(r[1].bodies[1], ball);
  EXPECT_EQ(r[2].kind, ScheduledQueryKind::kRaycastAll);
  ASSERT_EQ(r[2].ray_hits.size(), 2u);  // near to far
  EXPECT_EQ(r[2].ray_hits[0].body, box);
  EXPECT_EQ(r[2].ray_hits[1].body, ball);
  EXPECT_LT(r[2].ray_hits[0].distance, r[2].ray_hits[1].distance);
  EXPECT_TRUE(r[3].ray_hits.empty());  // nothing but the ground out there
}

TEST(ScheduledQueries, RepeatingQueriesRunEveryStepUntilCancelled) {
  World3D world;
  add_ground(world);
  add_box(world, {0.0f, 3.0f, 0.0f});
  const auto every = world.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPostPhysics, 7,
                                            QueryRepeat::kEveryStep);
  const auto once = world.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 8);
  ASSERT_TRUE(every.ok() && once.ok());
  world.step();
  ASSERT_EQ(world.step_queries().size(), 2u);
  for (int i = 0; i < 5; ++i) {
    world.step();
    ASSERT_EQ(world.step_queries().size(), 1u);
    EXPECT_EQ(world.step_queries()[0].ticket, *every);
    EXPECT_EQ(world.step_queries()[0].user_tag, 7u);
  }
  EXPECT_TRUE(world.is_scheduled(*every));
  ASSERT_TRUE(world.cancel_query(*every).ok());
  EXPECT_FALSE(world.is_scheduled(*every));
  EXPECT_EQ(world.cancel_query(*every).code(), ErrorCode::kNotFound);
  world.step();
  EXPECT_TRUE(world.step_queries().empty());
  // Tickets are never reused.
  const auto next = world.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 9);
  ASSERT_TRUE(next.ok());
  EXPECT_EQ(next->id, 3u);
}

// A pile with a few repeating queries of every kind, and a one-shot one.
void build_watched_pile(World3D& world) {
  add_ground(world);
  for (int i = 0; i < 8; ++i) {
    const float x = 0.7f * static_cast<float>(i % 3) - 0.7f;
    const float y = 0.6f + 1.1f * static_cast<float>(i);
    if (i % 2 == 0) {
      add_box(world, {x, y, 0.05f * static_cast<float>(i)});
    } else {
      add_sphere(world, {x, y, 0.0f}, 0.45f);
    }
  }
  ASSERT_TRUE(world
                  .schedule_raycast(down_at(0.1f), kAll, QueryPhase::kPrePhysics, 1,
                                    QueryRepeat::kEveryStep)
                  .ok());
  ASSERT_TRUE(world
                  .schedule_overlap(Shape::make_sphere(1.0f), {0.0f, 1.0f, 0.0f}, Quat{},
                                    QueryFilter{}, QueryPhase::kPostPhysics, 2,
                                    QueryRepeat::kEveryStep)
                  .ok());
  Ray slant;
  slant.origin = {-6.0f, 6.0f, 0.0f};
  slant.direction = {1.0f, -0.8f, 0.0f};
  ASSERT_TRUE(
      world.schedule_raycast_all(slant, kAll, QueryPhase::kPostPhysics, 3, QueryRepeat::kEveryStep)
          .ok());
  ASSERT_TRUE(world.schedule_raycast(down_at(-0.3f), kAll, QueryPhase::kPostPhysics, 4).ok());
}

TEST(ScheduledQueries, SchedulesRollBackAndReplayBitForBit) {
  World3D world;
  build_watched_pile(world);
  for (int i = 0; i < 10; ++i) world.step();
  // A one-shot query made between steps, before the save: it is state, so
  // the restored world runs it too.
  ASSERT_TRUE(world.schedule_raycast(down_at(0.4f), kAll, QueryPhase::kPrePhysics, 5).ok());
  WorldState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  const uint64_t saved_sum = world.checksum();
  std::vector<std::string> first;
  std::vector<uint64_t> sums;
  for (int i = 0; i < 60; ++i) {
    world.step();
    first.push_back(answers(world));
    sums.push_back(world.checksum());
  }
  EXPECT_NE(first[0].find(":5:"), std::string::npos) << first[0];
  EXPECT_EQ(first[1].find(":5:"), std::string::npos) << first[1];

  // A schedule made after the save is dropped by the restore, like any
  // other edit after it: the game makes it again when it replays the tick.
  ASSERT_TRUE(world.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 6).ok());
  world.restore(saved);
  EXPECT_TRUE(world.step_queries().empty());
  EXPECT_EQ(world.checksum(), saved_sum);
  World3D loaded;
  ASSERT_TRUE(loaded.deserialize(bytes).ok());
  EXPECT_EQ(loaded.checksum(), saved_sum);
  EXPECT_EQ(loaded.scheduled_query_count(), world.scheduled_query_count());
  for (int i = 0; i < 60; ++i) {
    world.step();
    loaded.step();
    ASSERT_EQ(answers(world), first[i]) << i;
    ASSERT_EQ(answers(loaded), first[i]) << i;
    ASSERT_EQ(world.checksum(), sums[i]) << i;
    ASSERT_EQ(loaded.checksum(), sums[i]) << i;
  }
  std::string text;
  loaded.dump_state(text);
  EXPECT_NE(text.find("last_query_ticket = 5\n"), std::string::npos);
  EXPECT_NE(text.find("query[2].kind = 1\n"), std::string::npos) << text;
}

TEST(ScheduledQueries, QueriesNeverChangeTheSimulation) {
  World3D plain;
  World3D watched;
  add_ground(plain);
  for (int i = 0; i < 8; ++i) {
    const float x = 0.7f * static_cast<float>(i % 3) - 0.7f;
    const float y = 0.6f + 1.1f * static_cast<float>(i);
    if (i % 2 == 0) {
      add_box(plain, {x, y, 0.05f * static_cast<float>(i)});
    } else {
      add_sphere(plain, {x, y, 0.0f}, 0.45f);
    }
  }
  build_watched_pile(watched);
  for (int i = 0; i < 120; ++i) {
    plain.step();
    watched.step();
    // The watched world's state without its schedule hashes as the plain one.
    WorldState s = watched.state();
    s.queries.clear();
    s.last_query_ticket = 0;
    StateHasher hasher;
    World3D::hash_state(s, hasher);
    ASSERT_EQ(hasher.digest(), plain.checksum()) << i;
  }
  EXPECT_NE(watched.checksum(), plain.checksum());  // the schedule is state
}

TEST(ScheduledQueries, EveryScheduleEverMadeIsInTheChecksum) {
  World3D a;
  World3D b;
  add_ground(a);
  add_ground(b);
  EXPECT_EQ(a.checksum(), b.checksum());
  const auto t = a.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 1);
  ASSERT_TRUE(t.ok());
  EXPECT_NE(a.checksum(), b.checksum());
  // Cancelled, it still moved the ticket count: the next ticket differs.
  ASSERT_TRUE(a.cancel_query(*t).ok());
  EXPECT_NE(a.checksum(), b.checksum());
  ASSERT_TRUE(b.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 1).ok());
  ASSERT_TRUE(b.cancel_query(QueryTicket{1}).ok());
  EXPECT_EQ(a.checksum(), b.checksum());
  // The tag is state too.
  ASSERT_TRUE(a.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 2).ok());
  ASSERT_TRUE(b.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 3).ok());
  EXPECT_NE(a.checksum(), b.checksum());
}

TEST(ScheduledQueries, BadInputIsRefusedAndChangesNothing) {
  World3D world;
  add_ground(world);
  add_box(world, {0.0f, 0.5f, 0.0f});
  ASSERT_TRUE(world
                  .schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 1,
                                    QueryRepeat::kEveryStep)
                  .ok());
  const uint64_t before = world.checksum();
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto refused_ray = [&](Ray r, const char* what) {
    const auto t = world.schedule_raycast(r, kAll, QueryPhase::kPrePhysics, 2);
    EXPECT_EQ(t.status().code(), ErrorCode::kInvalidArgument) << what;
    EXPECT_FALSE(t.status().message().empty()) << what;
    const auto all = world.schedule_raycast_all(r, kAll, QueryPhase::kPostPhysics, 2);
    EXPECT_EQ(all.status().code(), ErrorCode::kInvalidArgument) << what;
  };
  Ray r = down_at(0.0f);
  r.origin.x = nan;
  refused_ray(r, "nan origin");
  r = down_at(0.0f);
  r.origin.y = inf;
  refused_ray(r, "infinite origin");
  r = down_at(0.0f);
  r.direction = {};
  refused_ray(r, "zero direction");
  r.direction = {1e-30f, 0.0f, 0.0f};
  refused_ray(r, "direction too short to normalize");
  r.direction = {0.0f, nan, 0.0f};
  refused_ray(r, "nan direction");
  r = down_at(0.0f);
  r.max_distance = -1.0f;
  refused_ray(r, "negative length");
  r.max_distance = inf;
  refused_ray(r, "infinite length");
  r = down_at(0.0f);
  const auto bad_phase = world.schedule_raycast(r, kAll, static_cast<QueryPhase>(7), 2);
  EXPECT_EQ(bad_phase.status().code(), ErrorCode::kInvalidArgument);
  const auto bad_repeat =
      world.schedule_raycast(r, kAll, QueryPhase::kPrePhysics, 2, static_cast<QueryRepeat>(3));
  EXPECT_EQ(bad_repeat.status().code(), ErrorCode::kInvalidArgument);

  const auto refused_overlap = [&](const Shape& shape, Vec3 p, Quat q, const char* what) {
    const auto t = world.schedule_overlap(shape, p, q, kAll, QueryPhase::kPrePhysics, 2);
    EXPECT_EQ(t.status().code(), ErrorCode::kInvalidArgument) << what;
    EXPECT_FALSE(t.status().message().empty()) << what;
  };
  refused_overlap(Shape::make_sphere(0.0f), {}, Quat{}, "zero radius");
  refused_overlap(Shape::make_sphere(-1.0f), {}, Quat{}, "negative radius");
  refused_overlap(Shape::make_box({1.0f, nan, 1.0f}), {}, Quat{}, "nan size");
  refused_overlap(Shape::make_hull(GeometryId{42}), {}, Quat{}, "unknown hull");
  refused_overlap(Shape::make_sphere(1.0f), {nan, 0.0f, 0.0f}, Quat{}, "nan position");
  refused_overlap(Shape::make_sphere(1.0f), {0.0f, 0.0f, 0.0f}, Quat{0.0f, 0.0f, 0.0f, 0.0f},
                  "zero rotation");
  refused_overlap(Shape::make_sphere(1.0f), {0.0f, 0.0f, 0.0f}, Quat{inf, 0.0f, 0.0f, 1.0f},
                  "infinite rotation");

  EXPECT_EQ(world.cancel_query(QueryTicket{}).code(), ErrorCode::kNotFound);
  EXPECT_EQ(world.cancel_query(QueryTicket{99}).code(), ErrorCode::kNotFound);
  EXPECT_EQ(world.checksum(), before);
  EXPECT_EQ(world.scheduled_query_count(), 1u);
  // The next good schedule gets the next ticket: refusals took none.
  const auto next = world.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 3);
  ASSERT_TRUE(next.ok());
  EXPECT_EQ(next->id, 2u);
}

TEST(ScheduledQueries, TheScheduleHasALimit) {
  World3D world;
  for (uint32_t i = 0; i < World3D::kMaxScheduledQueries; ++i) {
    ASSERT_TRUE(world.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, i).ok());
  }
  const uint64_t before = world.checksum();
  const auto full = world.schedule_raycast(down_at(0.0f), kAll, QueryPhase::kPrePhysics, 0);
  EXPECT_EQ(full.status().code(), ErrorCode::kCapacity);
  EXPECT_EQ(world.checksum(), before);
  world.step();
  EXPECT_EQ(world.step_queries().size(), World3D::kMaxScheduledQueries);
  EXPECT_EQ(world.scheduled_query_count(), 0u);
}

TEST(ScheduledQueries, SnapshotsWithBadSchedulesAreRefused) {
  World3D world;
  add_ground(world);
  ASSERT_TRUE(world
                  .schedule_overlap(Shape::make_sphere(1.0f), {0.0f, 1.0f, 0.0f}, Quat{}, kAll,
                                    QueryPhase::kPostPhysics, 0x1234, QueryRepeat::kEveryStep)
                  .ok());
  std::vector<uint8_t> good;
  world.serialize(good);
  World3D target;
  const uint64_t empty = target.checksum();
  // Cut anywhere inside the schedule: refused, the target unchanged.
  for (size_t cut = 1; cut < 60; ++cut) {
    std::vector<uint8_t> bytes(good.begin(), good.end() - static_cast<std::ptrdiff_t>(cut));
    EXPECT_EQ(target.deserialize(bytes).code(), ErrorCode::kCorrupt) << cut;
  }
  // The overlap's rotation is the last field: make it non-unit.
  std::vector<uint8_t> bytes = good;
  const float two = 2.0f;
  std::memcpy(&bytes[bytes.size() - 4], &two, 4);
  const Status s = target.deserialize(bytes);
  EXPECT_EQ(s.code(), ErrorCode::kCorrupt);
  EXPECT_NE(s.message().find("scheduled query 0"), std::string::npos) << s.message();
  EXPECT_EQ(target.checksum(), empty);
  ASSERT_TRUE(target.deserialize(good).ok());
  EXPECT_EQ(target.checksum(), world.checksum());
}

}  // namespace
}  // namespace rwd::sim
