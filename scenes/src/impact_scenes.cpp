// SPDX-License-Identifier: MIT
// Scenes of violent motion: projectiles against a thin wall, piles of boxes
// (and of boxes and capsules) dropped into a bin, and boxes created
// overlapping.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "scene_factories.h"
#include "scene_kit.h"

namespace rwd::scenes {
namespace {

/// A 10 cm ball fired at `speed` m/s at a 5 cm thick wall, no gravity: it
/// must not come out on the far side.
class ProjectileScene final : public kit::SpecScene {
 public:
  explicit ProjectileScene(int speed) : SpecScene(speed) {
    add(kit::fixed(kit::box({kWallX, 0.0f, 0.0f}, {0.025f, 2.0f, 2.0f})));
    BodySpec ball = kit::sphere({0.0f, 0.0f, 0.0f}, 0.05f);
    ball.linear_velocity = {static_cast<float>(speed), 0.0f, 0.0f};
    ball.continuous = true;
    add(ball);
  }
  std::string_view name() const override { return "projectile"; }
  WorldSpec world() const override {
    WorldSpec w;
    w.gravity = {};
    return w;
  }
  Tick ticks() const override { return 60; }
  void after_step(Tick, const Engine& engine) override {
    if (engine.position(handles_[1]).x > kWallX) tunneled_ = 1.0;
  }
  std::vector<Metric> metrics() const override {
    return {kit::at_most("tunneled", "", tunneled_, 0.0,
                         "the ball never reaches the far side of the 5 cm wall (1 = it did)")};
  }

