// SPDX-License-Identifier: MIT
// Bodies on terrain: boxes set down on the rolling hills of a height field.
#include <algorithm>
#include <cmath>

#include "scene_factories.h"
#include "scene_kit.h"

namespace rwd::scenes {
namespace {

/// `count` 0.4 m boxes (friction 0.8) set down 5 cm above the slopes of a
/// height field of rolling hills (0.5 m cells, hills 0.35 m high and 8 m
/// apart: slopes up to 15 degrees, well inside what friction holds). They
/// must land, settle and stay where they landed: nothing slides off, nothing
/// sinks in or rocks on a cell edge.
class FieldBoxesScene final : public kit::SpecScene {
 public:
  explicit FieldBoxesScene(int count) : SpecScene(count) {
    const int k = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count)))));
    const float spacing = 1.2f;
    const float half = 0.5f * spacing * static_cast<float>(k) + 2.0f;
    const uint32_t samples = static_cast<uint32_t>(std::ceil(2.0f * half / kCell)) + 1;
    std::vector<float> heights(samples * samples);
    for (uint32_t r = 0; r < samples; ++r) {
      for (uint32_t c = 0; c < samples; ++c) {
        heights[r * samples + c] =
            height(static_cast<float>(c) * kCell - half, static_cast<float>(r) * kCell - half);
      }
    }
    BodySpec field;
    field.kind = BodyKind::kStatic;
    field.shape = add_height_field(samples, samples, {kCell, 1.0f, kCell}, std::move(heights));
    field.position = {-half, 0.0f, -half};
    field.friction = 0.8f;
    add(field);
    for (int i = 0; i < count; ++i) {
      const float x = (static_cast<float>(i % k) - 0.5f * static_cast<float>(k - 1)) * spacing;
      const float z = (static_cast<float>(i / k) - 0.5f * static_cast<float>(k - 1)) * spacing;
      // High enough that no corner starts in the ground, on any slope here.
      const Vec3 p{x, height(x, z) + kHalf * 1.5f + 0.05f, z};
      add(kit::box(p, {kHalf, kHalf, kHalf}, 0.8f));
      start_.push_back(p);
    }
  }
  std::string_view name() const override { return "field_boxes"; }
  Tick ticks() const override { return 600; }
  void after_step(Tick tick, const Engine& engine) override {
    // Sideways travel from where each box landed (after the first second).
    if (tick + 1 == 60) {
      for (size_t i = 0; i < start_.size(); ++i) start_[i] = engine.position(handles_[i + 1]);
    }
    if (tick + 1 < 60) return;
    for (size_t i = 0; i < start_.size(); ++i) {
      const Vec3 p = engine.position(handles_[i + 1]);
      drift_m_ = std::max(drift_m_, static_cast<double>(kit::horizontal_distance(p, start_[i])));
    }
    if (tick + 1 == ticks()) {
      double speed = 0.0;
      for (size_t i = 0; i < start_.size(); ++i) {
        speed += kit::point_speed(engine, handles_[i + 1], 0.35f);
      }
      mean_speed_ = speed / static_cast<double>(start_.size());
    }
  }
  std::vector<Metric> metrics() const override {
    return {kit::at_most("drift_m", "m", drift_m_, 0.02,
                         "no box moves more than 2 cm sideways from where it landed, 1 s to 10 s"),
            kit::at_most("mean_speed_mps", "m/s", mean_speed_, 0.01,
                         "after 10 s the boxes' mean speed is below 0.01 m/s")};
  }

 private:
  static float height(float x, float z) {
    return 0.35f * std::sin(0.785f * x) * std::cos(0.785f * z);
  }
  static constexpr float kCell = 0.5f;
  static constexpr float kHalf = 0.2f;
  std::vector<Vec3> start_;
  double drift_m_ = 0.0;
  double mean_speed_ = 0.0;
};

}  // namespace

std::unique_ptr<Scene> make_field_boxes(int count) {
  if (count < 1 || count > 10000) return nullptr;
  return std::make_unique<FieldBoxesScene>(count);
}

}  // namespace rwd::scenes
