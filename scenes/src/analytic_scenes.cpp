// SPDX-License-Identifier: MIT
// Scenes with an analytic answer: free fall, bounce apex, stop distance,
// sticking and slipping on an incline, rolling, and the intermediate axis
// flip of a free-spinning box.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "scene_factories.h"
#include "scene_kit.h"

namespace rwd::scenes {
namespace {

constexpr float kG = 9.81f;
constexpr float kTick = 1.0f / 60.0f;

/// A sphere dropped in empty space for `seconds`: drop = g t^2 / 2.
class FreeFallScene final : public kit::SpecScene {
 public:
  explicit FreeFallScene(int seconds) : SpecScene(seconds) {
    add(kit::sphere({0.0f, 0.0f, 0.0f}, 0.5f));
  }
  std::string_view name() const override { return "free_fall"; }
  Tick ticks() const override { return size() * 60; }
  void after_step(Tick, const Engine& engine) override {
    drop_m_ = -engine.position(handles_[0]).y;
  }
  std::vector<Metric> metrics() const override {
    const double t = static_cast<double>(ticks()) * kTick;
    const double expected = 0.5 * kG * t * t;
    return {kit::at_most("drop_error_pct", "%", kit::error_pct(drop_m_, expected), 1.0,
                         "drop after t seconds within 1% of g t^2 / 2")};
  }

 private:
  double drop_m_ = 0.0;
};

/// A sphere dropped from 2 m onto the ground; size is restitution in percent.
/// The first apex after the bounce is e^2 h.
class BounceScene final : public kit::SpecScene {
 public:
  explicit BounceScene(int percent) : SpecScene(percent) {
    add(kit::ground());
    BodySpec ball = kit::sphere({0.0f, kRadius + kDropM, 0.0f}, kRadius);
    ball.restitution = static_cast<float>(percent) / 100.0f;
    add(ball);
  }
  std::string_view name() const override { return "bounce"; }
  Tick ticks() const override { return 180; }
  void after_step(Tick, const Engine& engine) override {
    const float vy = engine.linear_velocity(handles_[1]).y;
    const float y = engine.position(handles_[1]).y - kRadius;
    if (phase_ == 0 && vy > 0.0f) phase_ = 1;  // bounced
    if (phase_ == 1) {
      apex_m_ = std::max(apex_m_, static_cast<double>(y));
      if (vy < 0.0f) phase_ = 2;  // past the first apex
    }
  }
  std::vector<Metric> metrics() const override {
    const double e = static_cast<double>(size()) / 100.0;
    return {kit::at_most("apex_error_pct", "%", kit::error_pct(apex_m_, e * e * kDropM), 5.0,
                         "first apex after the bounce within 5% of e^2 h (h = 2 m)")};
  }

 private:
  static constexpr float kRadius = 0.5f;
  static constexpr float kDropM = 2.0f;
  int phase_ = 0;
  double apex_m_ = 0.0;
};

/// A box sliding on the ground at `speed` m/s with mu = 0.5 stops after
/// v^2 / (2 mu g).
class SlideScene final : public kit::SpecScene {
 public:
  explicit SlideScene(int speed) : SpecScene(speed) {
    add(kit::ground(0.0f, 0.0f, 0.0f, kMu));
    BodySpec b = kit::box({-20.0f, 0.5f, 0.0f}, {0.5f, 0.5f, 0.5f}, kMu);
    b.linear_velocity = {static_cast<float>(speed), 0.0f, 0.0f};
    add(b);
  }
  std::string_view name() const override { return "slide"; }
  Tick ticks() const override {
    return static_cast<Tick>(60.0f * (static_cast<float>(size()) / (kMu * kG) + 1.0f));
  }
  void after_step(Tick, const Engine& engine) override {
    distance_m_ = engine.position(handles_[1]).x + 20.0f;
  }
  std::vector<Metric> metrics() const override {
    const double v = size();
    const double expected = v * v / (2.0 * kMu * kG);
    return {kit::at_most("stop_error_pct", "%", kit::error_pct(distance_m_, expected), 5.0,
                         "stop distance within 5% of v^2 / (2 mu g), mu = 0.5")};
  }

