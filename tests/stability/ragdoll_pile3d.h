// SPDX-License-Identifier: MIT
#pragma once
// The 3D ragdoll pile shared by the built stability suite
// (stability3d_ragdolls.cpp): fifty ragdolls (rewind/sim/ragdoll3d.h)
// lying in ten crossed layers of five, each turned a little and dropped
// from 0.4 to 4.5 m onto a floor, stepped for a number of ticks while the
// widest joint opening and the time every part is asleep are measured.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "rewind/core/det_math.h"
#include "rewind/sim/ragdoll3d.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim::pile {

inline constexpr int kTicksPerSecond = 60;

inline void report(const std::string& what, double value, const char* unit, const char* bound = "",
                   double limit = 0.0) {
  std::printf("[ measured ] %s = %g %s", what.c_str(), value, unit);
  if (*bound != '\0') std::printf(" (%s %g)", bound, limit);
  std::printf("\n");
  std::string key = what;
  for (char& c : key) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  ::testing::Test::RecordProperty(key, std::to_string(value));
}

inline Quat about(Vec3 axis, float angle) {
  const float s = det_sin(0.5f * angle);
  return {axis.x * s, axis.y * s, axis.z * s, det_cos(0.5f * angle)};
}

// The n-th pair of layer bits from bits 16..31: every ragdoll on its own
// pair, so no two ragdolls share their self_layer and all collide with
// each other, while each one's parts do not (ragdoll3d.h).
inline uint32_t layer_pair(uint32_t n) {
  for (uint32_t a = 16; a < 32; ++a) {
    for (uint32_t b = a + 1; b < 32; ++b) {
      if (n-- == 0) return (1u << a) | (1u << b);
    }
  }
  return 1u << 31;
}

/// What a run of the pile measured.
struct PileResult {
  double worst_gap = 0.0;  ///< m, the widest any joint opened
  int asleep_at = -1;      ///< tick every part was asleep, -1: not within the run
};

/// A ragdoll of the pile moved from where it is dropped: the pile is a
/// chaotic heap, so a solver that holds its joints only by luck shows it
/// under a nudge far below anything the criteria measure.
struct PileNudge {
  uint32_t ragdoll = 0xFFFFFFFFu;  ///< which of the 50 (none by default)
  Vec3 offset;                     ///< m
};

/// Builds the pile and steps it `run_ticks` ticks (stopping once all
/// sleep), printing what it measured.
inline PileResult run_pile(int run_ticks, const PileNudge& nudge = {}) {
  World3D world;
  BodyDef floor;
  floor.kind = BodyKind::kStatic;
  floor.shape = Shape::make_box({30.0f, 0.5f, 30.0f});
  floor.position = {0.0f, -0.5f, 0.0f};
  EXPECT_TRUE(world.create_body(floor).ok());

  std::vector<Ragdoll3D> ragdolls;
  const Quat lying = about({1.0f, 0.0f, 0.0f}, -0.5f * kPi);  // face up, head toward +z
  for (uint32_t i = 0; i < 50; ++i) {
    const uint32_t layer = i / 5;
    const uint32_t slot = i % 5;
    const float across = (static_cast<float>(slot) - 2.0f) * 0.6f;
    const float yaw =
        (layer % 2 == 0 ? 0.0f : 0.5f * kPi) + 0.25f * det_sin(1.7f * static_cast<float>(i) + 0.3f);
    RagdollSpec3D spec;
    spec.rotation = about({0.0f, 1.0f, 0.0f}, yaw) * lying;
    const float along = 0.3f * det_cos(2.3f * static_cast<float>(i));
    spec.position = layer % 2 == 0 ? Vec3{across, 0.4f + 0.45f * layer, along}
                                   : Vec3{along, 0.4f + 0.45f * layer, across};
    if (i == nudge.ragdoll) spec.position += nudge.offset;
    spec.self_layer = layer_pair(i);
    auto r = create_ragdoll(world, spec);
    EXPECT_TRUE(r.ok()) << r.status().message();
    if (!r.ok()) return {};
    ragdolls.push_back(*r);
  }

  double worst_gap = 0.0;
  int worst_tick = 0;
  std::string worst_joint;
  int asleep_at = -1;
  uint32_t awake_at_8s = 0;
  double speed_at_8s = 0.0;  // the fastest part then, m/s and rad/s
  double spin_at_8s = 0.0;
  double fastest = 0.0;
  for (int t = 0; t < run_ticks && asleep_at < 0; ++t) {
    world.step();
    uint32_t awake = 0;
    for (const Ragdoll3D& r : ragdolls) {
      for (uint32_t j = 0; j < kRagdollJointCount3D; ++j) {
        const auto joint = static_cast<RagdollJoint3D>(j);
        const double gap = ragdoll_joint_gap(world, r, joint);
        if (gap > worst_gap) {
          worst_gap = gap;
          worst_tick = t + 1;
          worst_joint = ragdoll_joint_name(joint);
        }
      }
      for (const BodyId id : r.parts) {
        awake += world.is_awake(id) ? 1u : 0u;
        if (t + 1 == 8 * kTicksPerSecond) {
          speed_at_8s =
              std::max(speed_at_8s, static_cast<double>(length(world.linear_velocity(id))));
          spin_at_8s =
              std::max(spin_at_8s, static_cast<double>(length(world.angular_velocity(id))));
        }
        fastest = std::max(fastest, static_cast<double>(length(world.linear_velocity(id))));
      }
    }
    if (t + 1 == 8 * kTicksPerSecond) awake_at_8s = awake;
    if (awake == 0) asleep_at = t + 1;
  }
  const double run_s = static_cast<double>(run_ticks) / kTicksPerSecond;
  // -1: not all asleep within the run.
  const double asleep_s = asleep_at < 0 ? -1.0 : static_cast<double>(asleep_at) / kTicksPerSecond;
  std::printf(
      "[ measured ] ragdoll pile: worst opening at tick %d (%.2f s), joint %s; %u of 550 parts "
      "awake at 8 s (fastest %.3f m/s, %.3f rad/s)%s %.0f s\n",
      worst_tick, static_cast<double>(worst_tick) / kTicksPerSecond, worst_joint.c_str(),
      awake_at_8s, speed_at_8s, spin_at_8s,
      asleep_at < 0 ? "; not all asleep after" : "; all asleep within", run_s);
  report("ragdolls3d worst_gap_m", worst_gap, "m", "<=", 0.02);
  report("ragdolls3d all_asleep_s", asleep_s, "s", "<=", 8.0);
  report("ragdolls3d fastest_mps", fastest, "m/s");
  return {worst_gap, asleep_at};
}

}  // namespace rwd::sim::pile