 private:
  static constexpr float kWallX = 5.0f;
  double tunneled_ = 0.0;
};

/// `count` 0.5 m boxes released in a loose lattice (about ten layers) inside an open bin; they
/// fall, tumble and settle. None may leave the bin, and after 6 s the pile
/// should be nearly at rest. The mixed pile makes every other body a
/// capsule (0.15 m radius, 0.7 m long), so boxes and capsules meet in every
/// pairing; the convex pile cycles through box, capsule, sphere, rock (a
/// stretched icosahedron hull) and hexagonal prism hull; the mesh pile drops
/// the convex mix onto a bumpy triangle-mesh floor (0.5 m cells, bumps of
/// +-8 cm) instead of a box; the compound pile drops tables (a top on four
/// legs, five boxes) and dumbbells (a capsule bar with a ball at each end)
/// in turn, bodies that rest on a few small contacts far apart.
enum class PileMix : uint8_t { kBoxes, kCapsules, kConvex, kOnMesh, kCompounds };

class PileScene final : public kit::SpecScene {
 public:
  PileScene(int count, PileMix mix) : SpecScene(count), mix_(mix) {
    if (mix == PileMix::kConvex || mix == PileMix::kOnMesh) {
      rock_ = add_hull(kit::rock_points({0.3f, 0.22f, 0.26f}));
      // Points about the prism's middle, so it turns about its centre.
      std::vector<Vec3> prism = kit::prism_points(6, 0.28f, 0.36f);
      for (Vec3& p : prism) p.y -= 0.18f;
      prism_ = add_hull(std::move(prism));
    }
    if (mix == PileMix::kCompounds) {
      // Both reach at most 0.37 m from their origin, inside the lattice's
      // 0.4 m half pitch.
      std::vector<sim::CompoundChild> table = {
          {Shape::make_box({0.28f, 0.02f, 0.18f}), {0.0f, 0.12f, 0.0f}, {}}};
      for (const float x : {-0.25f, 0.25f}) {
        for (const float z : {-0.15f, 0.15f}) {
          table.push_back({Shape::make_box({0.02f, 0.1f, 0.02f}), {x, 0.0f, z}, {}});
        }
      }
      table_ = add_compound(std::move(table));
      const Quat lying = kit::axis_angle({0.0f, 0.0f, 1.0f}, kit::radians(90.0f));
      dumbbell_ = add_compound({{Shape::make_capsule(0.03f, 0.25f), {}, lying},
                                {Shape::make_sphere(0.09f), {-0.28f, 0.0f, 0.0f}, {}},
                                {Shape::make_sphere(0.09f), {0.28f, 0.0f, 0.0f}, {}}});
    }
    // About ten layers of k x k boxes, 0.8 m apart (a turned box reaches
    // at most 0.39 m from its centre, so none starts touching another).
    const int k = std::max(2, static_cast<int>(std::ceil(std::sqrt(count / 10.0))));
    const float pitch = 0.8f;
    inner_half_ = 0.5f * pitch * static_cast<float>(k) + 0.5f;
    const int layers = (count + k * k - 1) / (k * k);
    wall_top_ = 1.0f + pitch * static_cast<float>(layers) + 1.0f;
    if (mix == PileMix::kOnMesh) {
      BodySpec floor;
      floor.kind = BodyKind::kStatic;
      floor.shape = bumpy_floor(inner_half_ + 1.0f);
      add(floor);
    } else {
      add(kit::ground());
    }
    const float t = 0.25f;  // wall half thickness
    const float h = 0.5f * wall_top_;
    const float span = inner_half_ + 2.0f * t;
    add(kit::fixed(kit::box({inner_half_ + t, h, 0.0f}, {t, h, span})));
    add(kit::fixed(kit::box({-inner_half_ - t, h, 0.0f}, {t, h, span})));
    add(kit::fixed(kit::box({0.0f, h, inner_half_ + t}, {span, h, t})));
    add(kit::fixed(kit::box({0.0f, h, -inner_half_ - t}, {span, h, t})));
    first_box_ = specs_.size();
    for (int i = 0; i < count; ++i) {
      const int layer = i / (k * k);
      const int row = (i / k) % k;
      const int col = i % k;
      // Odd layers shift and turn a little so the boxes do not stack neatly.
      const float shift = (layer % 2 == 1) ? 0.2f : 0.0f;
      Vec3 p{(static_cast<float>(col) - 0.5f * static_cast<float>(k - 1)) * pitch + shift,
             1.0f + pitch * static_cast<float>(layer),
             (static_cast<float>(row) - 0.5f * static_cast<float>(k - 1)) * pitch - shift};
      BodySpec b = make_body(i, p);
      const float turn = 0.3f * static_cast<float>((i * 7) % 5 - 2);
      b.rotation = kit::axis_angle({0.6f, 0.0f, 0.8f}, turn);
      add(b);
    }
  }
  std::string_view name() const override {
    switch (mix_) {
      case PileMix::kBoxes:
        return "pile";
      case PileMix::kCapsules:
        return "mixed_pile";
      case PileMix::kConvex:
        return "convex_pile";
      case PileMix::kOnMesh:
        return "mesh_pile";
      case PileMix::kCompounds:
        return "compound_pile";
    }
    return "pile";
  }
  Tick ticks() const override { return 360; }
  void after_step(Tick tick, const Engine& engine) override {
    if (tick + 1 != ticks()) return;
    const float limit = inner_half_ + 0.5f;
    double speed_sum = 0.0;
    for (size_t i = first_box_; i < handles_.size(); ++i) {
      const Vec3 p = engine.position(handles_[i]);
      const bool inside = engine.enabled(handles_[i]) && std::fabs(p.x) < limit &&
                          std::fabs(p.z) < limit && p.y > -0.1f && std::isfinite(p.y);
      if (!inside) ++escaped_;
      // The farthest surface point of either shape: a box's corner, a
      // capsule's pole.
      speed_sum += kit::point_speed(engine, handles_[i], 0.433f);
    }
    mean_speed_ = speed_sum / static_cast<double>(handles_.size() - first_box_);
  }
  std::vector<Metric> metrics() const override {
    return {kit::at_most("escaped", "", escaped_, 0.0,
                         "no box ends outside the bin or below its floor"),
            kit::at_most("mean_speed_mps", "m/s", mean_speed_, 0.05,
                         "after 6 s the mean speed of the boxes is below 0.05 m/s")};
  }

 private:
  // A square triangle mesh reaching `half` m from the origin each way, top
  // near y = 0 with bumps of +-8 cm (shared vertices, so the edges between
  // its cells are internal).
  Shape bumpy_floor(float half) {
    const int n = std::max(2, static_cast<int>(std::ceil(2.0f * half / 0.5f)));
    const float cell = 2.0f * half / static_cast<float>(n);
    std::vector<Vec3> vertices;
    std::vector<uint32_t> indices;
    for (int r = 0; r <= n; ++r) {
      for (int c = 0; c <= n; ++c) {
        const float x = static_cast<float>(c) * cell - half;
        const float z = static_cast<float>(r) * cell - half;
        vertices.push_back({x, 0.08f * std::sin(1.3f * x) * std::cos(1.1f * z), z});
      }
    }
    const auto at = [n](int r, int c) { return static_cast<uint32_t>(r * (n + 1) + c); };
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) {
        indices.insert(indices.end(), {at(r, c), at(r + 1, c), at(r + 1, c + 1)});
        indices.insert(indices.end(), {at(r, c), at(r + 1, c + 1), at(r, c + 1)});
      }
    }
    return add_mesh(std::move(vertices), std::move(indices));
  }