 private:
  static constexpr float kMu = 0.5f;
  double distance_m_ = 0.0;
};

/// A ball rolling on flat ground at 2 m/s with a coefficient of rolling
/// resistance of N/10 (the seeds' authoring scale): it stops after v^2 /
/// (2 a), a = c g / (1 + I / (m r^2)) = c g / 1.4 for a solid ball.
class RollStopScene final : public kit::SpecScene {
 public:
  explicit RollStopScene(int tenths) : SpecScene(tenths) {
    BodySpec ground = kit::ground(0.0f, 0.0f, 0.0f, 0.8f);
    add(ground);
    BodySpec ball = kit::sphere({-20.0f, kRadius, 0.0f}, kRadius, 0.8f);
    ball.linear_velocity = {kSpeed, 0.0f, 0.0f};
    ball.angular_velocity = {0.0f, 0.0f, -kSpeed / kRadius};  // rolling from the start
    ball.rolling_resistance = coefficient();
    ball.angular_damping = 0.0f;
    add(ball);
  }
  std::string_view name() const override { return "roll_stop"; }
  Tick ticks() const override { return 180; }
  void after_step(Tick, const Engine& engine) override {
    distance_m_ = engine.position(handles_[1]).x + 20.0f;
  }
  std::vector<Metric> metrics() const override {
    const double a = coefficient() * kG / 1.4;
    const double expected = kSpeed * kSpeed / (2.0 * a);
    return {kit::at_most("stop_error_pct", "%", kit::error_pct(distance_m_, expected), 5.0,
                         "a ball rolling at 2 m/s stops within 5% of v^2 / (2 c g / 1.4)")};
  }

 private:
  float coefficient() const { return 0.1f * static_cast<float>(size()); }
  static constexpr float kRadius = 0.25f;
  static constexpr float kSpeed = 2.0f;
  double distance_m_ = 0.0;
};

/// An inclined static slab and the frame of its top surface.
struct Incline {
  float angle = 0.0f;
  Quat rotation;
  Vec3 along;   ///< unit vector up the slope
  Vec3 normal;  ///< unit surface normal
  Vec3 centre;  ///< a point on the top surface

  explicit Incline(float angle_rad) : angle(angle_rad) {
    rotation = kit::axis_angle({0.0f, 0.0f, 1.0f}, angle_rad);
    along = {std::cos(angle_rad), std::sin(angle_rad), 0.0f};
    normal = {-std::sin(angle_rad), std::cos(angle_rad), 0.0f};
    centre = {0.0f, 0.0f, 0.0f};
  }
  BodySpec slab(float friction) const {
    BodySpec s = kit::fixed(kit::box(centre - normal * 0.5f, {30.0f, 0.5f, 5.0f}, friction));
    s.rotation = rotation;
    return s;
  }
  /// A point `up` metres up the slope, `height` above the surface.
  Vec3 at(float up, float height) const { return centre + along * up + normal * height; }
  float up_slope(Vec3 p) const { return sim::dot(p - centre, along); }
};

/// A box on an incline. Sticking (tan angle < mu): it must not creep.
/// Slipping (tan angle > mu): it travels g (sin - mu cos) t^2 / 2, whatever
/// its shape: the hull variant slides an octagonal prism hull (0.5 m
/// circumradius, 0.6 m tall, its points' origin at the centre of its base,
/// so it also checks that a hull body turns about its centre of mass).
class InclineScene final : public kit::SpecScene {
 public:
  InclineScene(int degrees, float mu, bool stick, bool hull = false)
      : SpecScene(degrees),
        incline_(kit::radians(static_cast<float>(degrees))),
        mu_(mu),
        stick_(stick),
        hull_(hull) {
    add(incline_.slab(mu));
    BodySpec b =
        hull ? kit::hull(add_hull(kit::prism_points(8, 0.5f, 0.6f)), incline_.at(10.0f, 0.0f), mu)
             : kit::box(incline_.at(10.0f, 0.5f), {0.5f, 0.5f, 0.5f}, mu);
    b.rotation = incline_.rotation;
    add(b);
    start_ = incline_.up_slope(b.position);
  }
  std::string_view name() const override {
    return stick_ ? "incline_stick" : (hull_ ? "hull_slip" : "incline_slip");
  }
  Tick ticks() const override { return stick_ ? 180 : 120; }
  void after_step(Tick, const Engine& engine) override {
    travel_m_ = start_ - incline_.up_slope(engine.position(handles_[1]));
    max_travel_m_ = std::max(max_travel_m_, std::fabs(travel_m_));
  }
  std::vector<Metric> metrics() const override {
    if (stick_) {
      std::ostringstream text;
      text << "a box with mu = " << mu_ << " on a " << size()
           << "-degree slope (tan < mu) moves less than 5 mm in 3 s";
      return {kit::at_most("creep_mm", "mm", 1000.0 * max_travel_m_, 5.0, text.str())};
    }
    const double t = static_cast<double>(ticks()) * kTick;
    const double a = kG * (std::sin(incline_.angle) - mu_ * std::cos(incline_.angle));
    return {kit::at_most("travel_error_pct", "%", kit::error_pct(travel_m_, 0.5 * a * t * t), 3.0,
                         "distance slid in 2 s (mu = 0.3) within 3% of g (sin - mu cos) t^2 / 2")};
  }

