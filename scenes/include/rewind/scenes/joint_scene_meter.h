// SPDX-License-Identifier: MIT
#pragma once
// Measuring a jointed scene (joint_scenes.h) from the poses an engine
// reports: how far a joint's anchors are apart, the scene's energy, and the
// figures of a whole run. Header only.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "rewind/scenes/joint_scenes.h"

namespace rwd::scenes {

// --- measuring ------------------------------------------------------------

/// The world point of a joint's anchor on side a (the fixed point when a
/// is the world) and on side b.
inline sim::Vec3 anchor_world(const std::vector<JointBodyState>& states, int body,
                              sim::Vec3 local) {
  if (body < 0) return local;
  const JointBodyState& s = states[static_cast<size_t>(body)];
  return s.position + sim::rotate(s.rotation, local);
}

/// How far apart a joint's two anchors are, m (0 for a joint that holds).
inline double joint_opening(const JointScene& scene, const std::vector<JointBodyState>& states,
                            int joint) {
  const JointSceneJoint& j = scene.joints[static_cast<size_t>(joint)];
  return sim::length(anchor_world(states, j.b, j.local_b) - anchor_world(states, j.a, j.local_a));
}

/// Kinetic plus potential energy of the dynamic bodies, J (potential from
/// y = 0).
inline double joint_scene_energy(const JointScene& scene,
                                 const std::vector<JointBodyState>& states) {
  double e = 0.0;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const JointSceneBody& b = scene.bodies[i];
    if (b.fixed) continue;
    const JointBodyState& s = states[i];
    const double m = b.mass_kg();
    const sim::Vec3 v = s.linear_velocity;
    const sim::Vec3 w = sim::inv_rotate(s.rotation, s.angular_velocity);
    const sim::Vec3 in = b.inertia();
    e += 0.5 * m * (double{v.x} * v.x + double{v.y} * v.y + double{v.z} * v.z);
    e += 0.5 * (double{in.x} * w.x * w.x + double{in.y} * w.y * w.y + double{in.z} * w.z * w.z);
    e -= m * (double{scene.gravity.x} * s.position.x + double{scene.gravity.y} * s.position.y +
              double{scene.gravity.z} * s.position.z);
  }
  return e;
}

/// The figures of one run, from the states after every tick (and the
/// starting ones, tick 0).
class JointSceneMeter {
 public:
  explicit JointSceneMeter(const JointScene& scene) : scene_(scene) {}

