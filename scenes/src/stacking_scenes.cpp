// SPDX-License-Identifier: MIT
// Scenes where boxes rest on boxes: stacks, pyramids, mass ratios, a stack
// far from the origin, a kicked stack, a house of cards, and how long a
// pyramid takes to sleep.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "scene_factories.h"
#include "scene_kit.h"

namespace rwd::scenes {
namespace {

using kit::RestingBoxes;

constexpr float kBoxHalf = 0.5f;  // 1 m boxes
constexpr float kLinearSlopMm = 5.0f;
constexpr double kDriftLimitM = 0.1;  // a tenth of a box
// Resting overlap allowed: the linear slop plus 1 mm of solver error.
constexpr double kDepthLimitMm = kLinearSlopMm + 1.0;
constexpr Tick kLastSecond = 60;

std::string depth_text(const char* what) {
  std::ostringstream out;
  out << "deepest resting overlap " << what
      << " <= linear slop (5 mm) + 1 mm (n/a, failed, once a box moved 0.25 m sideways)";
  return out.str();
}

// What a standing structure is judged by: how far any box drifted sideways
// over the whole scene, and how deep boxes rest in each other at the end.
std::vector<Metric> standing_metrics(const RestingBoxes& rest, float seconds) {
  std::ostringstream stands;
  stands << "every box stays within " << kDriftLimitM << " m of its start sideways for " << seconds
         << " s";
  return {kit::at_most("drift_m", "m", rest.drift_m(), kDriftLimitM, stands.str()),
          kit::at_most("penetration_mm", "mm", 1000.0 * rest.depth_m(), kDepthLimitMm,
                       depth_text("in the last second"))};
}

/// A vertical stack of `boxes` 1 m boxes at (x, 0, z) resting on the ground.
class StackScene : public kit::SpecScene {
 public:
  StackScene(int size, int boxes, float x, float seconds, std::string_view name)
      : SpecScene(size), name_(name), seconds_(seconds) {
    add(kit::ground(0.0f, x, 0.0f));
    rest_.set_ground(0.0f);
    for (int i = 0; i < boxes; ++i) {
      Vec3 p{x, kBoxHalf + static_cast<float>(i) * 2.0f * kBoxHalf, 0.0f};
      int body = static_cast<int>(add(kit::box(p, {kBoxHalf, kBoxHalf, kBoxHalf})));
      rest_.track(body, p);
      rest_.support(i == 0 ? -1 : body - 1, body, i == 0 ? kBoxHalf : 2.0f * kBoxHalf);
    }
  }
  std::string_view name() const override { return name_; }
  WorldSpec world() const override {
    WorldSpec w;
    const float x = specs_[0].position.x;
    w.bounds_lower = {x - 1000.0f, -1000.0f, -1000.0f};
    w.bounds_upper = {x + 1000.0f, 1000.0f, 1000.0f};
    return w;
  }
  Tick ticks() const override { return static_cast<Tick>(seconds_ * 60.0f + 0.5f); }
  void after_step(Tick tick, const Engine& engine) override {
    rest_.observe(engine, handles_, tick >= ticks() - kLastSecond);
  }
  std::vector<Metric> metrics() const override { return standing_metrics(rest_, seconds_); }

 private:
  std::string_view name_;
  float seconds_;
  RestingBoxes rest_;
};

/// A 2D pyramid of 1 m boxes, `base` boxes wide, 5 cm apart.
class PyramidScene : public kit::SpecScene {
 public:
  explicit PyramidScene(int base, std::string_view name = "pyramid", float seconds = 10.0f)
      : SpecScene(base), name_(name), seconds_(seconds) {
    add(kit::ground());
    rest_.set_ground(0.0f);
    const float pitch = 2.0f * kBoxHalf + 0.05f;
    std::vector<int> below;
    for (int level = 0; level < base; ++level) {
      std::vector<int> row;
      const int count = base - level;
      for (int i = 0; i < count; ++i) {
        float x = (static_cast<float>(i) - 0.5f * static_cast<float>(count - 1)) * pitch;
        Vec3 p{x, kBoxHalf + static_cast<float>(level) * 2.0f * kBoxHalf, 0.0f};
        int body = static_cast<int>(add(kit::box(p, {kBoxHalf, kBoxHalf, kBoxHalf})));
        rest_.track(body, p);
        if (level == 0) {
          rest_.support(-1, body, kBoxHalf);
        } else {
          rest_.support(below[i], body, 2.0f * kBoxHalf);
          rest_.support(below[i + 1], body, 2.0f * kBoxHalf);
        }
        row.push_back(body);
      }
      below = std::move(row);
    }
  }
  std::string_view name() const override { return name_; }
  Tick ticks() const override { return static_cast<Tick>(seconds_ * 60.0f + 0.5f); }
  void after_step(Tick tick, const Engine& engine) override {
    rest_.observe(engine, handles_, tick >= ticks() - kLastSecond);
    if (asleep_tick_ < 0 && engine.awake_count() == 0) asleep_tick_ = tick + 1;
  }
  std::vector<Metric> metrics() const override { return standing_metrics(rest_, seconds_); }