 private:
  Incline incline_;
  float mu_;
  bool stick_;
  bool hull_;
  float start_ = 0.0f;
  double travel_m_ = 0.0;
  double max_travel_m_ = 0.0;
};

/// A solid sphere rolling down an incline without slipping: 5/7 g sin.
class RollScene final : public kit::SpecScene {
 public:
  explicit RollScene(int degrees)
      : SpecScene(degrees), incline_(kit::radians(static_cast<float>(degrees))) {
    add(incline_.slab(0.8f));
    BodySpec s = kit::sphere(incline_.at(20.0f, kRadius), kRadius, 0.8f);
    add(s);
    start_ = incline_.up_slope(s.position);
  }
  std::string_view name() const override { return "roll"; }
  Tick ticks() const override { return 120; }
  void after_step(Tick, const Engine& engine) override {
    travel_m_ = start_ - incline_.up_slope(engine.position(handles_[1]));
  }
  std::vector<Metric> metrics() const override {
    const double t = static_cast<double>(ticks()) * kTick;
    const double a = 5.0 / 7.0 * kG * std::sin(incline_.angle);
    return {kit::at_most("travel_error_pct", "%", kit::error_pct(travel_m_, 0.5 * a * t * t), 3.0,
                         "distance rolled in 2 s within 3% of 5/7 g sin(angle) t^2 / 2")};
  }

 private:
  static constexpr float kRadius = 0.5f;
  Incline incline_;
  float start_ = 0.0f;
  double travel_m_ = 0.0;
};

/// A box spinning at `rate` rad/s about its intermediate axis with a small
/// perturbation, in zero gravity (the Dzhanibekov effect): the axis must flip
/// over, and angular momentum and kinetic energy must be conserved over 10 s.
class FreeSpinScene final : public kit::SpecScene {
 public:
  explicit FreeSpinScene(int rate) : SpecScene(rate) {
    BodySpec b = kit::box({0.0f, 0.0f, 0.0f}, kHalf);
    b.angular_velocity = {0.01f * static_cast<float>(rate), static_cast<float>(rate),
                          0.01f * static_cast<float>(rate)};
    add(b);
    momentum0_ = momentum(b.rotation, b.angular_velocity);
    energy0_ = 0.5 * static_cast<double>(sim::dot(b.angular_velocity, momentum0_));
  }
  std::string_view name() const override { return "free_spin"; }
  WorldSpec world() const override {
    WorldSpec w;
    w.gravity = {};
    return w;
  }
  Tick ticks() const override { return 600; }
  void after_step(Tick, const Engine& engine) override {
    const Quat q = engine.rotation(handles_[0]);
    const Vec3 axis = sim::rotate(q, {0.0f, 1.0f, 0.0f});
    min_dot_ = std::min(min_dot_, static_cast<double>(axis.y));
    const Vec3 l = momentum(q, engine.angular_velocity(handles_[0]));
    const double drift =
        std::sqrt(sim::length_squared(l - momentum0_)) / std::sqrt(sim::length_squared(momentum0_));
    max_drift_ = std::max(max_drift_, drift);
    const double energy =
        0.5 * static_cast<double>(sim::dot(engine.angular_velocity(handles_[0]), l));
    max_energy_drift_ = std::max(max_energy_drift_, std::fabs(energy - energy0_) / energy0_);
  }
  std::vector<Metric> metrics() const override {
    return {kit::at_most("flip_min_dot", "", min_dot_, -0.5,
                         "the intermediate axis turns over (its dot with the start axis "
                         "falls below -0.5) within 10 s"),
            kit::at_most("momentum_drift_pct", "%", 100.0 * max_drift_, 1.0,
                         "angular momentum stays within 1% of its start value for 10 s"),
            kit::at_most("energy_drift_pct", "%", 100.0 * max_energy_drift_, 1.0,
                         "rotational kinetic energy stays within 1% of its start value for 10 s")};
  }