  /// Call with the starting states, then after every tick.
  void observe(const std::vector<JointBodyState>& states, double time_s) {
    double opening = 0.0;
    for (size_t j = 0; j < scene_.joints.size(); ++j) {
      opening = std::max(opening, joint_opening(scene_, states, static_cast<int>(j)));
    }
    final_opening_m = opening;
    max_opening_m = std::max(max_opening_m, opening);
    if (scene_.heavy >= 0) {
      const JointSceneJoint& first = scene_.joints[static_cast<size_t>(scene_.first_joint)];
      const JointSceneJoint& last = scene_.joints[static_cast<size_t>(scene_.last_joint)];
      const double reach = sim::length(anchor_world(states, last.b, last.local_b) -
                                       anchor_world(states, first.a, first.local_a));
      final_stretch_pct = 100.0 * (reach - scene_.chain_length_m) / scene_.chain_length_m;
      max_stretch_pct = std::max(max_stretch_pct, final_stretch_pct);
    }
    if (scene_.rod >= 0) {
      const JointBodyState& r = states[static_cast<size_t>(scene_.rod)];
      const sim::Vec3 down = sim::rotate(r.rotation, {0.0f, -1.0f, 0.0f});
      const double angle = std::atan2(static_cast<double>(down.x), -static_cast<double>(down.y));
      if (seen_ && (angle > 0.0) != (last_angle_ > 0.0)) {
        crossings_.push_back(last_time_ +
                             (time_s - last_time_) * last_angle_ / (last_angle_ - angle));
      }
      last_angle_ = angle;
      last_time_ = time_s;
    }
    const double e = joint_scene_energy(scene_, states);
    if (!seen_) {
      start_energy_j = e;
      lowest_energy_j_ = e;
      max_energy_j = e;
    }
    lowest_energy_j_ = std::min(lowest_energy_j_, e);
    energy_rebound_j = std::max(energy_rebound_j, e - lowest_energy_j_);
    max_energy_j = std::max(max_energy_j, e);
    final_energy_j = e;
    if (!scene_.loads.empty()) {
      double lowest_plank = 1e30, half_span = 0.0;
      for (int p : scene_.planks) {
        lowest_plank = std::min(lowest_plank, double{states[static_cast<size_t>(p)].position.y});
        half_span =
            std::max(half_span, std::fabs(double{states[static_cast<size_t>(p)].position.x}) + 0.5);
      }
      loads_carried = 0;
      for (int l : scene_.loads) {
        const sim::Vec3 p = states[static_cast<size_t>(l)].position;
        if (p.y >= lowest_plank - 0.1 && std::fabs(p.z) <= 0.4f && std::fabs(p.x) <= half_span) {
          ++loads_carried;
        }
      }
    }
    final_speed_mps = 0.0;
    for (size_t i = 0; i < scene_.bodies.size(); ++i) {
      if (scene_.bodies[i].fixed) continue;
      final_speed_mps =
          std::max(final_speed_mps, static_cast<double>(sim::length(states[i].linear_velocity)));
    }
    seen_ = true;
  }

  /// The pendulum's period from its zero crossings (first to last; two
  /// crossings a period), s; 0 before three crossings.
  double period_s() const {
    if (crossings_.size() < 3) return 0.0;
    return 2.0 * (crossings_.back() - crossings_.front()) /
           static_cast<double>(crossings_.size() - 1);
  }
  int crossings() const { return static_cast<int>(crossings_.size()); }
  double period_error_pct() const {
    if (scene_.analytic_period_s <= 0.0 || period_s() <= 0.0) return 0.0;
    return 100.0 * std::fabs(period_s() - scene_.analytic_period_s) / scene_.analytic_period_s;
  }
  /// How far the energy ever rose above its start, % of the scene's
  /// energy scale (0 when it never did).
  double energy_growth_pct() const {
    if (scene_.energy_scale_j <= 0.0) return 0.0;
    return 100.0 * (max_energy_j - start_energy_j) / scene_.energy_scale_j;
  }
  /// The largest rise of the energy above the lowest it had been before,
  /// % of the scale: energy the soft joints took into their stretch (a
  /// sheet snapping taut) and gave back shows here, as would energy a
  /// solver adds while the fall still releases more.
  double energy_rebound_pct() const {
    if (scene_.energy_scale_j <= 0.0) return 0.0;
    return 100.0 * energy_rebound_j / scene_.energy_scale_j;
  }

  double max_opening_m = 0.0;    ///< the widest joint opening at any tick
  double final_opening_m = 0.0;  ///< the widest at the last tick observed
  double max_stretch_pct = 0.0;  ///< chain: the longest it was, % over its length
  double final_stretch_pct = 0.0;
  double start_energy_j = 0.0;
  double max_energy_j = 0.0;      ///< see energy_growth_pct()
  double energy_rebound_j = 0.0;  ///< see energy_rebound_pct()
  double final_energy_j = 0.0;
  /// rope_bridge: the boxes on the deck at the last tick observed (above
  /// the lowest plank's centre less 0.1 m, within its width and span).
  int loads_carried = 0;
  double final_speed_mps = 0.0;  ///< fastest dynamic body at the last tick

 private:
  const JointScene& scene_;
  bool seen_ = false;
  double last_angle_ = 0.0;
  double last_time_ = 0.0;
  double lowest_energy_j_ = 0.0;
  std::vector<double> crossings_;
};

}  // namespace rwd::scenes
