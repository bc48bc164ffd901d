// SPDX-License-Identifier: MIT
// The lane seam: a Simulation reaches its world only through Lane, and the
// 3D lane behind it must keep every checksum and serialized byte of the
// world it wraps. Counts global operator new calls to show that saving
// into a reused snapshot does not allocate.
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "allocation_counter.h"
#include "rewind/game/crates_game.h"
#include "rewind/game/simulation.h"
#include "rewind/game/world_lane.h"
#include "rewind/sim/world3d.h"

namespace rwd::game {
namespace {

std::vector<PlayerInput> steer(uint32_t players, Tick tick) {
  std::vector<StickInput> inputs(players);
  for (uint32_t p = 0; p < players; ++p) {
    inputs[p].axis_x = static_cast<int16_t>(((tick / 20 + static_cast<Tick>(p)) % 3 - 1) * 1000);
    inputs[p].axis_y = kAxisMax;
  }
  return stick_inputs(inputs);
}

std::unique_ptr<Simulation> played(Tick ticks) {
  auto sim = Simulation::create("crates", {2, 7});
  EXPECT_TRUE(sim.ok()) << sim.status().message();
  for (Tick t = 0; t < ticks; ++t) EXPECT_TRUE((*sim)->step(steer(2, t)).ok());
  return std::move(*sim);
}

TEST(WorldLane, ForwardsToTheWorldItWraps) {
  std::unique_ptr<Simulation> sim = played(90);
  const sim::World3D* world = world_of<sim::World3D>(sim->lane());
  ASSERT_NE(world, nullptr);

  rwd::StateHasher via_lane;
  sim->lane().hash(via_lane);
  EXPECT_EQ(via_lane.digest(), world->checksum());

  std::vector<uint8_t> lane_bytes;
  std::vector<uint8_t> world_bytes;
  sim->lane().serialize(lane_bytes);
  world->serialize(world_bytes);
  EXPECT_EQ(lane_bytes, world_bytes);

  std::vector<uint8_t> game_config;
  std::vector<uint8_t> world_config;
  sim->game().encode_world_config(game_config);
  sim::World3D::encode_config(CratesGame().world_config(), world_config);
  EXPECT_EQ(game_config, world_config);

  std::vector<rwd::BodyField> lane_dump;
  std::vector<rwd::BodyField> world_dump;
  sim->dump_bodies(lane_dump);
  world->dump_fields(world_dump);
  EXPECT_FALSE(lane_dump.empty());
  EXPECT_TRUE(rwd::diff_body_fields(lane_dump, world_dump).empty());
}

TEST(WorldLane, SnapshotsAreOpaqueAndRoundTrip) {
  std::unique_ptr<Simulation> sim = played(60);
  SimSnapshot saved;
  sim->save(saved);
  ASSERT_NE(saved.world, nullptr);
  ASSERT_NE(state_of<sim::World3D>(*saved.world), nullptr);
  const uint64_t at_save = sim->checksum();
  EXPECT_EQ(sim->checksum_of(saved), at_save);

  std::vector<uint64_t> first;
  for (Tick t = 60; t < 120; ++t) {
    EXPECT_TRUE(sim->step(steer(2, t)).ok());
    first.push_back(sim->checksum());
  }
  // A copy is independent of the snapshot it came from.
  SimSnapshot copy = saved;
  sim->save(saved);
  EXPECT_EQ(sim->checksum_of(copy), at_save);
  EXPECT_NE(sim->checksum_of(saved), at_save);

  sim->restore(copy);
  EXPECT_EQ(sim->checksum(), at_save);
  for (Tick t = 60; t < 120; ++t) {
    EXPECT_TRUE(sim->step(steer(2, t)).ok());
    ASSERT_EQ(sim->checksum(), first[static_cast<size_t>(t - 60)]) << "tick " << t;
  }
}

TEST(WorldLane, SavingIntoAReusedSnapshotDoesNotAllocate) {
  std::unique_ptr<Simulation> sim = played(60);
  SimSnapshot snapshot;
  sim->save(snapshot);
  sim->restore(snapshot);
  rwd::test::AllocationCounter::start();
  sim->save(snapshot);
  sim->restore(snapshot);
  EXPECT_EQ(rwd::test::AllocationCounter::stop(), 0);
}

TEST(WorldLane, TheGameDescribesItsLanesConfigBytes) {
  sim::WorldConfig config = CratesGame().world_config();
  config.substeps = 6;
  std::vector<uint8_t> bytes;
  sim::World3D::encode_config(config, bytes);
  auto fields = CratesGame().describe_world_config(bytes);
  ASSERT_TRUE(fields.ok()) << fields.status().message();
  EXPECT_EQ(*fields, sim::World3D::describe_config(config));
  ASSERT_GT(fields->size(), 2u);
  EXPECT_EQ((*fields)[2], (std::pair<std::string, std::string>{"substeps", "6"}));

  bytes.resize(3);
  auto garbled = CratesGame().describe_world_config(bytes);
  ASSERT_FALSE(garbled.ok());
  EXPECT_EQ(garbled.status().code(), ErrorCode::kCorrupt);
}

TEST(WorldLane, ASolverConfigBuildsThe3DLaneFromIt) {
  sim::WorldConfig config = CratesGame().world_config();
  config.substeps = 8;
  auto sim = Simulation::create("crates", {2, 1}, config);
  ASSERT_TRUE(sim.ok()) << sim.status().message();
  EXPECT_EQ(world_of<sim::World3D>((*sim)->lane())->config().substeps, 8);
}

TEST(WorldLane, ADrillPerturbsTheLastDynamicBodyTheSameWayEachTime) {
  std::unique_ptr<Simulation> a = played(30);
  std::unique_ptr<Simulation> b = played(30);
  const sim::World3D& world = *world_of<sim::World3D>(a->lane());
  std::vector<sim::BodyId> ids;
  world.body_ids(ids);
  sim::BodyId last{};
  for (sim::BodyId id : ids) {
    if (world.kind(id) == sim::BodyKind::kDynamic) last = id;
  }
  const sim::Vec3 before = world.position(last);
  const uint64_t unperturbed = a->checksum();

  ASSERT_TRUE(a->lane().perturb_for_drill());
  ASSERT_TRUE(b->lane().perturb_for_drill());
  EXPECT_NE(a->checksum(), unperturbed);
  EXPECT_EQ(a->checksum(), b->checksum());
  EXPECT_NEAR(world.position(last).x, before.x + 0.001f, 1e-4f);
  EXPECT_NEAR(world.position(last).z, before.z, 1e-4f);  // set_transform() quantizes
}

TEST(WorldLane, DrawsAndCountsItsWorldForAViewerOfEitherLane) {
  for (std::string_view name : builtin_game_names()) {
    auto made = Simulation::create(name, {2, 3});
    ASSERT_TRUE(made.ok()) << name;
    Simulation& sim = **made;
    for (Tick t = 0; t < 60; ++t) EXPECT_TRUE(sim.step(steer(2, t)).ok());
    const uint64_t before = sim.checksum();
    rwd::DebugDrawBuffers out;
    sim.lane().debug_draw({}, out);
    EXPECT_EQ(sim.checksum(), before) << name;
    EXPECT_GT(out.lines.size(), 8u) << name;
    const rwd::WorldViewStats stats = sim.lane().view_stats();
    std::vector<rwd::BodyField> fields;
    sim.dump_bodies(fields);
    // The dump names every live body's fields; its distinct indices are the
    // live bodies.
    std::vector<uint32_t> bodies;
    for (const rwd::BodyField& f : fields) {
      if (bodies.empty() || bodies.back() != f.body_index) bodies.push_back(f.body_index);
    }
    EXPECT_EQ(stats.bodies, bodies.size()) << name;
    EXPECT_LE(stats.awake_bodies, stats.bodies) << name;
    if (name != "arena") {  // top-down: nothing stands on anything
      EXPECT_GT(stats.touching_pairs, 0u) << name;
      EXPECT_GT(out.points.size(), 0u) << name;
    }
    EXPECT_GE(stats.contact_points, stats.touching_pairs) << name;
    // A joint, a contact point and a body each drew: a highlighted body
    // changes its outline's colour only.
    const uint32_t highlight[] = {bodies.back()};
    rwd::DebugDrawOptions lit;
    lit.highlight_bodies = highlight;
    rwd::DebugDrawBuffers marked;
    sim.lane().debug_draw(lit, marked);
    ASSERT_EQ(marked.lines.size(), out.lines.size()) << name;
    size_t recoloured = 0;
    for (size_t i = 0; i < out.lines.size(); ++i) {
      recoloured += marked.lines[i].color != out.lines[i].color ? 1u : 0u;
      if (marked.lines[i].color != out.lines[i].color) {
        EXPECT_EQ(marked.lines[i].color, lit.colors.highlight) << name;
      }
    }
    EXPECT_GT(recoloured, 0u) << name;
  }
}

}  // namespace
}  // namespace rwd::game
