// SPDX-License-Identifier: MIT
// The free spin scene's box (half extents 0.1 x 0.4 x 0.7 m, density 1000,
// spun at 10 rad/s about its intermediate axis y with 0.1 rad/s about x and
// z, no gravity, no damping) over 30 s at the default world settings (60 Hz,
// 4 substeps), against a reference integration of Euler's equations (RK4 in
// double: 1.8231 s between flips, 17 flips in 30 s; the closed form agrees).
// The scene catalogue's criterion only asks for a first flip within 10 s;
// this asks every flip to keep time. The orbit passes within a 1.7e-5 part
// of |L|^2 of the separatrix, and a flip's period goes with the logarithm
// of that distance, so a gyroscopic term that lets |L| and the energy
// wander by their float rounding each tick makes the flips come ever
// faster.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

constexpr int kTicksPerSecond = 60;
constexpr double kSeconds = 30.0;
constexpr Vec3 kHalf{0.1f, 0.4f, 0.7f};

void report(const std::string& what, double value, const char* unit) {
  std::cout << "[ measured ] " << what << " = " << value << " " << unit << "\n";
  ::testing::Test::RecordProperty(what, std::to_string(value));
}

// Principal moments of the box, kg m^2.
std::array<double, 3> box_inertia() {
  const double x = 2.0 * kHalf.x;
  const double y = 2.0 * kHalf.y;
  const double z = 2.0 * kHalf.z;
  const double m = 1000.0 * x * y * z;
  return {m / 12.0 * (y * y + z * z), m / 12.0 * (x * x + z * z), m / 12.0 * (x * x + y * y)};
}

// Times at which the box's y axis is perpendicular to the world y axis
// (each flip passes one), linearly interpolated between samples.
struct Crossings {
  std::vector<double> times;
  double last_time = 0.0;
  double last_value = 1.0;
  void observe(double time, double value) {
    if ((last_value > 0.0) != (value > 0.0)) {
      times.push_back(last_time + (time - last_time) * last_value / (last_value - value));
    }
    last_time = time;
    last_value = value;
  }
};

// The reference: Euler's equations for the body-frame momentum and the
// orientation quaternion, classical RK4 in double at 1e-4 s (halving the
// step moves no crossing by 1e-6 s).
Crossings reference(Vec3 w0, double seconds) {
  const std::array<double, 3> inertia = box_inertia();
  // l (body frame), then q = (x, y, z, w).
  using State = std::array<double, 7>;
  State s{inertia[0] * w0.x, inertia[1] * w0.y, inertia[2] * w0.z, 0.0, 0.0, 0.0, 1.0};
  auto rate = [&](const State& y) {
    const double wx = y[0] / inertia[0];
    const double wy = y[1] / inertia[1];
    const double wz = y[2] / inertia[2];
    State d;
    d[0] = y[1] * wz - y[2] * wy;  // dl/dt = l x w
    d[1] = y[2] * wx - y[0] * wz;
    d[2] = y[0] * wy - y[1] * wx;
    d[3] = 0.5 * (y[6] * wx + y[4] * wz - y[5] * wy);  // dq/dt = q (w, 0) / 2
    d[4] = 0.5 * (y[6] * wy + y[5] * wx - y[3] * wz);
    d[5] = 0.5 * (y[6] * wz + y[3] * wy - y[4] * wx);
    d[6] = -0.5 * (y[3] * wx + y[4] * wy + y[5] * wz);
    return d;
  };
  auto axis_y = [](const State& y) { return 1.0 - 2.0 * (y[3] * y[3] + y[5] * y[5]); };
  const double dt = 1e-4;
  const long steps = std::lround(seconds / dt);
  Crossings c;
  c.last_value = axis_y(s);
  for (long i = 1; i <= steps; ++i) {
    const State k1 = rate(s);
    State t;
    for (int j = 0; j < 7; ++j) t[j] = s[j] + 0.5 * dt * k1[j];
    const State k2 = rate(t);
    for (int j = 0; j < 7; ++j) t[j] = s[j] + 0.5 * dt * k2[j];
    const State k3 = rate(t);
    for (int j = 0; j < 7; ++j) t[j] = s[j] + dt * k3[j];
    const State k4 = rate(t);
    for (int j = 0; j < 7; ++j) s[j] += dt / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
    c.observe(static_cast<double>(i) * dt, axis_y(s));
  }
  return c;
}

// The same from the closed form (Landau & Lifshitz, Mechanics, section 37):
// with moments I1 < I2 < I3 and |L|^2 > 2E I2 the momentum goes round the
// I3 axis with period 4 K(k) sqrt(I1 I2 I3 / ((I3 - I2)(|L|^2 - 2E I1))),
// k^2 = (I2 - I1)(2E I3 - |L|^2) / ((I3 - I2)(|L|^2 - 2E I1)), and the
// middle axis turns over twice per period. K by the arithmetic-geometric
// mean.
double analytic_flip_interval(Vec3 w0) {
  const std::array<double, 3> inertia = box_inertia();
  const double i1 = inertia[2];
  const double i2 = inertia[1];
  const double i3 = inertia[0];
  const double l_sq = i3 * i3 * w0.x * w0.x + i2 * i2 * w0.y * w0.y + i1 * i1 * w0.z * w0.z;
  const double two_e = i3 * w0.x * w0.x + i2 * w0.y * w0.y + i1 * w0.z * w0.z;
  const double k_sq = (i2 - i1) * (two_e * i3 - l_sq) / ((i3 - i2) * (l_sq - two_e * i1));
  double a = 1.0;
  double b = std::sqrt(1.0 - k_sq);
  for (int i = 0; i < 40 && a - b > 1e-15 * a; ++i) {
    const double mean = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = mean;
  }
  const double k = 3.14159265358979323846 / (2.0 * a);
  return 2.0 * k * std::sqrt(i1 * i2 * i3 / ((i3 - i2) * (l_sq - two_e * i1)));
}

