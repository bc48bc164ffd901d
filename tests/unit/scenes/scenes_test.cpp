// SPDX-License-Identifier: MIT
// The scene library itself: the catalogue, the runner, and that each kind of
// criterion fails on an engine that gets the physics wrong.
#include <gtest/gtest.h>

#include <vector>

#include "rewind/scenes/rewind_engine.h"
#include "rewind/scenes/scene.h"

namespace rwd::scenes {
namespace {

// Bodies in ballistic flight with no collisions at all: exact kinematics,
// nothing ever touches.
class BallisticEngine final : public Engine {
 public:
  std::string name() const override { return "ballistic"; }
  std::string settings() const override { return ""; }
  void reset(const WorldSpec& world, uint32_t) override {
    world_ = world;
    bodies_.clear();
  }
  bool add_hull(std::span<const Vec3>, sim::GeometryId& out, std::string&) override {
    out = sim::GeometryId{hulls_++};
    return true;
  }
  bool add_compound(std::span<const sim::CompoundChild>, sim::GeometryId& out,
                    std::string&) override {
    out = sim::GeometryId{hulls_++};
    return true;
  }
  bool add_mesh(std::span<const Vec3>, std::span<const uint32_t>, sim::GeometryId& out,
                std::string&) override {
    out = sim::GeometryId{hulls_++};
    return true;
  }
  bool add_height_field(uint32_t, uint32_t, Vec3, std::span<const float>, sim::GeometryId& out,
                        std::string&) override {
    out = sim::GeometryId{hulls_++};
    return true;
  }
  bool add_body(const BodySpec& spec, BodyHandle& out, std::string& error) override {
    if (refuse_spheres && spec.shape.type == sim::ShapeType::kSphere) {
      error = "spheres refused";
      return false;
    }
    out = static_cast<BodyHandle>(bodies_.size());
    bodies_.push_back(spec);
    return true;
  }
  void step() override {
    const float t = world_.tick_seconds;
    for (BodySpec& b : bodies_) {
      if (b.kind != BodyKind::kDynamic) continue;
      b.position += b.linear_velocity * t + world_.gravity * (0.5f * t * t);
      b.linear_velocity += world_.gravity * t;
    }
  }
  Vec3 position(BodyHandle h) const override { return bodies_[h].position; }
  Quat rotation(BodyHandle h) const override { return bodies_[h].rotation; }
  Vec3 linear_velocity(BodyHandle h) const override { return bodies_[h].linear_velocity; }
  Vec3 angular_velocity(BodyHandle h) const override { return bodies_[h].angular_velocity; }
  bool enabled(BodyHandle) const override { return true; }
  void apply_impulse(BodyHandle, Vec3, Vec3) override {}
  void set_velocity(BodyHandle h, Vec3 v, Vec3 w) override {
    bodies_[h].linear_velocity = v;
    bodies_[h].angular_velocity = w;
  }
  uint32_t awake_count() const override { return static_cast<uint32_t>(bodies_.size()); }

  bool refuse_spheres = false;

 private:
  WorldSpec world_;
  std::vector<BodySpec> bodies_;
  uint32_t hulls_ = 0;
};

SceneResult run(const char* name, int size, Engine& engine) {
  auto scene = make_scene(name, size);
  EXPECT_NE(scene, nullptr);
  return scene ? run_scene(*scene, engine) : SceneResult{};
}

TEST(SceneCatalog, EveryEntryBuildsItsSizesOnRewind) {
  for (const SceneEntry& e : scene_catalog()) {
    bool chart_size_listed = false;
    for (int size : e.sizes) {
      chart_size_listed = chart_size_listed || size == e.chart_size;
      auto scene = e.make(size);
      ASSERT_NE(scene, nullptr) << e.name << " " << size;
      EXPECT_EQ(scene->name(), e.name);
      EXPECT_EQ(scene->size(), size);
      EXPECT_GT(scene->ticks(), 0);
      RewindEngine engine;
      engine.reset(scene->world(), scene->body_capacity());
      std::string error;
      EXPECT_TRUE(scene->build(engine, error)) << e.name << " " << size << ": " << error;
      EXPECT_EQ(engine.world().body_count(), scene->body_capacity()) << e.name;
      for (const Metric& m : scene->metrics()) EXPECT_FALSE(m.criterion.empty()) << e.name;
    }
    EXPECT_TRUE(chart_size_listed) << e.name;
  }
}

TEST(SceneCatalog, UnknownNamesAndSizesAreRefused) {
  EXPECT_EQ(make_scene("no_such_scene", 5), nullptr);
  EXPECT_EQ(make_scene("stack", 0), nullptr);
  EXPECT_EQ(make_scene("incline_stick", 45), nullptr);  // tan 45 > mu: it would slip
  EXPECT_EQ(make_scene("bounce", 101), nullptr);
}

TEST(RunScene, ReportsABodyTheEngineRefuses) {
  BallisticEngine engine;
  engine.refuse_spheres = true;
  SceneResult r = run("bounce", 50, engine);
  EXPECT_EQ(r.error, "spheres refused");
  EXPECT_FALSE(r.pass());
  EXPECT_TRUE(r.metrics.empty());
}

TEST(RunScene, ExactKinematicsPassFreeFall) {
  BallisticEngine engine;
  SceneResult r = run("free_fall", 1, engine);
  ASSERT_TRUE(r.error.empty());
  EXPECT_EQ(r.ticks, 60);
  EXPECT_EQ(r.engine, "ballistic");
  ASSERT_NE(r.metric("drop_error_pct"), nullptr);
  EXPECT_LT(r.metric("drop_error_pct")->value, 0.01);
  EXPECT_TRUE(r.pass());
}

// Without contacts every box falls through the ground, the ball never
// bounces and the projectile crosses the wall: the criteria must say so.
TEST(RunScene, CriteriaFailWithoutContacts) {
  BallisticEngine engine;
  SceneResult stack = run("stack", 5, engine);
  EXPECT_TRUE(stack.metric("drift_m")->pass());  // nothing moves sideways
  EXPECT_FALSE(stack.metric("penetration_mm")->pass());
  EXPECT_FALSE(run("bounce", 50, engine).pass());
  EXPECT_FALSE(run("projectile", 50, engine).pass());
  EXPECT_FALSE(run("slide", 2, engine).pass());
  EXPECT_FALSE(run("roll", 30, engine).pass());
  SceneResult pile = run("pile", 250, engine);
  EXPECT_GT(pile.metric("escaped")->value, 0.0);
  SceneResult spin = run("free_spin", 10, engine);
  EXPECT_FALSE(spin.metric("flip_min_dot")->pass());  // it never turns at all
  EXPECT_FALSE(run("sleep", 5, engine).pass());       // nothing ever sleeps
}

TEST(RunScene, RewindMeasuresStepTime) {
  RewindEngine engine;
  SceneResult r = run("pyramid", 10, engine);
  ASSERT_TRUE(r.error.empty());
  EXPECT_EQ(r.bodies, 56u);  // ground + 55 boxes
  EXPECT_GT(r.ms_per_step, 0.0);
  EXPECT_EQ(r.settings, "substeps=4 relax=1 hertz=30");
}

}  // namespace
}  // namespace rwd::scenes
