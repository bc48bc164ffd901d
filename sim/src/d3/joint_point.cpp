// SPDX-License-Identifier: MIT
// Point joints (joint_solver.h): a ball joint with nothing but its point,
// solved on its own, is the three linear rows of the general block with
// the world axes as directions. Their K is the point mass matrix, so the
// block's factorization, gathers and scatters reduce to one symmetric
// 3 x 3 inverse per refresh and a matrix-vector product per pass. The
// stages and their semantics are the block's: rows (lever arms) from the
// last refresh, the bias from where the anchors stand now, the soft step
// while solving and rigid rows while relaxing, a clamped projection.
#include "d3/joint_solver.h"
#include "d3/joint_types.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {

bool is_point_joint(const JointRecord& j, const JointConstraint& c) {
  // A hinge on its own: its turns are its angular part, whatever it drives.
  if (j.type == JointType::kHinge) return c.tree == kNoTree;
  // (A loaded state may hold a motor or spring impulse a ball joint no
  // longer drives; the general path keeps warm-starting it, so such a
  // joint stays there.)
  return j.type == JointType::kBall &&
         ((j.flags & (kJointLimit | kJointSpring | kJointMotor)) == 0 || has_angular_part(j)) &&
         c.tree == kNoTree && c.block.size() == 3 &&
         ((j.flags & kJointMotor) != 0 || j.motor_impulse == Vec3{}) && j.spring_impulse == Vec3{};
}

void refresh_point(JointConstraint& c, const SolverBody& a, const SolverBody& b) {
  c.point_ra = rotate(a.delta_rotation, c.anchor_a);
  c.point_rb = rotate(b.delta_rotation, c.anchor_b);
  c.point_inv_mass = inverse_symmetric(point_mass_matrix(a.inv_mass, a.inv_inertia, c.point_ra,
                                                         b.inv_mass, b.inv_inertia, c.point_rb));
}

void warm_start_point(const JointConstraint& c, SolverBody& a, SolverBody& b) {
  apply_linear(a, b, c.point_ra, c.point_rb, c.linear_impulse);
}

void solve_point(JointConstraint& c, SolverBody& a, SolverBody& b, bool use_bias) {
  Vec3 rhs = anchor_velocity(a, b, c.point_ra, c.point_rb);
  Vec3 impulse;
  if (use_bias) {
    // The anchors' gap where the bodies stand: they have not moved since
    // the refresh (the solve comes before the substep's move), so the
    // refreshed lever arms are where the anchors are.
    const Vec3 d =
        (b.delta_position - a.delta_position) + c.delta_center + (c.point_rb - c.point_ra);
    rhs += d * c.soft.bias_rate;
    impulse =
        -(c.point_inv_mass * rhs) * c.soft.mass_scale - c.linear_impulse * c.soft.impulse_scale;
  } else {
    impulse = -(c.point_inv_mass * rhs);
  }
  c.linear_impulse += impulse;
  apply_linear(a, b, c.point_ra, c.point_rb, impulse);
}

void project_point(const JointConstraint& c, SolverBody& a, SolverBody& b) {
  const JointFrames f = joint_frames(c, a, b);
  const Vec3 error{clamp_projection(f.d.x), clamp_projection(f.d.y), clamp_projection(f.d.z)};
  const Vec3 x = -(c.point_inv_mass * error);
  if (a.inv_mass > 0.0f) {
    a.delta_position -= x * a.inv_mass;
    a.delta_rotation =
        integrate_rotation(a.delta_rotation, -(a.inv_inertia * cross(c.point_ra, x)), 1.0f);
  }
  if (b.inv_mass > 0.0f) {
    b.delta_position += x * b.inv_mass;
    b.delta_rotation =
        integrate_rotation(b.delta_rotation, b.inv_inertia * cross(c.point_rb, x), 1.0f);
  }
}

}  // namespace rwd::sim::d3