 private:
  // Half extents 0.1 x 0.4 x 0.7 m: y is the intermediate axis.
  static constexpr Vec3 kHalf{0.1f, 0.4f, 0.7f};
  // World angular momentum I_world w of the box (density 1000).
  static Vec3 momentum(Quat q, Vec3 w) {
    const float m = 1000.0f * 8.0f * kHalf.x * kHalf.y * kHalf.z;
    const float x2 = 4.0f * kHalf.x * kHalf.x;
    const float y2 = 4.0f * kHalf.y * kHalf.y;
    const float z2 = 4.0f * kHalf.z * kHalf.z;
    const Vec3 inertia{m / 12.0f * (y2 + z2), m / 12.0f * (x2 + z2), m / 12.0f * (x2 + y2)};
    const Vec3 local = sim::inv_rotate(q, w);
    return sim::rotate(q, sim::mul_elements(inertia, local));
  }
  Vec3 momentum0_;
  double energy0_ = 0.0;
  double max_energy_drift_ = 0.0;
  double min_dot_ = 1.0;
  double max_drift_ = 0.0;
};

}  // namespace

std::unique_ptr<Scene> make_free_fall(int seconds) {
  if (seconds < 1 || seconds > 10) return nullptr;
  return std::make_unique<FreeFallScene>(seconds);
}
std::unique_ptr<Scene> make_bounce(int percent) {
  if (percent < 1 || percent > 100) return nullptr;
  return std::make_unique<BounceScene>(percent);
}
std::unique_ptr<Scene> make_slide(int speed) {
  if (speed < 1 || speed > 30) return nullptr;
  return std::make_unique<SlideScene>(speed);
}
std::unique_ptr<Scene> make_incline_stick(int degrees) {
  if (degrees < 1 || degrees > 30) return nullptr;  // tan 31 deg > 0.6 slips
  return std::make_unique<InclineScene>(degrees, 0.6f, true);
}
std::unique_ptr<Scene> make_incline_slip(int degrees) {
  if (degrees < 17 || degrees > 60) return nullptr;  // tan 17 deg > 0.3
  return std::make_unique<InclineScene>(degrees, 0.3f, false);
}
std::unique_ptr<Scene> make_roll_stop(int tenths) {
  if (tenths < 1 || tenths > 10) return nullptr;
  return std::make_unique<RollStopScene>(tenths);
}
std::unique_ptr<Scene> make_hull_slip(int degrees) {
  if (degrees < 20 || degrees > 40) return nullptr;
  return std::make_unique<InclineScene>(degrees, 0.3f, false, true);
}
std::unique_ptr<Scene> make_roll(int degrees) {
  // Rolling without slipping needs mu >= 2/7 tan(angle); mu is 0.8.
  if (degrees < 1 || degrees > 60) return nullptr;
  return std::make_unique<RollScene>(degrees);
}
std::unique_ptr<Scene> make_free_spin(int rate) {
  if (rate < 1 || rate > 30) return nullptr;
  return std::make_unique<FreeSpinScene>(rate);
}

}  // namespace rwd::scenes
