// SPDX-License-Identifier: MIT
// The joint stages (joint_solver.h): which joints take part in a tick, the
// table of joint types, the passes over them in a fixed order, storing
// their impulses and breaking them.
#include "d3/joint_solver.h"

#include <cmath>

#include "d3/body_storage.h"
#include "d3/joint_types.h"
#include "d3/state_rules.h"
#include "d3/world_scratch.h"

namespace rwd::sim::d3 {
namespace {

// The structural rows are as soft as Box2D v3's joints: twice the contact
// stiffness, held to a quarter of the substep rate (stiffer stops being
// stable), and heavily damped so an error closes without ringing.
constexpr float kJointDampingRatio = 2.0f;

const JointOps* const kOps[kJointTypeCount] = {
    &kBallOps,       // kBall
    &kHingeOps,      // kHinge
    &kWeldOps,       // kWeld
    &kDistanceOps,   // kDistance
    &kPrismaticOps,  // kPrismatic
    &kDistanceOps,   // kSpring
    &kGrabOps,       // kGrab
};

}  // namespace

const JointOps& joint_ops(JointType type) {
  return *kOps[static_cast<uint8_t>(type)];
}

bool joint_acts(const WorldState& state, const JointRecord& j) {
  if (j.alive == 0 || (j.flags & kJointBroken) != 0) return false;
  if (!is_simulated(state.infos[j.index_b])) return false;
  return j.index_a == kJointWorld || is_simulated(state.infos[j.index_a]);
}

void prepare_joints(const WorldState& state, WorldScratch& scratch, float h) {
  std::vector<JointConstraint>& out = scratch.joint_constraints;
  if (state.live_joints == 0) {
    out.clear();
    return;
  }
  // The constraints of the last tick are reused in place rather than made
  // afresh (each is most of a kilobyte, and zeroing them was a tenth of a
  // large joint scene's step). The loop below sets the joint's own fields,
  // next() resets the tick's sums, the block and its rows' kinds, and the
  // stages after set the rest before reading it (the trees and batches
  // mark every joint; the block's factor, a tree's offsets and a point
  // joint's levers are written where they are made).
  size_t used = 0;
  auto next = [&]() -> JointConstraint& {
    if (used == out.size()) out.emplace_back();
    JointConstraint& c = out[used++];
    c.tick_linear = Vec3{};
    c.tick_angular = Vec3{};
    c.block.clear();
    c.orientation_ready = false;
    for (int i = 0; i < kMaxBlockRows; ++i) {
      c.row_kind[i] = kRowStructure;
      c.row_gap[i] = 0.0f;
    }
    return c;
  };
  const WorldConfig& config = state.config;
  float hertz = 2.0f * config.contact_hertz;
  if (hertz > 0.25f / h) hertz = 0.25f / h;
  const JointSoftness soft = joint_softness(hertz, kJointDampingRatio, h);
  for (uint32_t k = 0; k < state.joints.size(); ++k) {
    const JointRecord& j = state.joints[k];
    if (!joint_acts(state, j)) continue;
    const bool world = j.index_a == kJointWorld || j.type == JointType::kGrab;
    const uint32_t ia = world ? 0 : scratch.solver_index[j.index_a];
    const uint32_t ib = scratch.solver_index[j.index_b];
    // Neither side moves this tick (asleep, static or kinematic at rest
    // with a sleeping partner): nothing to solve.
    if (ia == 0 && ib == 0) continue;
    JointConstraint& c = next();
    c.record = k;
    c.body_a = ia;
    c.body_b = ib;
    c.h = h;
    Vec3 center_a{};
    if (j.type == JointType::kGrab) {
      c.rotation_a = Quat{};
      c.anchor_a = j.target;
    } else if (j.index_a == kJointWorld) {
      c.rotation_a = Quat{};
      c.anchor_a = j.local_anchor_a;
    } else {
      const BodySim& sa = state.sims[j.index_a];
      center_a = sa.position;
      c.rotation_a = sa.rotation;
      c.anchor_a = rotate(sa.rotation, j.local_anchor_a);
    }
    const BodySim& sb = state.sims[j.index_b];
    c.rotation_b = sb.rotation;
    c.anchor_b = rotate(sb.rotation, j.local_anchor_b);
    c.delta_center = sb.position - center_a;
    c.frame_a = c.rotation_a * j.frame_a;
    c.frame_b = c.rotation_b * j.frame_b;
    c.soft = soft;
    c.orients =
        j.type == JointType::kHinge || j.type == JointType::kWeld ||
        j.type == JointType::kPrismatic ||
        (j.type == JointType::kBall && (j.flags & (kJointLimit | kJointSpring | kJointMotor)) != 0);
    c.spring_soft =
        joint_softness(j.type == JointType::kWeld ? j.linear_hertz : j.hertz, j.damping_ratio, h);
    c.angular_soft = joint_softness(j.angular_hertz, j.damping_ratio, h);
    c.linear_impulse = j.linear_impulse;
    c.angular_impulse = j.angular_impulse;
    c.motor_impulse = j.motor_impulse;
    c.spring_impulse = j.spring_impulse;
    c.axial_impulse = j.axial_impulse;
    c.lower_impulse = j.lower_impulse;
    c.upper_impulse = j.upper_impulse;
    c.cone_impulse = j.cone_impulse;
    SolverBody& a = scratch.solver_bodies[ia];
    SolverBody& b = scratch.solver_bodies[ib];
    a.jointed = ia != 0;
    b.jointed = true;
    const JointOps& ops = joint_ops(j.type);
    if (ops.prepare != nullptr) ops.prepare(j, c);
    // The structure's rows as they stand at the tick's start (which
    // joints form trees depends only on their count).
    JointRow rows[kMaxBlockRows];
    const JointFrames f = start_frames(c);
    const int m = ops.rows != nullptr ? ops.rows(j, f, rows) : 0;
    for (int i = 0; i < m; ++i) c.block.add(rows[i]);
    LimitRow limits[kMaxLimitRows];
    const int l = m > 0 && ops.limits != nullptr ? ops.limits(j, f, limits) : 0;
    c.capacity = static_cast<uint8_t>(m + l < kMaxBlockRows ? m + l : kMaxBlockRows);
  }
  out.resize(used);
  build_joint_trees(scratch);
  scratch.joint_angular.clear();
  for (uint32_t k = 0; k < out.size(); ++k) {
    JointConstraint& c = out[k];
    const JointRecord& j = state.joints[c.record];
    c.point = is_point_joint(j, c);
    c.angular = c.point && has_angular_part(j);
    if (c.angular) scratch.joint_angular.push_back(k);
  }
  build_point_batches(state, scratch);
  scratch.joint_general.clear();
  for (uint32_t k = 0; k < out.size(); ++k) {
    if (!out[k].batched) scratch.joint_general.push_back(k);
  }
  // A batched joint's angular part is solved in its batch's lanes: the
  // scalar angular path keeps the rest.
  size_t kept = 0;
  for (const uint32_t k : scratch.joint_angular) {
    if (!out[k].batched) scratch.joint_angular[kept++] = k;
  }
  scratch.joint_angular.resize(kept);
}

void refresh_joint_rows(const WorldState& state, WorldScratch& scratch, bool trees_only) {
  JointRow rows[kMaxBlockRows];
  for (const uint32_t index : scratch.joint_general) {
    JointConstraint& c = scratch.joint_constraints[index];
    if (c.block.size() == 0 || (trees_only && c.tree == kNoTree)) continue;
    const JointRecord& j = state.joints[c.record];
    const SolverBody& a = scratch.solver_bodies[c.body_a];
    const SolverBody& b = scratch.solver_bodies[c.body_b];
    if (c.point) {
      refresh_point(c, a, b);
      continue;
    }
    const JointOps& ops = joint_ops(j.type);
    const JointFrames f = joint_frames(c, a, b);
    const int m = ops.rows(j, f, rows);
    c.block.clear();
    for (int i = 0; i < m; ++i) {
      c.block.add(rows[i]);
      c.row_kind[i] = kRowStructure;
    }
    // A limit already reached joins the structure (within the rows the
    // joint reserved): solved with it, and in a tree with the whole tree,
    // it holds the way the structure does, where a row against one
    // joint's block alone would be undone by the rest of the tree.
    c.frames = f;
    c.limit_count = 0;
    if (ops.limits != nullptr) {
      const LimitRow* limits = c.limits;
      const int n = ops.limits(j, f, c.limits);
      c.limit_count = static_cast<uint8_t>(n);
      for (int k = 0; k < n && c.block.size() < c.capacity; ++k) {
        if (limits[k].gap > 0.0f) continue;
        c.row_kind[c.block.size()] = limits[k].kind;
        c.row_gap[c.block.size()] = limits[k].gap;
        c.block.add(limits[k].row);
      }
    }
    c.block.factor(a, b);
    c.orientation_ready = false;
    for (KeptRow& kept : c.kept) kept.ready = false;
  }
  if (!trees_only) {
    refresh_angular_parts(state, scratch);
    refresh_point_batches(scratch);
    scratch.joint_frames_fresh = true;
  }
  factor_joint_trees(scratch);
}

void warm_start_joints(const WorldState& state, WorldScratch& scratch) {
  refresh_joint_rows(state, scratch);
  warm_start_angular_parts(state, scratch);
  warm_start_angular_batches(scratch);
  float acc[kMaxBlockRows];
  for (const uint32_t k : scratch.joint_general) {
    const JointConstraint& c = scratch.joint_constraints[k];
    const JointRecord& j = state.joints[c.record];
    SolverBody& a = scratch.solver_bodies[c.body_a];
    SolverBody& b = scratch.solver_bodies[c.body_b];
    // The structure along the same rows its passes read and apply.
    if (c.point) {
      warm_start_point(c, a, b);
    } else if (c.block.size() > 0) {
      gather_impulses(c, acc);
      c.block.apply(a, b, acc);
      warm_start_free_limits(c, a, b);
    }
    // (A point joint has no motor or spring impulse to warm-start.)
    if (!c.point) joint_ops(j.type).warm_start(j, c, a, b);
  }
  warm_start_point_batches(scratch);
  // The shared immovable body takes no velocity from any of it.
  scratch.solver_bodies[0].linear_velocity = {};
  scratch.solver_bodies[0].angular_velocity = {};
}

namespace {

// One pass over a joint solved on its own: its extra rows, then its
// structure as one block.
// `at_refresh`: the bodies stand where the rows were refreshed, so the
// frames, limits and one-row groups kept then hold.
void solve_alone(const JointRecord& j, JointConstraint& c, SolverBody& a, SolverBody& b,
                 bool use_bias, bool at_refresh) {
  const JointOps& ops = joint_ops(j.type);
  const int m = c.block.size();
  if (m == 0) {
    ops.solve(j, c, a, b, use_bias);
    return;
  }
  const JointFrames f = at_refresh ? c.frames : joint_frames(c, a, b);
  float acc[kMaxBlockRows];
  gather_impulses(c, acc);
  float bias[kMaxBlockRows] = {};
  if (use_bias) structural_bias(c, f, ops.angular_error(j, f), c.soft.bias_rate, bias);
  solve_block(c.block, a, b, bias, c.soft, use_bias, acc);
  settle_held_limits(c, a, b, acc);
  // Springs, motors and the limits not yet reached after the structure,
  // each with the impulse that leaves the structure where it is: both
  // end the pass satisfied.
  ExtraBase base;
  base.block = &c.block;
  base.block_impulse = acc;
  if (at_refresh) base.kept = c.kept;
  if (ops.extras != nullptr) ops.extras(j, c, a, b, f, use_bias, base);
  solve_free_limits(j, c, a, b, f, use_bias, base, at_refresh);
  // Their compensation may have pulled on a limit the block holds.
  settle_held_limits(c, a, b, acc);
  scatter_impulses(c, acc);
}

}  // namespace

void solve_joints(const WorldState& state, WorldScratch& scratch, bool use_bias,
                  bool contacted_only) {
  const std::vector<SolverBody>& bodies = scratch.solver_bodies;
  // The angular parts before their points (the structure ends the pass).
  solve_angular_parts(state, scratch, use_bias, contacted_only);
  solve_angular_batches(scratch, use_bias, contacted_only);
  for (uint32_t t = 0; t < scratch.trees.size(); ++t) {
    if (contacted_only) {
      const JointTree& tree = scratch.trees[t];
      bool contacted = false;
      for (uint32_t q = tree.body_begin; q < tree.body_end; ++q) {
        contacted = contacted || bodies[scratch.tree_bodies[q].body].contacted;
      }
      if (!contacted) continue;
    }
    solve_joint_tree(state.joints, scratch, t, use_bias);
  }
  for (const uint32_t k : scratch.joint_general) {
    JointConstraint& c = scratch.joint_constraints[k];
    if (c.tree != kNoTree) continue;
    if (contacted_only && !bodies[c.body_a].contacted && !bodies[c.body_b].contacted) continue;
    if (c.point) {
      solve_point(c, scratch.solver_bodies[c.body_a], scratch.solver_bodies[c.body_b], use_bias);
      continue;
    }
    solve_alone(state.joints[c.record], c, scratch.solver_bodies[c.body_a],
                scratch.solver_bodies[c.body_b], use_bias, scratch.joint_frames_fresh);
  }
  solve_point_batches(scratch, use_bias, contacted_only);
  scratch.solver_bodies[0].linear_velocity = {};
  scratch.solver_bodies[0].angular_velocity = {};
}

void displace(const RowBlock& block, const float* lambda, SolverBody& a, SolverBody& b) {
  Vec3 linear{};
  Vec3 angular_a{};
  Vec3 angular_b{};
  for (int i = 0; i < block.size(); ++i) {
    const JointRow& r = block.row(i);
    linear += r.linear * lambda[i];
    angular_a += r.angular_a * lambda[i];
    angular_b += r.angular_b * lambda[i];
  }
  if (a.inv_mass > 0.0f) {
    a.delta_position -= linear * a.inv_mass;
    a.delta_rotation = integrate_rotation(a.delta_rotation, -(a.inv_inertia * angular_a), 1.0f);
  }
  if (b.inv_mass > 0.0f) {
    b.delta_position += linear * b.inv_mass;
    b.delta_rotation = integrate_rotation(b.delta_rotation, b.inv_inertia * angular_b, 1.0f);
  }
}

void release_pulling_limits(const JointConstraint& c, float* x) {
  release_block_limits(c, x, nullptr);
}

void project_joints(const WorldState& state, WorldScratch& scratch) {
  project_angular_parts(state, scratch);
  project_angular_batches(scratch);
  for (uint32_t t = 0; t < scratch.trees.size(); ++t) project_joint_tree(state.joints, scratch, t);
  float error[kMaxBlockRows];
  float x[kMaxBlockRows];
  for (const uint32_t k : scratch.joint_general) {
    const JointConstraint& c = scratch.joint_constraints[k];
    if (c.tree != kNoTree || c.block.size() == 0) continue;
    const JointRecord& j = state.joints[c.record];
    SolverBody& a = scratch.solver_bodies[c.body_a];
    SolverBody& b = scratch.solver_bodies[c.body_b];
    if (c.point) {
      project_point(c, a, b);
      continue;
    }
    const JointFrames f = joint_frames(c, a, b);
    structural_bias(c, f, joint_ops(j.type).angular_error(j, f), 1.0f, error);
    for (int i = 0; i < c.block.size(); ++i) error[i] = -clamp_projection(error[i]);
    c.block.solve(error, x);
    release_pulling_limits(c, x);
    displace(c.block, x, a, b);
  }
  project_point_batches(scratch);
}

void sum_joint_impulses(WorldScratch& scratch) {
  sum_point_batches(scratch);
  for (const uint32_t k : scratch.joint_general) {
    JointConstraint& c = scratch.joint_constraints[k];
    c.tick_linear += c.linear_impulse;
    c.tick_angular += c.angular_impulse;
  }
}

namespace {

// An impulse as the state rule keeps it (check_joint): finite, each
// component within kMaxForce.
float settle(float v) {
  const float f = settle_impulse(v);
  return f > kMaxForce ? kMaxForce : (f < -kMaxForce ? -kMaxForce : f);
}
Vec3 settle(Vec3 v) {
  return {settle(v.x), settle(v.y), settle(v.z)};
}
float settle_push(float v) {
  const float f = settle(v);
  return f > 0.0f ? f : 0.0f;
}

}  // namespace

void store_joint_impulses(WorldState& state, WorldScratch& scratch) {
  store_point_batches(scratch, state.config.substeps);
  for (const JointConstraint& c : scratch.joint_constraints) {
    JointRecord& j = state.joints[c.record];
    j.linear_impulse = settle(c.linear_impulse);
    j.angular_impulse = settle(c.angular_impulse);
    j.motor_impulse = settle(c.motor_impulse);
    j.spring_impulse = settle(c.spring_impulse);
    j.axial_impulse = settle(c.axial_impulse);
    // A limit only pushes: its impulse is kept at zero or above, as the
    // state rule holds it (the passes settle it so; this holds the rule
    // whatever rounding leaves).
    j.lower_impulse = settle_push(c.lower_impulse);
    j.upper_impulse = settle_push(c.upper_impulse);
    j.cone_impulse = settle_push(c.cone_impulse);
    if (j.break_impulse <= 0.0f) continue;
    const float limit_sq = j.break_impulse * j.break_impulse;
    if (length_squared(c.tick_linear) > limit_sq || length_squared(c.tick_angular) > limit_sq) {
      j.flags |= kJointBroken;
      // A broken joint holds nothing: its impulses go, so nothing warm
      // starts from them should it ever be read.
      j.linear_impulse = j.angular_impulse = j.motor_impulse = j.spring_impulse = Vec3{};
      j.axial_impulse = j.lower_impulse = j.upper_impulse = j.cone_impulse = 0.0f;
      scratch.broken_joints.push_back({c.record, j.generation});
      ++scratch.joint_serial;  // its pair collides again from the next step
    }
  }
}

}  // namespace rwd::sim::d3
