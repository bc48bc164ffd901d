// SPDX-License-Identifier: MIT
// Point joints with an angular part (limited ball joints and hinges with
// motors) solved both in the solver's lanes and on the scalar path in one
// world: a hub holds more of them than there are colours, so the first
// ones (in slot order) are coloured into lane batches with their angular
// parts and the last stay scalar. Their limits hold on both paths, and
// the world restores and re-steps bit for bit. The lanes' atan2 is
// det_atan2 bit for bit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "d3/lane_atan2.h"
#include "joint_test_helpers.h"
#include "rewind/core/det_math.h"
#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using namespace joint_test;

constexpr float kDeg = kPi / 180.0f;
// More arms than the joints' colours (24, one taken by the hub's own
// joint to the world), so the hub's last arms find no colour.
constexpr int kArms = 30;

struct Hub {
  World3D world;
  BodyId hub;
  std::vector<BodyId> arms;
  std::vector<JointId> joints;  // arm k's joint: a hinge when k is even
  std::vector<JointDef> defs;
  JointDef hinge_def;
  JointDef ball_def;

  Hub() {
    hub = test::add_sphere(world, {0.0f, 10.0f, 0.0f}, 0.5f);
    make(world, joint_at(world, JointType::kBall, {}, hub, {0.0f, 10.5f, 0.0f}));
    for (int k = 0; k < kArms; ++k) {
      const float angle = 2.0f * kPi * static_cast<float>(k) / kArms;
      const Vec3 out{det_cos(angle), 0.0f, det_sin(angle)};
      const Vec3 tangent{-out.z, 0.0f, out.x};
      const Vec3 anchor = Vec3{0.0f, 10.0f, 0.0f} + out * 0.55f;
      // A capsule along `out` (its own axis is y): a quarter turn about
      // the tangent.
      const float h = std::sqrt(0.5f);
      const Quat turn{tangent.x * h, tangent.y * h, tangent.z * h, h};
      const BodyId arm = add_capsule(world, anchor + out * 0.25f, 0.03f, 0.2f, turn);
      arms.push_back(arm);
      JointDef def;
      if (k % 2 == 0) {
        def = joint_at(world, JointType::kHinge, hub, arm, anchor, tangent);
        def.enable_limit = true;
        def.lower = -30.0f * kDeg;
        def.upper = 25.0f * kDeg;
        def.enable_motor = true;
        def.motor_speed = 0.5f;
        def.max_motor_torque = 0.05f;
        hinge_def = def;
      } else {
        def = joint_at(world, JointType::kBall, hub, arm, anchor, out);
        def.enable_limit = true;
        def.cone_angle = 30.0f * kDeg;
        def.twist_lower = -20.0f * kDeg;
        def.twist_upper = 20.0f * kDeg;
        def.enable_motor = true;
        def.max_motor_torque = 0.05f;
        ball_def = def;
      }
      joints.push_back(make(world, def));
      defs.push_back(def);
      // Kicked about the hinge axis (either way) or twisted and swung.
      const float sign = (k / 2) % 2 == 0 ? 1.0f : -1.0f;
      const Vec3 w = k % 2 == 0 ? tangent * (8.0f * sign) : out * (12.0f * sign) + tangent * 4.0f;
      EXPECT_TRUE(world.set_angular_velocity(arm, w).ok());
    }
    // A second joint between the hub and its first arm closes a loop, so
    // the arms are solved joint by joint (as point joints), not as a tree.
    const Vec3 first = Vec3{0.0f, 10.0f, 0.0f} + Vec3{1.0f, 0.0f, 0.0f} * 0.55f;
    make(world, joint_at(world, JointType::kBall, hub, arms[0], first));
  }
};

// How far any arm went past its limits (rad; <= 0 within them).
struct Watch {
  float hinge = -10.0f;
  float cone = -10.0f;
  float twist = -10.0f;
  void watch(const Hub& h) {
    for (int k = 0; k < kArms; ++k) {
      const JointId j = h.joints[static_cast<size_t>(k)];
      const float a = h.world.joint_position(j);
      if (k % 2 == 0) {
        hinge = std::max({hinge, h.hinge_def.lower - a, a - h.hinge_def.upper});
      } else {
        cone = std::max(cone, h.world.joint_swing(j) - h.ball_def.cone_angle);
        twist = std::max({twist, h.ball_def.twist_lower - a, a - h.ball_def.twist_upper});
      }
    }
  }
};

