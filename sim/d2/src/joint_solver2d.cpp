// SPDX-License-Identifier: MIT
#include "joint_solver2d.h"

#include "body_mass2d.h"
#include "body_math2d.h"
#include "contact_solver2d.h"
#include "joint_math2d.h"
#include "rewind/core/detail/take_color.h"
#include "rewind/fixed/trig.h"

namespace rwd::sim2d::detail {

W angle_of(Rot q) {
  return fixed::vector_angle(q.s, q.c).raw();
}

V2 solve22(W k11, W k12, W k22, V2 v) {
  const W det = wmul(k11, k22) - wmul(k12, k12);
  if (det == 0) return {};
  return {wdiv(wmul(k22, v.x) - wmul(k12, v.y), det), wdiv(wmul(k11, v.y) - wmul(k12, v.x), det)};
}

PointMass2D point_mass(const SolverBody2D& a, const SolverBody2D& b, const Anchors2D& r) {
  const W m = a.inv_mass + b.inv_mass;
  return {
      m + wmul(a.inv_inertia, wmul(r.ra.y, r.ra.y)) + wmul(b.inv_inertia, wmul(r.rb.y, r.rb.y)),
      -wmul(a.inv_inertia, wmul(r.ra.y, r.ra.x)) - wmul(b.inv_inertia, wmul(r.rb.y, r.rb.x)),
      m + wmul(a.inv_inertia, wmul(r.ra.x, r.ra.x)) + wmul(b.inv_inertia, wmul(r.rb.x, r.rb.x))};
}

W solve_angle_limit(W c, W sign, W& accumulated, W axial_mass, const Softness2D& soft,
                    SolverBody2D& a, SolverBody2D& b, const JointPass2D& pass) {
  const W cdot = wmul(sign, b.w - a.w);
  W impulse;
  if (c > 0) {
    // Speculative, as one_sided_bias() gives it: mass scale one (the
    // product by kWOne is exact) and no impulse term.
    impulse = -wmul(axial_mass, cdot + wmul(c, pass.inv_h));
  } else {
    const BiasTerms2D t = one_sided_bias(c, soft, pass);
    impulse =
        -wmul(wmul(axial_mass, t.mass_scale), cdot + t.bias) - wmul(t.impulse_scale, accumulated);
  }
  const W next = wmax(accumulated + impulse, 0);
  const W applied = next - accumulated;
  accumulated = next;
  // Far from the limit nothing is applied (most rows, most passes).
  if (applied != 0) apply_angular(a, b, wmul(sign, applied));
  return applied;
}

namespace {

bool active(const JointRecord2D& j) {
  return (j.flags & kJointLive) && !(j.flags & kJointBroken);
}

// The relative angle in [-pi, pi] after taking the reference off.
W unwind(W angle) {
  const W pi = kWPi;
  if (angle > pi) return angle - 2 * pi;
  if (angle < -pi) return angle + 2 * pi;
  return angle;
}

// Colours of the joint order, as the 3D solver's (take_color.h).
constexpr uint32_t kJointColors = 24;

// Reorders the joints colour by colour: each joint, in state order, takes
// the first colour in which neither of its bodies that the joint moves
// already has a joint (kJointColors when every colour has one; those last,
// in state order), and the pass runs colour 0's joints, then colour 1's.
// A colour's joints share no moving body, so within it the order changes
// nothing, and across them every body meets its joints spread over the
// pass rather than in the order they were made. That order matters for
// stiff lattices: in a 100 x 100 grid of revolute joints (made column by
// column) hanging from seven anchors, the joints near the anchors carry
// 15 kN on 0.5 kg links, and solved in creation order the links there spun
// up within 1.7 s and threw the grid apart (98 x 98 and larger); coloured,
// as Box2D v3 orders its joints, the 100 x 100 grid holds.
void order_by_color(StepScratch2D& scratch) {
  auto& joints = scratch.joints;
  if (joints.size() < 2) return;
  const size_t words = (scratch.bodies.size() + 63) / 64;
  auto& bits = scratch.joint_color_bits;
  bits.assign(words * kJointColors, 0);
  auto& color = scratch.joint_color;
  color.resize(joints.size());
  uint32_t count[kJointColors + 1] = {};
  for (size_t k = 0; k < joints.size(); ++k) {
    const JointConstraint2D& c = joints[k];
    const SolverBody2D& a = scratch.bodies[c.a];
    const SolverBody2D& b = scratch.bodies[c.b];
    const bool moves_a = a.inv_mass != 0 || a.inv_inertia != 0;
    const bool moves_b = b.inv_mass != 0 || b.inv_inertia != 0;
    const uint32_t col =
        rwd::detail::take_color(bits.data(), words, kJointColors, c.a, moves_a, c.b, moves_b);
    color[k] = col;
    ++count[col];
  }
  uint32_t start[kJointColors + 1];
  uint32_t at = 0;
  for (uint32_t col = 0; col <= kJointColors; ++col) {
    start[col] = at;
    at += count[col];
  }
  auto& sorted = scratch.joint_spare;
  sorted.resize(joints.size());
  for (size_t k = 0; k < joints.size(); ++k) sorted[start[color[k]]++] = joints[k];
  joints.swap(sorted);
}

}  // namespace

void prepare_joints(World2DState& state, StepScratch2D& scratch, W h) {
  const World2DConfig& config = state.config;
  const W substep_hz = winv(h);
  const W contact_hertz = wmin(w_from(config.contact_hertz), substep_hz / 4);
  const Softness2D joint_soft =
      make_softness(2 * contact_hertz, w_from(config.joint_damping_ratio), h);
  auto& out = scratch.joints;
  out.clear();
  for (uint32_t ji = 0; ji < state.joints.size(); ++ji) {
    const JointRecord2D& j = state.joints[ji];
    if (!active(j)) continue;
    const BodyRecord2D& body_a = state.bodies[j.a];
    const BodyRecord2D& body_b = state.bodies[j.b];
    if (!(body_a.flags & kBodyEnabled) || !(body_b.flags & kBodyEnabled)) continue;
    if (!is_moving(body_a) && !is_moving(body_b)) continue;
    // Between two static or kinematic bodies every inverse mass is zero, so
    // no row can move anything (each effective mass is zero); left out, such
    // a joint costs nothing and its impulses stay zero.
    if (body_a.kind != BodyKind2D::kDynamic && body_b.kind != BodyKind2D::kDynamic) continue;
    const SolverBody2D& a = scratch.bodies[j.a];
    const SolverBody2D& b = scratch.bodies[j.b];
    JointConstraint2D& c = out.emplace_back();
    c.joint = ji;
    c.a = j.a;
    c.b = j.b;
    c.frame_a = rotate(body_a.rotation, j.local_anchor_a - body_a.local_center);
    c.frame_b = rotate(body_b.rotation, j.local_anchor_b - body_b.local_center);
    c.delta_center = body_b.center - body_a.center;
    // The angle (an arctangent, the dearest part of the preparation) only
    // for the joints that hold or limit one.
    const bool needs_angle =
        j.type == JointType2D::kWeld || j.type == JointType2D::kPrismatic ||
        j.type == JointType2D::kWheel ||
        (j.type == JointType2D::kRevolute && (j.flags & (kJointSpring | kJointLimit)));
    if (needs_angle) {
      c.delta_angle =
          unwind(angle_of(rinv_mul(body_a.rotation, body_b.rotation)) - j.reference_angle);
    }
    c.axis_a = rotate(body_a.rotation, j.local_axis_a);
    // The rows about the angle need the angular mass (a division per joint
    // and step); a distance joint and a bare revolute have none.
    const bool plain = j.type == JointType2D::kDistance ||
                       (j.type == JointType2D::kRevolute &&
                        !(j.flags & (kJointSpring | kJointMotor | kJointLimit)));
    const W k = a.inv_inertia + b.inv_inertia;
    c.angular_mass = !plain && k > 0 ? winv(k) : 0;
    c.soft = joint_soft;
    c.spring = (j.flags & kJointSpring) ? make_softness(j.hertz, j.damping_ratio, h) : Softness2D{};
    switch (j.type) {
      case JointType2D::kDistance:
        prepare_distance(j, c, a, b);
        break;
      case JointType2D::kPrismatic:
      case JointType2D::kWheel:
        prepare_slider(j, c, a, b);
        break;
      case JointType2D::kWeld:
        c.spring =
            j.linear_hertz > 0 ? make_softness(j.linear_hertz, j.damping_ratio, h) : joint_soft;
        c.angular_spring =
            j.angular_hertz > 0 ? make_softness(j.angular_hertz, j.damping_ratio, h) : joint_soft;
        break;
      case JointType2D::kGrab:
        // Pulled toward the target; its spin is damped softly so a grabbed
        // body does not whirl about the grab point.
        c.delta_center = body_b.center - j.target;
        c.angular_spring = make_softness(kWOne / 2, kWOne / 10, h);
        c.angular_mass = b.inv_inertia > 0 ? winv(b.inv_inertia) : 0;
        break;
      case JointType2D::kRevolute:
        prepare_revolute(c, a, b);
        break;
    }
  }
  order_by_color(scratch);
}

void warm_start_joints(World2DState& state, StepScratch2D& scratch) {
  for (const JointConstraint2D& c : scratch.joints) {
    const JointRecord2D& j = state.joints[c.joint];
    SolverBody2D& a = scratch.bodies[c.a];
    SolverBody2D& b = scratch.bodies[c.b];
    switch (j.type) {
      case JointType2D::kDistance:
        warm_start_distance(j, c, a, b);
        break;
      case JointType2D::kRevolute:
        warm_start_revolute(j, c, a, b);
        break;
      case JointType2D::kPrismatic:
      case JointType2D::kWheel:
        warm_start_slider(j, c, a, b);
        break;
      case JointType2D::kWeld:
        warm_start_weld(j, c, a, b);
        break;
      case JointType2D::kGrab:
        warm_start_grab(j, c, b);
        break;
    }
  }
}

void solve_joints(World2DState& state, StepScratch2D& scratch, const JointPass2D& pass) {
  for (JointConstraint2D& c : scratch.joints) {
    JointRecord2D& j = state.joints[c.joint];
    SolverBody2D& a = scratch.bodies[c.a];
    SolverBody2D& b = scratch.bodies[c.b];
    switch (j.type) {
      case JointType2D::kDistance:
        solve_distance(j, c, a, b, pass);
        break;
      case JointType2D::kRevolute:
        solve_revolute(j, c, a, b, pass);
        break;
      case JointType2D::kPrismatic:
        solve_prismatic(j, c, a, b, pass);
        break;
      case JointType2D::kWheel:
        solve_wheel(j, c, a, b, pass);
        break;
      case JointType2D::kWeld:
        solve_weld(j, c, a, b, pass);
        break;
      case JointType2D::kGrab:
        solve_grab(j, c, b, pass);
        break;
    }
  }
}

void break_joints(World2DState& state, int substeps) {
  for (JointRecord2D& j : state.joints) {
    if (!active(j) || j.break_impulse == 0) continue;
    // The last substep's impulses, times the substeps: the tick's impulse.
    const W linear = vlength(j.linear_impulse) + wabs(j.axial_impulse) + wabs(j.spring_impulse) +
                     wabs(j.lower_impulse) + wabs(j.upper_impulse);
    const W angular = wabs(j.angular_impulse) + wabs(j.motor_impulse);
    if (wmax(linear, angular) * substeps > j.break_impulse) j.flags |= kJointBroken;
  }
}

}  // namespace rwd::sim2d::detail