// Body-frame momentum of the engine's box from its world state, in double.
std::array<double, 3> body_momentum(Quat q, Vec3 w) {
  const Vec3 local = inv_rotate(q, w);
  const std::array<double, 3> inertia = box_inertia();
  return {inertia[0] * local.x, inertia[1] * local.y, inertia[2] * local.z};
}

TEST(AccuracyFreeSpin, EveryFlipKeepsTheReferencePeriodFor30Seconds) {
  WorldConfig config;
  config.gravity = {};
  World3D world(config);
  BodyDef def;
  def.shape = Shape::make_box(kHalf);
  def.angular_velocity = {0.1f, 10.0f, 0.1f};
  def.angular_damping = 0.0f;
  auto id = world.create_body(def);
  ASSERT_TRUE(id.ok()) << id.status().message();
  const Vec3 w0 = world.angular_velocity(*id);  // as quantized on entry

  const std::array<double, 3> inertia = box_inertia();
  const double mid = inertia[1];
  // |L|^2, 2E and the distance from the separatrix |L|^2 - 2E I_mid, in
  // double from the engine's float state (the world momentum is the
  // body-frame one turned by q, so its length is the body-frame one's).
  auto invariants = [&](Quat q, Vec3 w) {
    const std::array<double, 3> l = body_momentum(q, w);
    double l_sq = 0.0;
    double two_e = 0.0;
    for (int i = 0; i < 3; ++i) {
      l_sq += l[i] * l[i];
      two_e += l[i] * l[i] / inertia[i];
    }
    // The separatrix distance without the middle axis's term, which
    // cancels exactly.
    const double gap = (inertia[0] - mid) / inertia[0] * l[0] * l[0] +
                       (inertia[2] - mid) / inertia[2] * l[2] * l[2];
    return std::array<double, 3>{l_sq, two_e, gap};
  };
  const std::array<double, 3> start = invariants(world.rotation(*id), w0);
  double momentum_drift = 0.0;
  double energy_drift = 0.0;
  double gap_drift = 0.0;
  Crossings flips;
  const int ticks = static_cast<int>(kSeconds + 2.0) * kTicksPerSecond;
  for (int t = 1; t <= ticks; ++t) {
    world.step();
    const Quat q = world.rotation(*id);
    flips.observe(static_cast<double>(t) / kTicksPerSecond, rotate(q, {0.0f, 1.0f, 0.0f}).y);
    if (t > static_cast<int>(kSeconds) * kTicksPerSecond) continue;
    const std::array<double, 3> now = invariants(q, world.angular_velocity(*id));
    momentum_drift = std::max(momentum_drift, std::fabs(std::sqrt(now[0] / start[0]) - 1.0));
    energy_drift = std::max(energy_drift, std::fabs(now[1] / start[1] - 1.0));
    gap_drift = std::max(gap_drift, std::fabs(now[2] / start[2] - 1.0));
  }

  // The flips of the reference's 30 s. The engine runs 2 s longer so that a
  // last flip a little late still counts against its reference.
  const Crossings ref = reference(w0, kSeconds);
  ASSERT_GE(ref.times.size(), 3u);
  const double ref_period =
      (ref.times.back() - ref.times.front()) / static_cast<double>(ref.times.size() - 1);
  report("reference_flip_interval_s", ref_period, "s");
  const double analytic = analytic_flip_interval(w0);
  report("analytic_flip_interval_s", analytic, "s");
  EXPECT_NEAR(ref_period, analytic, 1e-3 * analytic) << "the reference against the closed form";
  report("reference_first_flip_s", ref.times.front(), "s");
  report("reference_flips", static_cast<double>(ref.times.size()), "");
  const size_t in_window = static_cast<size_t>(std::count_if(
      flips.times.begin(), flips.times.end(), [](double t) { return t <= kSeconds; }));
  report("flips", static_cast<double>(in_window), "");
  ASSERT_GE(flips.times.size(), ref.times.size()) << "as many flips as the reference's";
  report("first_flip_s", flips.times.front(), "s");
  double worst = 0.0;
  double worst_time = 0.0;
  for (size_t i = 0; i < ref.times.size(); ++i) {
    worst_time = std::max(worst_time, std::fabs(flips.times[i] / ref.times[i] - 1.0));
    if (i == 0) continue;
    const double interval = flips.times[i] - flips.times[i - 1];
    std::cout << "[ measured ] flip interval " << i << " = " << interval << " s\n";
    worst = std::max(worst, std::fabs(interval / ref_period - 1.0));
  }
  report("worst_flip_interval_error_pct", 100.0 * worst, "%");
  report("worst_flip_time_error_pct", 100.0 * worst_time, "%");
  EXPECT_LE(worst, 0.02) << "every flip interval within 2% of the reference's";
  EXPECT_LE(worst_time, 0.02) << "every flip within 2% of the reference's time";
  report("momentum_drift_pct", 100.0 * momentum_drift, "%");
  report("energy_drift_pct", 100.0 * energy_drift, "%");
  report("separatrix_gap_drift_pct", 100.0 * gap_drift, "%");
  EXPECT_LE(momentum_drift, 1e-4) << "|L| within 0.01% for 30 s";
  EXPECT_LE(energy_drift, 2e-4) << "kinetic energy within 0.02% for 30 s";
  EXPECT_LE(gap_drift, 0.3) << "the orbit's distance from the separatrix within 30% for 30 s";
}

}  // namespace
}  // namespace rwd::sim