 protected:
  RestingBoxes rest_;
  Tick asleep_tick_ = -1;

 private:
  std::string_view name_;
  float seconds_;
};

/// How long a settled pyramid takes until every body sleeps, and what a
/// step costs once it does, against a step of the first second (every body
/// awake and settling): a resting scene should cost next to nothing.
class SleepScene final : public PyramidScene {
 public:
  explicit SleepScene(int base) : PyramidScene(base, "sleep", 10.0f) {}
  void step_timed(Tick tick, double ms) override {
    if (tick < kAwakeTicks) {
      awake_ms_ += ms;
    } else if (asleep_tick_ >= 0 && tick >= asleep_tick_) {
      asleep_ms_ += ms;
      ++asleep_steps_;
    }
  }
  std::vector<Metric> metrics() const override {
    double seconds = asleep_tick_ < 0 ? 1e9 : static_cast<double>(asleep_tick_) / 60.0;
    const double awake = awake_ms_ / static_cast<double>(kAwakeTicks);
    const double asleep =
        asleep_steps_ == 0 ? awake : asleep_ms_ / static_cast<double>(asleep_steps_);
    return {kit::at_most("sleep_s", "s", seconds, 3.0,
                         "every body of the pyramid sleeps within 3 s of its creation"),
            kit::at_most("asleep_cost_pct", "%", awake > 0.0 ? 100.0 * asleep / awake : 100.0, 5.0,
                         "a step once every body sleeps costs under 5% of a step of the first "
                         "second (wall time, so only meaningful in the benchmarks)")};
  }

 private:
  static constexpr Tick kAwakeTicks = 60;
  double awake_ms_ = 0.0;
  double asleep_ms_ = 0.0;
  int asleep_steps_ = 0;
};

/// A heavy box on a light one: size is the mass ratio.
class MassRatioScene final : public kit::SpecScene {
 public:
  explicit MassRatioScene(int ratio) : SpecScene(ratio) {
    add(kit::ground());
    rest_.set_ground(0.0f);
    Vec3 low{0.0f, kBoxHalf, 0.0f};
    Vec3 high{0.0f, 3.0f * kBoxHalf, 0.0f};
    int a = static_cast<int>(add(kit::box(low, {kBoxHalf, kBoxHalf, kBoxHalf})));
    BodySpec heavy = kit::box(high, {kBoxHalf, kBoxHalf, kBoxHalf});
    heavy.density = 1000.0f * static_cast<float>(ratio);
    int b = static_cast<int>(add(heavy));
    rest_.track(a, low);
    rest_.track(b, high);
    rest_.support(-1, a, kBoxHalf);
    rest_.support(a, b, 2.0f * kBoxHalf);
  }
  std::string_view name() const override { return "mass_ratio"; }
  Tick ticks() const override { return 600; }
  void after_step(Tick tick, const Engine& engine) override {
    rest_.observe(engine, handles_, tick >= ticks() - kLastSecond);
  }
  std::vector<Metric> metrics() const override {
    return {kit::at_most("drift_m", "m", rest_.drift_m(), kDriftLimitM,
                         "both boxes stay within 0.1 m of their start sideways for 10 s"),
            kit::at_most("penetration_mm", "mm", 1000.0 * rest_.depth_m(), kDepthLimitMm,
                         depth_text("in the last second"))};
  }

