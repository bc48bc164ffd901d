// SPDX-License-Identifier: MIT
// TGS-Soft contact solver (after Erin Catto's "Solver2D" soft step, as in
// Box2D v3), in 3D. Per tick, with h = tick / substeps:
//   for each substep:
//     integrate velocities (gravity, forces, damping)
//     warm start (apply last substep's impulses)
//     solve      (soft contacts: spring-damper push-out, capped speed)
//     integrate positions
//     relax      (rigid contacts, no push-out: removes the bias velocity)
//   restitution (bounce from the pre-step approach speed)
//   store impulses in the contact cache for next tick's warm start
//   write back, settling every body under the state rule (state_rules.h):
//   speed limits, finite poses, world bounds (bodies that left are disabled
//   and reported)
// Contact anchors stay fixed relative to the body centres for the whole tick;
// each substep recomputes the separation from how far the bodies have moved
// and turned since the tick began, so the narrowphase runs once per tick.
// Inverse inertia is taken at the start of the tick (small substeps keep the
// error small; recomputing it per substep would cost a matrix per body).
#include <cmath>

#include "d3/body_storage.h"
#include "d3/pipeline.h"
#include "d3/state_rules.h"
#include "rewind/sim/det_math.h"

namespace rwd::sim::d3 {
namespace {

// Speed limits keep one bad input from producing inf/NaN state: no body
// moves faster than this, or turns more than a quarter turn per substep.
constexpr float kMaxLinearSpeed = 400.0f;  // m/s
constexpr float kMaxRotationPerSubstep = 0.25f * kPi;

Softness make_soft(float hertz, float zeta, float h) {
  if (hertz == 0.0f) return {0.0f, 1.0f, 0.0f};
  float omega = 2.0f * kPi * hertz;
  float a1 = 2.0f * zeta + h * omega;
  float a2 = h * omega * a1;
  float a3 = 1.0f / (1.0f + a2);
  return {omega / a1, a2 * a3, a3};
}

float effective_mass(const SolverBody& a, const SolverBody& b, Vec3 ra, Vec3 rb, Vec3 dir) {
  Vec3 rna = cross(ra, dir);
  Vec3 rnb = cross(rb, dir);
  float k = a.inv_mass + b.inv_mass + dot(rna, a.inv_inertia * rna) + dot(rnb, b.inv_inertia * rnb);
  return k > 0.0f ? 1.0f / k : 0.0f;
}

void apply_impulse(SolverBody& a, SolverBody& b, Vec3 ra, Vec3 rb, Vec3 p) {
  a.linear_velocity -= p * a.inv_mass;
  a.angular_velocity -= a.inv_inertia * cross(ra, p);
  b.linear_velocity += p * b.inv_mass;
  b.angular_velocity += b.inv_inertia * cross(rb, p);
}

Vec3 relative_velocity(const SolverBody& a, const SolverBody& b, Vec3 ra, Vec3 rb) {
  Vec3 va = a.linear_velocity + cross(a.angular_velocity, ra);
  Vec3 vb = b.linear_velocity + cross(b.angular_velocity, rb);
  return vb - va;
}

void prepare(WorldState& state, WorldScratch& scratch, float h) {
  const WorldConfig& config = state.config;
  const uint32_t n = static_cast<uint32_t>(state.infos.size());
  scratch.solver_index.assign(n, 0);
  scratch.solver_body_ids.clear();
  scratch.solver_bodies.clear();
  SolverBody immovable{};
  immovable.delta_rotation = Quat{};
  immovable.inv_inertia = mat3_zero();
  immovable.linear_damping_factor = 1.0f;
  immovable.angular_damping_factor = 1.0f;
  scratch.solver_bodies.push_back(immovable);
  scratch.solver_body_ids.push_back(0);
  for (uint32_t i = 0; i < n; ++i) {
    const BodyInfo& info = state.infos[i];
    if (!is_active(info)) continue;
    const BodySim& sim = state.sims[i];
    const BodyMass& mass = state.masses[i];
    SolverBody b{};
    b.linear_velocity = sim.linear_velocity;
    b.angular_velocity = sim.angular_velocity;
    b.delta_rotation = Quat{};
    b.inv_mass = mass.inv_mass;
    b.linear_damping_factor = 1.0f;
    b.angular_damping_factor = 1.0f;
    if (info.kind == BodyKind::kDynamic) {
      b.inv_inertia = world_inverse_inertia(mass, sim.rotation);
      b.linear_acceleration = config.gravity * info.gravity_scale + sim.force * mass.inv_mass;
      b.linear_damping_factor = 1.0f / (1.0f + h * info.linear_damping);
      b.angular_damping_factor = 1.0f / (1.0f + h * info.angular_damping);
    } else {
      b.inv_inertia = mat3_zero();
    }
    scratch.solver_index[i] = static_cast<uint32_t>(scratch.solver_bodies.size());
    scratch.solver_bodies.push_back(b);
    scratch.solver_body_ids.push_back(i);
  }

  // The soft contact must not be stiffer than a quarter of the substep rate
  // or it stops being stable; contacts against immovable bodies get twice the
  // stiffness since only one side moves (Box2D's static softness).
  float hertz = config.contact_hertz;
  float limit = 0.25f / h;
  if (hertz > limit) hertz = limit;
  Softness soft = make_soft(hertz, config.contact_damping_ratio, h);
  Softness static_soft = make_soft(2.0f * hertz, config.contact_damping_ratio, h);

  scratch.constraints.clear();
  uint32_t points = 0;
  for (uint32_t k = 0; k < state.contacts.size(); ++k) {
    const ContactRecord& rec = state.contacts[k];
    const ContactGeometry& geo = scratch.geometry[k];
    if (geo.valid == 0 || rec.sensor != 0 || rec.point_count == 0) continue;
    uint32_t ia = scratch.solver_index[rec.index_a];
    uint32_t ib = scratch.solver_index[rec.index_b];
    const SolverBody& a = scratch.solver_bodies[ia];
    const SolverBody& b = scratch.solver_bodies[ib];
    if (a.inv_mass == 0.0f && b.inv_mass == 0.0f) continue;  // nothing can respond
    ContactConstraint c{};
    c.body_a = ia;
    c.body_b = ib;
    c.record = k;
    c.point_count = rec.point_count;
    c.normal = geo.manifold.normal;
    tangent_basis(c.normal, c.tangent1, c.tangent2);
    c.friction = geo.friction;
    c.restitution = geo.restitution;
    c.softness = (a.inv_mass == 0.0f || b.inv_mass == 0.0f) ? static_soft : soft;
    for (uint32_t p = 0; p < c.point_count; ++p) {
      const ManifoldPoint& mp = geo.manifold.points[p];
      ConstraintPoint& cp = c.points[p];
      cp.anchor_a = mp.anchor_a;
      cp.anchor_b = mp.anchor_b;
      cp.base_separation = mp.separation - dot(mp.anchor_b - mp.anchor_a, c.normal);
      cp.normal_mass = effective_mass(a, b, cp.anchor_a, cp.anchor_b, c.normal);
      cp.tangent_mass1 = effective_mass(a, b, cp.anchor_a, cp.anchor_b, c.tangent1);
      cp.tangent_mass2 = effective_mass(a, b, cp.anchor_a, cp.anchor_b, c.tangent2);
      cp.normal_impulse = rec.points[p].normal_impulse;
      cp.tangent_impulse1 = rec.points[p].tangent_impulse1;
      cp.tangent_impulse2 = rec.points[p].tangent_impulse2;
      cp.max_normal_impulse = 0.0f;
      cp.relative_velocity = dot(c.normal, relative_velocity(a, b, cp.anchor_a, cp.anchor_b));
    }
    points += c.point_count;
    scratch.constraints.push_back(c);
  }
  scratch.stats.contact_points = points;
}

void integrate_velocities(WorldScratch& scratch, float h) {
  for (size_t i = 1; i < scratch.solver_bodies.size(); ++i) {
    SolverBody& b = scratch.solver_bodies[i];
    if (b.inv_mass == 0.0f) continue;  // kinematic: keeps its set velocity
    Vec3 v = b.linear_velocity * b.linear_damping_factor + b.linear_acceleration * h;
    Vec3 w = b.angular_velocity * b.angular_damping_factor;
    float speed_sq = length_squared(v);
    if (speed_sq > kMaxLinearSpeed * kMaxLinearSpeed) {
      v = v * (kMaxLinearSpeed / std::sqrt(speed_sq));
    }
    b.linear_velocity = v;
    b.angular_velocity = w;
  }
}

void integrate_positions(WorldScratch& scratch, float h) {
  for (size_t i = 1; i < scratch.solver_bodies.size(); ++i) {
    SolverBody& b = scratch.solver_bodies[i];
    Vec3 w = b.angular_velocity;
    float max_w = kMaxRotationPerSubstep / h;
    float w_sq = length_squared(w);
    if (w_sq > max_w * max_w) {
      w = w * (max_w / std::sqrt(w_sq));
      b.angular_velocity = w;
    }
    b.delta_position += b.linear_velocity * h;
    b.delta_rotation = integrate_rotation(b.delta_rotation, w, h);
  }
}

void warm_start(WorldScratch& scratch) {
  for (ContactConstraint& c : scratch.constraints) {
    SolverBody& a = scratch.solver_bodies[c.body_a];
    SolverBody& b = scratch.solver_bodies[c.body_b];
    for (uint32_t p = 0; p < c.point_count; ++p) {
      const ConstraintPoint& cp = c.points[p];
      Vec3 impulse = c.normal * cp.normal_impulse + c.tangent1 * cp.tangent_impulse1 +
                     c.tangent2 * cp.tangent_impulse2;
      apply_impulse(a, b, cp.anchor_a, cp.anchor_b, impulse);
    }
  }
}

void solve_contacts(WorldScratch& scratch, const WorldConfig& config, float inv_h, bool use_bias) {
  const float slop = config.linear_slop_m;
  const float push_max = config.contact_push_max_mps;
  for (ContactConstraint& c : scratch.constraints) {
    SolverBody& a = scratch.solver_bodies[c.body_a];
    SolverBody& b = scratch.solver_bodies[c.body_b];
    Vec3 dp = b.delta_position - a.delta_position;
    for (uint32_t p = 0; p < c.point_count; ++p) {
      ConstraintPoint& cp = c.points[p];
      // Current separation from the motion since the tick began.
      Vec3 pa = rotate(a.delta_rotation, cp.anchor_a);
      Vec3 pb = rotate(b.delta_rotation, cp.anchor_b);
      float s = dot(dp + (pb - pa), c.normal) + cp.base_separation;
      float bias = 0.0f;
      float mass_scale = 1.0f;
      float impulse_scale = 0.0f;
      if (s > 0.0f) {
        bias = s * inv_h;  // speculative: may close the gap, not more
      } else if (use_bias) {
        float depth = s + slop;  // penetration up to the slop is allowed
        if (depth < 0.0f) {
          bias = c.softness.bias_rate * depth;
          if (bias < -push_max) bias = -push_max;
        }
        mass_scale = c.softness.mass_scale;
        impulse_scale = c.softness.impulse_scale;
      }
      float vn = dot(relative_velocity(a, b, cp.anchor_a, cp.anchor_b), c.normal);
      float impulse =
          -cp.normal_mass * mass_scale * (vn + bias) - impulse_scale * cp.normal_impulse;
      float total = cp.normal_impulse + impulse;
      if (total < 0.0f) total = 0.0f;
      impulse = total - cp.normal_impulse;
      cp.normal_impulse = total;
      if (total > cp.max_normal_impulse) cp.max_normal_impulse = total;
      apply_impulse(a, b, cp.anchor_a, cp.anchor_b, c.normal * impulse);
    }
    // Friction after the normal impulses so the cone uses this pass's values.
    for (uint32_t p = 0; p < c.point_count; ++p) {
      ConstraintPoint& cp = c.points[p];
      Vec3 dv = relative_velocity(a, b, cp.anchor_a, cp.anchor_b);
      float i1 = -cp.tangent_mass1 * dot(dv, c.tangent1);
      float i2 = -cp.tangent_mass2 * dot(dv, c.tangent2);
      float t1 = cp.tangent_impulse1 + i1;
      float t2 = cp.tangent_impulse2 + i2;
      // Circular friction cone: |t| <= mu * normal impulse.
      float limit = c.friction * cp.normal_impulse;
      float len_sq = t1 * t1 + t2 * t2;
      if (len_sq > limit * limit) {
        float scale = limit / std::sqrt(len_sq);  // len_sq > 0 here
        t1 = t1 * scale;
        t2 = t2 * scale;
      }
      i1 = t1 - cp.tangent_impulse1;
      i2 = t2 - cp.tangent_impulse2;
      cp.tangent_impulse1 = t1;
      cp.tangent_impulse2 = t2;
      apply_impulse(a, b, cp.anchor_a, cp.anchor_b, c.tangent1 * i1 + c.tangent2 * i2);
    }
  }
  // The immovable body absorbs impulses with zero inverse mass; keep it at
  // rest explicitly so no -0/+0 noise can ever accumulate there.
  scratch.solver_bodies[0].linear_velocity = {};
  scratch.solver_bodies[0].angular_velocity = {};
}

void apply_restitution(WorldScratch& scratch, const WorldConfig& config) {
  const float threshold = config.restitution_threshold_mps;
  for (ContactConstraint& c : scratch.constraints) {
    if (c.restitution == 0.0f) continue;
    SolverBody& a = scratch.solver_bodies[c.body_a];
    SolverBody& b = scratch.solver_bodies[c.body_b];
    for (uint32_t p = 0; p < c.point_count; ++p) {
      ConstraintPoint& cp = c.points[p];
      // Only points that were approaching fast and actually pushed bounce.
      if (cp.relative_velocity > -threshold || cp.max_normal_impulse == 0.0f) continue;
      float vn = dot(relative_velocity(a, b, cp.anchor_a, cp.anchor_b), c.normal);
      float impulse = -cp.normal_mass * (vn + c.restitution * cp.relative_velocity);
      float total = cp.normal_impulse + impulse;
      if (total < 0.0f) total = 0.0f;
      impulse = total - cp.normal_impulse;
      cp.normal_impulse = total;
      apply_impulse(a, b, cp.anchor_a, cp.anchor_b, c.normal * impulse);
    }
  }
  scratch.solver_bodies[0].linear_velocity = {};
  scratch.solver_bodies[0].angular_velocity = {};
}

void store_impulses(WorldState& state, const WorldScratch& scratch) {
  for (const ContactConstraint& c : scratch.constraints) {
    ContactRecord& rec = state.contacts[c.record];
    for (uint32_t p = 0; p < c.point_count; ++p) {
      rec.points[p].normal_impulse = settle_impulse(c.points[p].normal_impulse);
      rec.points[p].tangent_impulse1 = settle_impulse(c.points[p].tangent_impulse1);
      rec.points[p].tangent_impulse2 = settle_impulse(c.points[p].tangent_impulse2);
    }
  }
}

// The gyroscopic term. The solver holds the inertia tensor fixed at the
// tick's starting orientation, so its angular velocity belongs to that
// orientation: the world angular momentum is L = I(q0) w. A free body keeps
// L while its inertia turns with it, so the velocity it ends the tick with
// is I(q1)^-1 L: this is what makes a box spun about its intermediate axis
// tumble (the Dzhanibekov effect) instead of spinning forever.
//
// The orientation q1 came from the tick's starting velocity, an explicit
// step that on its own pumps energy into a tumbling body (an explicit torque
// w x Iw does the same; an implicit one, as in Bullet, drains it). The
// gyroscopic term does no work, so the body-frame momentum is moved along the
// sphere |L| = const back onto the energy ellipsoid L.I^-1.L = 2E of the
// tick's start (two Newton steps), and the orientation is turned by the same
// small body-frame rotation, so the world momentum stays exactly L. Both
// invariants then hold to rounding.
struct Spin {
  Vec3 angular_velocity;
  Quat rotation;
};

Spin carry_angular_momentum(const BodyMass& mass, Quat q0, Quat q1, Vec3 w) {
  const Vec3 inv = mass.inv_inertia_local;
  // Equal principal moments (spheres, cubes): the inertia tensor does not
  // change as the body turns, so neither does w.
  if (inv.x == inv.y && inv.y == inv.z) return {w, q1};
  const Vec3 inertia{1.0f / inv.x, 1.0f / inv.y, 1.0f / inv.z};
  const Vec3 l_world = rotate(q0, mul_elements(inertia, inv_rotate(q0, w)));
  const float two_energy = dot(w, l_world);
  const float l_sq = length_squared(l_world);
  const Vec3 carried = inv_rotate(q1, l_world);  // body frame at the tick's end
  if (!(l_sq > 0.0f) || !(two_energy > 0.0f)) return {rotate(q1, mul_elements(inv, carried)), q1};
  Vec3 l = carried;
  for (int i = 0; i < 2; ++i) {
    const Vec3 g = mul_elements(inv, l);  // the body-frame w; L.I^-1.L has gradient 2g
    const float error = dot(l, g) - two_energy;
    // The gradient's part tangent to the momentum sphere.
    const Vec3 t = g - l * (dot(g, l) / length_squared(l));
    const float slope = 2.0f * dot(g, t);
    if (!(slope > 1e-12f * two_energy)) break;  // on a principal axis: nothing to correct
    Vec3 next = l - t * (error / slope);
    next = next * std::sqrt(l_sq / length_squared(next));
    if (!is_finite(next)) break;
    l = next;
  }
  // The body-frame rotation r taking l to `carried`: q1 r maps l to L.
  const Vec3 axis = cross(l, carried);
  const Quat r = normalize(Quat{axis.x, axis.y, axis.z, l_sq + dot(l, carried)});
  const Quat q = normalize(q1 * r);
  if (!is_finite(q)) return {rotate(q1, mul_elements(inv, carried)), q1};
  return {rotate(q, mul_elements(inv, l)), q};
}

void finalize(WorldState& state, WorldScratch& scratch, float tick) {
  const WorldConfig& config = state.config;
  for (size_t i = 1; i < scratch.solver_bodies.size(); ++i) {
    const SolverBody& b = scratch.solver_bodies[i];
    uint32_t index = scratch.solver_body_ids[i];
    BodySim& sim = state.sims[index];
    const BodySim before = sim;
    sim.position += b.delta_position;
    sim.rotation = normalize(b.delta_rotation * sim.rotation);
    sim.linear_velocity = b.linear_velocity;
    sim.angular_velocity = b.angular_velocity;
    if (state.infos[index].kind == BodyKind::kDynamic) {
      const Spin spin = carry_angular_momentum(state.masses[index], before.rotation, sim.rotation,
                                               b.angular_velocity);
      sim.angular_velocity = spin.angular_velocity;
      sim.rotation = spin.rotation;
    }
    sim.force = {};
    // Sleep timer: a body is at rest when no point of it moves faster than
    // the threshold (|v| + extent * |w| bounds every surface point's speed).
    // Kinematic bodies rest only when they are not driven at all.
    bool resting = false;
    if (state.infos[index].kind == BodyKind::kDynamic) {
      float speed =
          length(b.linear_velocity) + state.masses[index].extent * length(b.angular_velocity);
      resting = speed < config.sleep_threshold_mps;
    } else {
      resting = b.linear_velocity == Vec3{} && b.angular_velocity == Vec3{};
    }
    sim.sleep_time = resting ? sim.sleep_time + tick : 0.0f;
    // Solver bodies are in ascending body index, so events are too.
    if (settle_body(config, before, state.infos[index], sim)) {
      scratch.body_events.push_back(
          {BodyEventType::kLeftBounds, {index, state.infos[index].generation}, sim.position});
      mark_passive_dirty(scratch);
    }
  }
}

}  // namespace

void solve(WorldState& state, WorldScratch& scratch) {
  const WorldConfig& config = state.config;
  const float tick = config.tick_seconds;
  const float h = tick / static_cast<float>(config.substeps);
  const float inv_h = 1.0f / h;
  prepare(state, scratch, h);
  for (int32_t s = 0; s < config.substeps; ++s) {
    integrate_velocities(scratch, h);
    warm_start(scratch);
    solve_contacts(scratch, config, inv_h, true);
    integrate_positions(scratch, h);
    for (int32_t r = 0; r < config.relax_iterations; ++r) {
      solve_contacts(scratch, config, inv_h, false);
    }
  }
  apply_restitution(scratch, config);
  store_impulses(state, scratch);
  finalize(state, scratch, tick);
}

}  // namespace rwd::sim::d3