  BodySpec make_body(int i, Vec3 p) const {
    const BodySpec box = kit::box(p, {0.25f, 0.25f, 0.25f});
    switch (mix_) {
      case PileMix::kBoxes:
        return box;
      case PileMix::kCapsules:
        return i % 2 == 1 ? kit::capsule(p, 0.15f, 0.2f) : box;
      case PileMix::kConvex:
      case PileMix::kOnMesh:
        switch (i % 5) {
          case 1:
            return kit::capsule(p, 0.15f, 0.2f);
          case 2:
            return kit::sphere(p, 0.25f);
          case 3:
            return kit::hull(rock_, p);
          case 4:
            return kit::hull(prism_, p);
          default:
            return box;
        }
      case PileMix::kCompounds:
        return kit::hull(i % 2 == 0 ? table_ : dumbbell_, p);
    }
    return box;
  }

  PileMix mix_ = PileMix::kBoxes;
  Shape rock_;
  Shape prism_;
  Shape table_;
  Shape dumbbell_;
  float inner_half_ = 0.0f;
  float wall_top_ = 0.0f;
  size_t first_box_ = 0;
  double escaped_ = 0.0;
  double mean_speed_ = 0.0;
};

// Pushing boxes out of each other must not launch them: the push-out is a
// correction, not an impulse, so nothing should move faster than 3 m/s.
constexpr double kRecoverLimitS = 3.0;
constexpr double kMaxSpeedLimitMps = 3.0;

/// `count` 1 m boxes created in a column, each half inside the one below
/// (the lowest half inside the ground). They must separate without being
/// thrown about.
class OverlapScene final : public kit::SpecScene {
 public:
  explicit OverlapScene(int count) : SpecScene(count) {
    add(kit::ground());
    rest_.set_ground(0.0f);
    // Each box starts half inside the one below it (and the lowest half
    // inside the ground): 0.5 m of overlap per contact.
    for (int i = 0; i < count; ++i) {
      Vec3 p{0.0f, 0.25f + 0.5f * static_cast<float>(i), 0.0f};
      int body = static_cast<int>(add(kit::box(p, {0.5f, 0.5f, 0.5f})));
      rest_.track(body, p);
      rest_.support(i == 0 ? -1 : body - 1, body, i == 0 ? 0.5f : 1.0f);
    }
  }
  std::string_view name() const override { return "overlap"; }
  Tick ticks() const override { return 180; }
  void after_step(Tick tick, const Engine& engine) override {
    for (size_t i = 1; i < handles_.size(); ++i) {
      max_speed_ =
          std::max(max_speed_, static_cast<double>(kit::point_speed(engine, handles_[i], 0.0f)));
    }
    if (recovered_tick_ >= 0) return;
    kit::RestingBoxes now = rest_;
    now.observe(engine, handles_, true);
    if (now.depth_m() <= 0.02f) recovered_tick_ = tick + 1;
  }
  std::vector<Metric> metrics() const override {
    double seconds = recovered_tick_ < 0 ? 1e9 : static_cast<double>(recovered_tick_) / 60.0;
    return {kit::at_most("recover_s", "s", seconds, kRecoverLimitS,
                         "every overlap is below 20 mm within 3 s"),
            kit::at_most("max_speed_mps", "m/s", max_speed_, kMaxSpeedLimitMps,
                         "no point of any box moves faster than 3 m/s while the overlaps resolve")};
  }

 private:
  kit::RestingBoxes rest_;
  double max_speed_ = 0.0;
  Tick recovered_tick_ = -1;
};

}  // namespace

std::unique_ptr<Scene> make_projectile(int speed) {
  if (speed < 1 || speed > 390) return nullptr;
  return std::make_unique<ProjectileScene>(speed);
}
std::unique_ptr<Scene> make_pile(int count) {
  if (count < 1 || count > 100000) return nullptr;
  return std::make_unique<PileScene>(count, PileMix::kBoxes);
}
std::unique_ptr<Scene> make_mixed_pile(int count) {
  if (count < 1 || count > 100000) return nullptr;
  return std::make_unique<PileScene>(count, PileMix::kCapsules);
}
std::unique_ptr<Scene> make_convex_pile(int count) {
  if (count < 1 || count > 100000) return nullptr;
  return std::make_unique<PileScene>(count, PileMix::kConvex);
}
std::unique_ptr<Scene> make_mesh_pile(int count) {
  if (count < 1 || count > 100000) return nullptr;
  return std::make_unique<PileScene>(count, PileMix::kOnMesh);
}
std::unique_ptr<Scene> make_compound_pile(int count) {
  if (count < 1 || count > 100000) return nullptr;
  return std::make_unique<PileScene>(count, PileMix::kCompounds);
}
std::unique_ptr<Scene> make_overlap(int count) {
  if (count < 1 || count > 50) return nullptr;
  return std::make_unique<OverlapScene>(count);
}

}  // namespace rwd::scenes