 private:
  RestingBoxes rest_;
};

/// A settled stack whose top box is kicked sideways at 1 m/s after 1 s.
class KickScene final : public kit::SpecScene {
 public:
  explicit KickScene(int boxes) : SpecScene(boxes) {
    add(kit::ground());
    for (int i = 0; i < boxes; ++i) {
      Vec3 p{0.0f, kBoxHalf + static_cast<float>(i) * 2.0f * kBoxHalf, 0.0f};
      int body = static_cast<int>(add(kit::box(p, {kBoxHalf, kBoxHalf, kBoxHalf})));
      if (i + 1 < boxes) rest_.track(body, p);
    }
  }
  std::string_view name() const override { return "kick"; }
  Tick ticks() const override { return 240; }
  void before_step(Tick tick, Engine& engine) override {
    if (tick != kKickTick) return;
    const BodyHandle top = handles_.back();
    const float mass = 8.0f * kBoxHalf * kBoxHalf * kBoxHalf * 1000.0f;
    engine.apply_impulse(top, {mass * 1.0f, 0.0f, 0.0f}, engine.position(top));
  }
  void after_step(Tick tick, const Engine& engine) override {
    rest_.observe(engine, handles_, false);
    if (tick < kKickTick + 1 || rest_tick_ >= 0) return;
    float fastest = 0.0f;
    for (size_t i = 1; i < handles_.size(); ++i) {
      fastest = std::max(fastest, kit::point_speed(engine, handles_[i], 0.866f));
    }
    if (fastest < 0.05f) rest_tick_ = tick + 1;
  }
  std::vector<Metric> metrics() const override {
    double rest_s = rest_tick_ < 0 ? 1e9 : static_cast<double>(rest_tick_ - kKickTick) / 60.0;
    return {kit::at_most("rest_s", "s", rest_s, 1.0,
                         "every box moves slower than 0.05 m/s within 1 s of the kick"),
            kit::at_most("drift_m", "m", rest_.drift_m(), kDriftLimitM,
                         "the boxes under the kicked one stay within 0.1 m sideways")};
  }

 private:
  static constexpr Tick kKickTick = 60;
  RestingBoxes rest_;
  Tick rest_tick_ = -1;
};

/// A house of cards `levels` frames wide at the base: pairs of 2 cm thick
/// cards leaning 25 degrees off vertical against each other, a flat card
/// bridging each two neighbouring frames, the next level's frames on those.
/// It must stand for 10 s.
class CardHouseScene final : public kit::SpecScene {
 public:
  explicit CardHouseScene(int levels) : SpecScene(levels) {
    add(kit::ground());
    const float tilt = kit::radians(25.0f);
    const float st = std::sin(tilt);
    const float ct = std::cos(tilt);
    const float gap = 0.0005f;  // half a millimetre between touching faces
    const float pitch = 0.95f;  // apex to apex
    float base_y = 0.0f;
    for (int level = 0; level < levels; ++level) {
      const int frames = levels - level;
      const float first = -0.5f * pitch * static_cast<float>(frames - 1);
      float apex_y = 0.0f;
      for (int f = 0; f < frames; ++f) {
        const float apex_x = first + pitch * static_cast<float>(f);
        for (float side : {-1.0f, 1.0f}) {
          // The card's top outer edge meets the apex; its lowest edge is
          // just above the floor it stands on.
          Vec3 c{apex_x + side * (kCardHalf.y * st + kCardHalf.x * ct + gap),
                 base_y + kCardHalf.y * ct + kCardHalf.x * st + gap, 0.0f};
          BodySpec card = kit::box(c, kCardHalf);
          card.rotation = kit::axis_angle({0.0f, 0.0f, 1.0f}, side * tilt);
          rest_.track(static_cast<int>(add(card)), c);
          apex_y = c.y + kCardHalf.y * ct + kCardHalf.x * st;
        }
      }
      if (frames == 1) break;
      // Flat cards from apex to apex.
      const float flat_y = apex_y + kFlatHalf.y + gap;
      for (int f = 0; f + 1 < frames; ++f) {
        Vec3 c{first + pitch * (static_cast<float>(f) + 0.5f), flat_y, 0.0f};
        rest_.track(static_cast<int>(add(kit::box(c, kFlatHalf))), c);
      }
      base_y = flat_y + kFlatHalf.y;
    }
  }
  std::string_view name() const override { return "card_house"; }
  Tick ticks() const override { return 600; }
  void after_step(Tick, const Engine& engine) override { rest_.observe(engine, handles_, false); }
  std::vector<Metric> metrics() const override {
    return {kit::at_most("drift_m", "m", rest_.drift_m(), 0.05,
                         "every card stays within 5 cm of its start sideways for 10 s")};
  }