TEST(JointAngularBatches, LimitsHoldInLanesAndScalarAndTheWorldReStepsBitForBit) {
  Hub h;
  Watch w;
  std::vector<uint64_t> reference;
  WorldState at_40;
  for (int i = 0; i < 240; ++i) {
    if (i == 40) h.world.save(at_40);
    h.world.step();
    reference.push_back(h.world.checksum());
    w.watch(h);
  }
  std::printf("[ measured ] past the limits: hinge %.3f deg, cone %.3f deg, twist %.3f deg\n",
              w.hinge / kDeg, w.cone / kDeg, w.twist / kDeg);
  EXPECT_LT(w.hinge, 1.0f * kDeg);
  EXPECT_LT(w.cone, 1.0f * kDeg);
  EXPECT_LT(w.twist, 1.0f * kDeg);
  // The arms reached their limits (the kicks and gravity carry them there).
  EXPECT_GT(w.hinge, -1.0f * kDeg);
  EXPECT_GT(w.cone, -1.0f * kDeg);
  // Every joint still holds its point.
  for (int k = 0; k < kArms; ++k) {
    const JointDef& d = h.defs[static_cast<size_t>(k)];
    EXPECT_LT(anchor_gap(h.world, d.body_a, d.anchor_a, d.body_b, d.anchor_b), 0.01f) << k;
  }
  h.world.restore(at_40);
  for (int i = 40; i < 240; ++i) {
    h.world.step();
    ASSERT_EQ(h.world.checksum(), reference[static_cast<size_t>(i)]) << "tick " << i;
  }
  // A second world built the same way gives the same bits.
  Hub twin;
  for (int i = 0; i < 240; ++i) {
    twin.world.step();
    ASSERT_EQ(twin.world.checksum(), reference[static_cast<size_t>(i)]) << "tick " << i;
  }
}

uint32_t bits(float f) {
  uint32_t u = 0;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

TEST(JointAngularBatches, LaneAtan2IsDetAtan2BitForBit) {
  // Zeros of both signs, the axes, equal magnitudes, tan(pi/8) on either
  // side of the series' shift, tiny, subnormal and huge values, and
  // random pairs of every sign and scale.
  const float special[] = {0.0f,   -0.0f,   1.0f,        -1.0f,   0.41421354f, 0.41421357f,
                           1e-30f, -1e-30f, 1e-40f,      -1e-40f, 3e38f,       -3e38f,
                           0.5f,   2.0f,    0.70710677f, 1e-6f,   -1e-6f,      123.0f};
  std::vector<float> ys;
  std::vector<float> xs;
  for (const float y : special) {
    for (const float x : special) {
      ys.push_back(y);
      xs.push_back(x);
    }
  }
  test::Rng rng;
  for (int i = 0; i < 20000; ++i) {
    const float scale = i % 3 == 0 ? 1e-4f : (i % 3 == 1 ? 1.0f : 1e4f);
    ys.push_back(rng.uniform(-1.0f, 1.0f) * scale);
    xs.push_back(rng.uniform(-1.0f, 1.0f) * (i % 5 == 0 ? scale * 1e-3f : scale));
  }
  while (ys.size() % d3::kLanes != 0) {
    ys.push_back(1.0f);
    xs.push_back(1.0f);
  }
  int differ = 0;
  for (size_t i = 0; i < ys.size(); i += d3::kLanes) {
    alignas(16) float out[d3::kLanes];
    d3::store(out, d3::det_atan2_lanes(d3::load(&ys[i]), d3::load(&xs[i])));
    for (int k = 0; k < d3::kLanes; ++k) {
      const float want = det_atan2(ys[i + k], xs[i + k]);
      if (bits(out[k]) != bits(want)) {
        if (++differ < 10) {
          ADD_FAILURE() << "atan2(" << ys[i + k] << ", " << xs[i + k] << "): lanes " << out[k]
                        << ", det_atan2 " << want;
        }
      }
    }
  }
  EXPECT_EQ(differ, 0);
}

}  // namespace
}  // namespace rwd::sim
