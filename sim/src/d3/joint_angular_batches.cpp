// SPDX-License-Identifier: MIT
// The batched angular parts' packing and write-back
// (joint_angular_batches.h); their passes are in joint_angular_lanes.h.
#include "d3/joint_angular_batches.h"

#include "d3/joint_solver.h"
#include "d3/joint_types.h"

namespace rwd::sim::d3 {
namespace {

void put_quat(float (&dst)[4][kLanes], int lane, Quat q) {
  dst[0][lane] = q.x;
  dst[1][lane] = q.y;
  dst[2][lane] = q.z;
  dst[3][lane] = q.w;
}

void put3(float (&dst)[3][kLanes], int lane, Vec3 v) {
  dst[0][lane] = v.x;
  dst[1][lane] = v.y;
  dst[2][lane] = v.z;
}

Vec3 get3(const float (&src)[3][kLanes], int lane) {
  return {src[0][lane], src[1][lane], src[2][lane]};
}

float flag(const JointRecord& j, uint32_t bit) {
  return (j.flags & bit) != 0 ? 1.0f : 0.0f;
}

}  // namespace

void pack_ball_lane(BallPartBatch& p, int lane, const JointRecord& j, const JointConstraint& c) {
  put_quat(p.frame_a, lane, c.frame_a);
  put_quat(p.frame_b, lane, c.frame_b);
  p.limit_on[lane] = flag(j, kJointLimit);
  p.motor_on[lane] = flag(j, kJointMotor);
  p.cone_angle[lane] = j.cone_angle;
  p.twist_lower[lane] = j.twist_lower;
  p.twist_upper[lane] = j.twist_upper;
  put3(p.motor_velocity, lane, j.motor_velocity);
  p.max_motor[lane] = j.max_motor * c.h;
  put3(p.motor_impulse, lane, c.motor_impulse);
  p.limit_impulse[0][lane] = c.cone_impulse;
  p.limit_impulse[1][lane] = c.lower_impulse;
  p.limit_impulse[2][lane] = c.upper_impulse;
  p.any_motor = p.any_motor || (j.flags & kJointMotor) != 0;
  p.any_limit = p.any_limit || (j.flags & kJointLimit) != 0;
}

void clear_ball_lane(BallPartBatch& p, int lane) {
  put_quat(p.frame_a, lane, Quat{});
  put_quat(p.frame_b, lane, Quat{});
  p.limit_on[lane] = p.motor_on[lane] = 0.0f;
  p.cone_angle[lane] = p.twist_lower[lane] = p.twist_upper[lane] = 0.0f;
  put3(p.motor_velocity, lane, Vec3{});
  p.max_motor[lane] = 0.0f;
  put3(p.motor_impulse, lane, Vec3{});
  put3(p.limit_impulse, lane, Vec3{});
}

void pack_hinge_lane(HingePartBatch& p, int lane, const JointRecord& j, const JointConstraint& c) {
  put_quat(p.frame_a, lane, c.frame_a);
  put_quat(p.frame_b, lane, c.frame_b);
  p.limit_on[lane] = flag(j, kJointLimit);
  p.motor_on[lane] = flag(j, kJointMotor);
  p.spring_on[lane] = flag(j, kJointSpring);
  p.spring_soft[0][lane] = c.spring_soft.bias_rate;
  p.spring_soft[1][lane] = c.spring_soft.mass_scale;
  p.spring_soft[2][lane] = c.spring_soft.impulse_scale;
  p.spring_target[lane] = j.spring_target;
  p.motor_speed[lane] = j.motor_speed;
  p.max_motor[lane] = j.max_motor * c.h;
  p.lower[lane] = j.lower;
  p.upper[lane] = j.upper;
  p.spring_impulse[lane] = c.spring_impulse.x;
  p.motor_impulse[lane] = c.motor_impulse.x;
  p.limit_impulse[0][lane] = c.lower_impulse;
  p.limit_impulse[1][lane] = c.upper_impulse;
  put3(p.angular_impulse, lane, c.angular_impulse);
  put3(p.tick_angular, lane, Vec3{});
}

void clear_hinge_lane(HingePartBatch& p, int lane) {
  put_quat(p.frame_a, lane, Quat{});
  put_quat(p.frame_b, lane, Quat{});
  p.limit_on[lane] = p.motor_on[lane] = p.spring_on[lane] = 0.0f;
  p.spring_soft[0][lane] = 0.0f;
  p.spring_soft[1][lane] = 1.0f;
  p.spring_soft[2][lane] = 0.0f;
  p.spring_target[lane] = p.motor_speed[lane] = p.max_motor[lane] = 0.0f;
  p.lower[lane] = p.upper[lane] = 0.0f;
  p.spring_impulse[lane] = p.motor_impulse[lane] = 0.0f;
  p.limit_impulse[0][lane] = p.limit_impulse[1][lane] = 0.0f;
  put3(p.angular_impulse, lane, Vec3{});
  put3(p.tick_angular, lane, Vec3{});
}

void store_ball_lane(const BallPartBatch& p, int lane, JointConstraint& c) {
  c.motor_impulse = get3(p.motor_impulse, lane);
  c.cone_impulse = p.limit_impulse[0][lane];
  c.lower_impulse = p.limit_impulse[1][lane];
  c.upper_impulse = p.limit_impulse[2][lane];
}

void store_hinge_lane(const HingePartBatch& p, int lane, JointConstraint& c) {
  c.spring_impulse.x = p.spring_impulse[lane];
  c.motor_impulse.x = p.motor_impulse[lane];
  c.lower_impulse = p.limit_impulse[0][lane];
  c.upper_impulse = p.limit_impulse[1][lane];
  c.angular_impulse = get3(p.angular_impulse, lane);
  c.tick_angular = get3(p.tick_angular, lane);
}

void sum_hinge_part(HingePartBatch& p) {
  for (int d = 0; d < 3; ++d) {
    for (int i = 0; i < kLanes; ++i) {
      const float v = p.align_axis[0][d][i] * p.align_impulse[0][i] +
                      p.align_axis[1][d][i] * p.align_impulse[1][i];
      p.angular_impulse[d][i] = v;
      p.tick_angular[d][i] += v;
    }
  }
}

}  // namespace rwd::sim::d3