 private:
  // Leaning cards: 2 cm thick (x), 1 m long (y), 0.7 m wide (z), before
  // turning; flat cards 1.2 m long (x).
  static constexpr Vec3 kCardHalf{0.01f, 0.5f, 0.35f};
  static constexpr Vec3 kFlatHalf{0.6f, 0.01f, 0.35f};
  RestingBoxes rest_;
};

/// A log cabin of capsules: `layers` layers of two parallel 2 m logs
/// (0.2 m radius), each layer across the one below, so every log rests on
/// two crossings (a crossing touches at one point). Round logs on round
/// logs are in neutral balance, so the criterion allows the same creep as
/// the card house.
class LogCabinScene final : public kit::SpecScene {
 public:
  explicit LogCabinScene(int layers) : SpecScene(layers) {
    add(kit::ground());
    rest_.set_ground(0.0f);
    const Quat along_x = kit::axis_angle({0.0f, 0.0f, 1.0f}, -0.5f * kit::kPi);
    const Quat along_z = kit::axis_angle({1.0f, 0.0f, 0.0f}, 0.5f * kit::kPi);
    int below[2] = {-1, -1};
    for (int layer = 0; layer < layers; ++layer) {
      int here[2];
      for (int side = 0; side < 2; ++side) {
        const float offset = side == 0 ? -kSpacing : kSpacing;
        const float y = kRadius + 2.0f * kRadius * static_cast<float>(layer);
        const Vec3 p = layer % 2 == 0 ? Vec3{0.0f, y, offset} : Vec3{offset, y, 0.0f};
        BodySpec log = kit::capsule(p, kRadius, kHalfHeight);
        log.rotation = layer % 2 == 0 ? along_x : along_z;
        here[side] = static_cast<int>(add(log));
        rest_.track(here[side], p);
        if (layer == 0) {
          rest_.support(-1, here[side], kRadius);
        } else {
          rest_.support(below[0], here[side], 2.0f * kRadius);
          rest_.support(below[1], here[side], 2.0f * kRadius);
        }
      }
      below[0] = here[0];
      below[1] = here[1];
    }
  }
  std::string_view name() const override { return "log_cabin"; }
  Tick ticks() const override { return 600; }
  void after_step(Tick tick, const Engine& engine) override {
    // Overlaps are judged once settled, over the last second.
    rest_.observe(engine, handles_, tick >= ticks() - 60);
  }
  std::vector<Metric> metrics() const override {
    return {kit::at_most("drift_m", "m", rest_.drift_m(), 0.05,
                         "every log stays within 5 cm of its start sideways for 10 s"),
            kit::at_most("penetration_mm", "mm", 1000.0 * rest_.depth_m(), kDepthLimitMm,
                         "deepest resting overlap of a crossing in the last second <= linear "
                         "slop (5 mm) + 1 mm")};
  }

 private:
  static constexpr float kRadius = 0.2f;
  static constexpr float kHalfHeight = 0.8f;
  static constexpr float kSpacing = 0.6f;
  RestingBoxes rest_;
};

/// A column of `count` hexagonal prism hulls (0.5 m circumradius, 0.4 m
/// tall) on the ground, each turned 30 degrees from the one below so edges
/// cross faces. The prism's points have their origin at the centre of its
/// base, so the column also checks that hull bodies turn about their centre
/// of mass while reporting their authored origin.
class HullStackScene final : public kit::SpecScene {
 public:
  explicit HullStackScene(int count) : SpecScene(count) {
    add(kit::ground());
    rest_.set_ground(0.0f);
    const Shape prism = add_hull(kit::prism_points(6, 0.5f, kHeight));
    for (int i = 0; i < count; ++i) {
      const Vec3 p{0.0f, kHeight * static_cast<float>(i), 0.0f};
      BodySpec b = kit::hull(prism, p);
      b.rotation = kit::axis_angle({0.0f, 1.0f, 0.0f}, kit::radians(i % 2 == 0 ? 0.0f : 30.0f));
      const int body = static_cast<int>(add(b));
      rest_.track(body, p);
      rest_.support(i == 0 ? -1 : body - 1, body, i == 0 ? 0.0f : kHeight);
    }
  }
  std::string_view name() const override { return "hull_stack"; }
  Tick ticks() const override { return 600; }
  void after_step(Tick tick, const Engine& engine) override {
    rest_.observe(engine, handles_, tick >= ticks() - kLastSecond);
  }
  std::vector<Metric> metrics() const override { return standing_metrics(rest_, 10.0f); }

 private:
  static constexpr float kHeight = 0.4f;
  RestingBoxes rest_;
};

/// `count` lopsided props (a 1 m cube with a 3 m arm of 0.2 m square
/// section: a compound whose centre of mass is 0.21 m from the cube's
/// centre, toward the arm), each set on a 5 cm post right under its centre
/// of mass, so it balances only if the engine turns it about its true
/// centre of mass; every other prop is turned 90 degrees about y.
class CompoundBalanceScene final : public kit::SpecScene {
 public:
  explicit CompoundBalanceScene(int count) : SpecScene(count) {
    add(kit::ground());
    const Shape prop =
        add_compound({{Shape::make_box({0.5f, 0.5f, 0.5f}), {}, {}},
                      {Shape::make_box({1.5f, 0.1f, 0.1f}), {2.0f, 0.0f, 0.0f}, {}}});
    // Centre of mass along the arm: volumes 1 and 0.12 m^3 at 0 and 2 m.
    const float com = 0.24f / 1.12f;
    for (int i = 0; i < count; ++i) {
      const float x = 6.0f * static_cast<float>(i);
      add(kit::fixed(kit::box({x, 1.0f, 0.0f}, {0.025f, 1.0f, 0.025f})));
      BodySpec b = kit::hull(prop, {x - com, 2.5f, 0.0f});
      if (i % 2 == 1) {
        // A quarter turn about y takes the arm from +x to -z: the origin
        // goes com along +z so the centre of mass stays over the post.
        b.rotation = kit::axis_angle({0.0f, 1.0f, 0.0f}, kit::radians(90.0f));
        b.position = {x, 2.5f, com};
      }
      props_.push_back(add(b));
    }
  }
  std::string_view name() const override { return "compound_balance"; }
  Tick ticks() const override { return 300; }
  void after_step(Tick, const Engine& engine) override {
    for (size_t body : props_) {
      const Quat q = engine.rotation(handles_[body]);
      const double turn =
          2.0 * std::asin(std::min(1.0, std::sqrt(static_cast<double>(q.x * q.x + q.z * q.z))));
      tilt_ = std::max(tilt_, turn);
    }
  }
  std::vector<Metric> metrics() const override {
    return {kit::at_most("tilt_rad", "rad", tilt_, 0.02,
                         "each prop, set on a post under its centre of mass, tilts less than "
                         "0.02 rad in 5 s")};
  }

 private:
  std::vector<size_t> props_;
  double tilt_ = 0.0;
};

}  // namespace

std::unique_ptr<Scene> make_compound_balance(int count) {
  if (count < 1 || count > 100) return nullptr;
  return std::make_unique<CompoundBalanceScene>(count);
}

std::unique_ptr<Scene> make_hull_stack(int count) {
  if (count < 1 || count > 100) return nullptr;
  return std::make_unique<HullStackScene>(count);
}

std::unique_ptr<Scene> make_log_cabin(int layers) {
  if (layers < 1 || layers > 50) return nullptr;
  return std::make_unique<LogCabinScene>(layers);
}

std::unique_ptr<Scene> make_stack(int boxes) {
  if (boxes < 1 || boxes > 200) return nullptr;
  return std::make_unique<StackScene>(boxes, boxes, 0.0f, 60.0f, "stack");
}
std::unique_ptr<Scene> make_far_stack(int distance_m) {
  if (distance_m < 0 || distance_m > 90000) return nullptr;
  return std::make_unique<StackScene>(distance_m, 5, static_cast<float>(distance_m), 20.0f,
                                      "far_stack");
}
std::unique_ptr<Scene> make_pyramid(int base) {
  if (base < 1 || base > 150) return nullptr;
  return std::make_unique<PyramidScene>(base);
}
std::unique_ptr<Scene> make_sleep(int base) {
  if (base < 1 || base > 150) return nullptr;
  return std::make_unique<SleepScene>(base);
}
std::unique_ptr<Scene> make_mass_ratio(int ratio) {
  if (ratio < 1 || ratio > 10000) return nullptr;
  return std::make_unique<MassRatioScene>(ratio);
}
std::unique_ptr<Scene> make_card_house(int levels) {
  if (levels < 1 || levels > 10) return nullptr;
  return std::make_unique<CardHouseScene>(levels);
}
std::unique_ptr<Scene> make_kick(int boxes) {
  if (boxes < 2 || boxes > 50) return nullptr;
  return std::make_unique<KickScene>(boxes);
}

}  // namespace rwd::scenes
