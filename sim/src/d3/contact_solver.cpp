// SPDX-License-Identifier: MIT
// The contact solver: substeps after Erin Catto's "Solver2D" soft step (as
// in Box2D v3), in 3D, with the push-out split from the real velocities. Per
// tick, with h = tick / substeps:
//   for each substep:
//     integrate velocities (gravity, forces, damping)
//     warm start (apply last substep's impulses)
//     solve      (rigid contacts on the real velocities; three passes when
//                 the substep is longer than 1/240 s, world_config.h)
//     push-out   (overlaps beyond the slop pushed apart on separate push
//                 velocities, capped speed: deep ones one at a time from the
//                 ground up, then the rest in the lanes)
//     integrate positions (real plus push velocities; the push velocities
//                 and impulses last one tick and are never kept)
//     relax      (rigid contacts again, after the move)
//   restitution (bounce from the pre-step approach speed)
//   store impulses in the contact cache for next tick's warm start
//   write back, settling every body under the state rule (state_rules.h):
//   speed limits, finite poses, world bounds (bodies that left are disabled
//   and reported)
// Why the push-out has its own velocities: Box2D's soft contact pushes with
// the real velocities and lets relax take the push back, and carries load
// like a spring (an overlap proportional to the weight above: 10 mm at the
// foot of a 10-box stack, and a tall stack on such springs buckles). Here
// the real contact is rigid, so resting overlap stays at the slop whatever
// the load, and a push-out moves bodies apart without ever leaving them
// with speed (a column of deep overlaps separates without launching its top).
// The contact hertz and damping ratio still set how fast overlaps go.
//
// The normal impulses of a manifold's points are solved together (a few
// sweeps on the manifold's own K matrix) and applied to the bodies once;
// friction follows point by point. The real-velocity passes and the push-out
// of shallow overlaps run over coloured batches of eight contacts in SIMD
// lanes (contact_batches.cpp); the push-out of deep overlaps, which visits
// contacts from the ground up, runs here.
// Contact anchors stay fixed relative to the body centres for the whole tick;
// each substep recomputes the separation from how far the bodies have moved
// and turned since the tick began, so the narrowphase runs once per tick.
// Inverse inertia is taken at the start of the tick (small substeps keep the
// error small; recomputing it per substep would cost a matrix per body).
#include <cmath>

#include "d3/angular_momentum.h"
#include "d3/body_storage.h"
#include "d3/integrate_bodies.h"
#include "d3/pipeline.h"
#include "d3/shape_ops.h"
#include "d3/state_rules.h"
#include "rewind/core/det_math.h"

namespace rwd::sim::d3 {
namespace {

Softness make_soft(float hertz, float zeta, float h) {
  if (hertz == 0.0f) return {0.0f, 1.0f};
  float omega = 2.0f * kPi * hertz;
  float a1 = 2.0f * zeta + h * omega;
  float a2 = h * omega * a1;
  float a3 = 1.0f / (1.0f + a2);
  return {omega / a1, a2 * a3};
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
  // The awake bodies in ascending index: the broadphase's list, unless the
  // wake added some since (then a pass over every body).
  const bool listed = !scratch.woke_bodies;
  const uint32_t count = listed ? static_cast<uint32_t>(scratch.active.size()) : n;
  for (uint32_t k = 0; k < count; ++k) {
    const uint32_t i = listed ? scratch.active[k] : k;
    const BodyInfo& info = state.infos[i];
    if (!is_active(info)) continue;
    const BodySim& sim = state.sims[i];
    const BodyMass& mass = state.masses[i];
    scratch.solver_index[i] = static_cast<uint32_t>(scratch.solver_bodies.size());
    SolverBody& b = scratch.solver_bodies.emplace_back();
    b.linear_velocity = sim.linear_velocity;
    b.angular_velocity = sim.angular_velocity;
    b.delta_rotation = Quat{};
    b.inv_mass = mass.inv_mass;
    b.push_inv_mass = mass.inv_mass;
    b.linear_damping_factor = 1.0f;
    b.angular_damping_factor = 1.0f;
    if (info.kind == BodyKind::kDynamic) {
      b.inv_inertia = lock_inverse_inertia(
          info.lock_rotation, world_inverse_inertia(mass, body_axes(state, scratch, i)));
      b.torqued = !(sim.torque == Vec3{});
      if (b.torqued) b.angular_acceleration = b.inv_inertia * sim.torque;
      b.linear_acceleration = config.gravity * info.gravity_scale + sim.force * mass.inv_mass;
      b.linear_damping_factor = 1.0f / (1.0f + h * info.linear_damping);
      b.angular_damping_factor = 1.0f / (1.0f + h * info.angular_damping);
    } else {
      b.inv_inertia = mat3_zero();
    }
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
  scratch.overlapping = false;
  scratch.deep_overlap = false;
  const float deep_limit = -kDeepOverlapSlops * config.linear_slop_m;
  uint32_t points = 0;
  // The records with geometry this step, ascending: those update_contacts
  // evaluated and those the wake refreshed (the rest rest, and a level of
  // sleeping bodies makes them most of the cache).
  const std::vector<uint32_t>& evaluated = scratch.evaluated_records;
  const std::vector<uint32_t>& refreshed = scratch.refreshed_records;
  size_t e = 0;
  size_t f = 0;
  while (e < evaluated.size() || f < refreshed.size()) {
    const bool take_evaluated =
        f == refreshed.size() || (e < evaluated.size() && evaluated[e] < refreshed[f]);
    const uint32_t k = take_evaluated ? evaluated[e++] : refreshed[f++];
    const ContactRecord& rec = state.contacts[k];
    const ContactGeometry& geo = scratch.geometry[k];
    if (geo.valid == 0 || rec.sensor != 0 || rec.point_count == 0) continue;
    uint32_t ia = scratch.solver_index[rec.index_a];
    uint32_t ib = scratch.solver_index[rec.index_b];
    const SolverBody& a = scratch.solver_bodies[ia];
    const SolverBody& b = scratch.solver_bodies[ib];
    if (a.inv_mass == 0.0f && b.inv_mass == 0.0f) continue;  // nothing can respond
    // Built in place: a constraint is a few hundred bytes.
    ContactConstraint& c = scratch.constraints.emplace_back();
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
      cp.separation = mp.separation;
      if (mp.separation + config.linear_slop_m < 0.0f) c.overlapping = 1;
      if (mp.separation + config.linear_slop_m < deep_limit) scratch.deep_overlap = true;
      cp.normal_impulse = rec.points[p].normal_impulse;
      cp.tangent_impulse1 = rec.points[p].tangent_impulse1;
      cp.tangent_impulse2 = rec.points[p].tangent_impulse2;
      cp.max_normal_impulse = 0.0f;
      cp.tick_normal_impulse = 0.0f;
      // Only restitution reads the approach speed: a contact that cannot
      // bounce does not pay for it.
      cp.relative_velocity = c.restitution == 0.0f
                                 ? 0.0f
                                 : dot(c.normal, relative_velocity(a, b, cp.anchor_a, cp.anchor_b));
    }
    if (c.overlapping != 0) scratch.overlapping = true;
    points += c.point_count;
  }
  scratch.stats.contact_points = points;
}

// Impulses against the shared immovable body move nothing; its push row is
// cleared so the lanes read exact zeros from it.
void reset_immovable_push(WorldScratch& scratch) {
  SolverBody& immovable = scratch.solver_bodies[0];
  immovable.push_linear = {};
  immovable.push_angular = {};
  immovable.pushed = 0.0f;
}

// Projected Gauss-Seidel sweeps over one manifold's normal system with the
// bodies held: impulse[p] (accumulated, >= 0) is raised by delta[p] so that
// the normal velocity vn[p] + sum_j K[p][j] delta[j] reaches -bias[p], each
// step scaled by `scale`. No body is touched, so the sweeps cost a few
// multiply-adds; the caller applies the deltas to the bodies once. The
// residual is kept up to date column by column, so the inner loop has no
// dependency chain; N is the point count, fixed per instantiation.
template <uint32_t N>
void sweep_manifold(const float (*k)[kMaxManifoldPoints], const float* mass, const float* vn,
                    const float* bias, float scale, float* impulse, float* delta) {
  float residual[N];
  float step[N];
  float total[N];
  for (uint32_t p = 0; p < N; ++p) {
    residual[p] = vn[p] + bias[p];
    step[p] = mass[p] * scale;
    total[p] = impulse[p];
  }
  const int sweeps = N == 1 ? 1 : kManifoldSweeps;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (uint32_t p = 0; p < N; ++p) {
      float next = total[p] - step[p] * residual[p];
      if (next < 0.0f) next = 0.0f;
      const float change = next - total[p];
      total[p] = next;
      for (uint32_t j = 0; j < N; ++j) residual[j] += k[j][p] * change;
    }
  }
  for (uint32_t p = 0; p < N; ++p) {
    delta[p] = total[p] - impulse[p];
    impulse[p] = total[p];
  }
}

void solve_manifold(uint32_t n, const float (*k)[kMaxManifoldPoints], const float* mass,
                    const float* vn, const float* bias, float scale, float* impulse, float* delta) {
  switch (n) {
    case 1:
      sweep_manifold<1>(k, mass, vn, bias, scale, impulse, delta);
      break;
    case 2:
      sweep_manifold<2>(k, mass, vn, bias, scale, impulse, delta);
      break;
    case 3:
      sweep_manifold<3>(k, mass, vn, bias, scale, impulse, delta);
      break;
    default:
      sweep_manifold<4>(k, mass, vn, bias, scale, impulse, delta);
      break;
  }
}

// Applies normal impulses delta[p] at the manifold's points to a pair of
// velocities (real or push); a side marked fixed is left alone.
void apply_normal_impulses(const ContactConstraint& c, const float* delta, const SolverBody& a,
                           const SolverBody& b, Vec3& va, Vec3& wa, Vec3& vb, Vec3& wb,
                           uint8_t fixed = kPushFixedNone) {
  Vec3 linear{};
  Vec3 torque_a{};
  Vec3 torque_b{};
  for (uint32_t p = 0; p < c.point_count; ++p) {
    const Vec3 impulse = c.normal * delta[p];
    linear += impulse;
    torque_a += cross(c.points[p].anchor_a, impulse);
    torque_b += cross(c.points[p].anchor_b, impulse);
  }
  if (fixed != kPushFixedA) {
    va -= linear * a.inv_mass;
    wa -= a.inv_inertia * torque_a;
  }
  if (fixed != kPushFixedB) {
    vb += linear * b.inv_mass;
    wb += b.inv_inertia * torque_b;
  }
}

// The normal K matrix of a contact whose side `fixed` does not move.
void one_sided_coupling(const ContactConstraint& c, const SolverBody& moving, bool moving_is_b,
                        float (*k)[kMaxManifoldPoints], float* mass) {
  Vec3 rn[kMaxManifoldPoints];
  for (uint32_t i = 0; i < c.point_count; ++i) {
    const Vec3 r = moving_is_b ? c.points[i].anchor_b : c.points[i].anchor_a;
    rn[i] = cross(r, c.normal);
  }
  for (uint32_t i = 0; i < c.point_count; ++i) {
    const Vec3 irn = moving.inv_inertia * rn[i];
    for (uint32_t j = 0; j < c.point_count; ++j) k[i][j] = moving.inv_mass + dot(rn[j], irn);
    mass[i] = k[i][i] > 0.0f ? 1.0f / k[i][i] : 0.0f;
  }
}

// The push-out of the overlaps deeper than kDeepOverlapSlops slops past the
// slop, one contact at a time from the ground up (support_order.cpp): the
// lower body is held, so a column that was built overlapping rises box by
// box instead of compounding its pushes up the column. The shallow
// overlaps are pushed out next, in the lanes (push_batches). Deep overlaps
// are rare, so this pass mostly tests and skips.
void push_out_deep(WorldScratch& scratch, const WorldConfig& config, float inv_h) {
  const float slop = config.linear_slop_m;
  const float push_max = config.contact_push_max_mps;
  const float deep_limit = -kDeepOverlapSlops * slop;
  float vn[kMaxManifoldPoints];
  float bias[kMaxManifoldPoints];
  float mass[kMaxManifoldPoints];
  float impulse[kMaxManifoldPoints];
  float delta[kMaxManifoldPoints];
  float one_sided[kMaxManifoldPoints][kMaxManifoldPoints];
  for (uint32_t index : scratch.push_order) {
    ContactConstraint& c = scratch.constraints[index];
    float deepest = 0.0f;
    for (uint32_t p = 0; p < c.point_count; ++p) {
      const float depth = c.points[p].separation + slop;  // overlap up to the slop is allowed
      if (depth < deepest) deepest = depth;
    }
    if (!(deepest < deep_limit)) continue;
    SolverBody& a = scratch.solver_bodies[c.body_a];
    SolverBody& b = scratch.solver_bodies[c.body_b];
    ContactBatch& batch = scratch.batches[c.batch];
    for (uint32_t p = 0; p < c.point_count; ++p) {
      const ConstraintPoint& cp = c.points[p];
      const float s = cp.separation;
      bias[p] = s > 0.0f ? s * inv_h : 0.0f;
      const float depth = s + slop;
      if (depth < 0.0f) {
        const float push = c.softness.bias_rate * depth;
        bias[p] = push < -push_max ? -push_max : push;
      }
      const Vec3 va = a.push_linear + cross(a.push_angular, cp.anchor_a);
      const Vec3 vb = b.push_linear + cross(b.push_angular, cp.anchor_b);
      vn[p] = dot(vb - va, c.normal);
      mass[p] = cp.normal_mass;
      impulse[p] = batch.points[p].push_impulse[c.lane];
    }
    const float(*k)[kMaxManifoldPoints] = c.coupling;
    const uint8_t fixed = c.push_fixed;
    if (fixed != kPushFixedNone) {
      const bool moving_is_b = fixed == kPushFixedA;
      one_sided_coupling(c, moving_is_b ? b : a, moving_is_b, one_sided, mass);
      k = one_sided;
    }
    solve_manifold(c.point_count, k, mass, vn, bias, c.softness.mass_scale, impulse, delta);
    bool moved = false;
    for (uint32_t p = 0; p < c.point_count; ++p) {
      batch.points[p].push_impulse[c.lane] = impulse[p];
      moved = moved || delta[p] != 0.0f;
    }
    if (!moved) continue;
    apply_normal_impulses(c, delta, a, b, a.push_linear, a.push_angular, b.push_linear,
                          b.push_angular, fixed);
    if (fixed != kPushFixedA && a.inv_mass != 0.0f) a.pushed = 1.0f;
    if (fixed != kPushFixedB && b.inv_mass != 0.0f) b.pushed = 1.0f;
  }
  reset_immovable_push(scratch);
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
      cp.tick_normal_impulse += impulse;
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

// How far from an axis through the centre of mass along `u` (unit, body
// frame) the box of half sizes `half` about that centre reaches: the
// largest |p|^2 - (p.u)^2 over the box, a convex function of p, so taken at
// a corner, where it is |half|^2 less the smallest (p.u)^2 of the corners
// (one of four sign patterns; the other four are their negatives).
float reach_from_axis(Vec3 half, Vec3 u) {
  const float a = half.x * u.x;
  const float b = half.y * u.y;
  const float c = half.z * u.z;
  const float along = std::fmin(std::fmin(std::fabs(a + b + c), std::fabs(a + b - c)),
                                std::fmin(std::fabs(a - b + c), std::fabs(-a + b + c)));
  const float sq = length_squared(half) - along * along;
  return sq > 0.0f ? std::sqrt(sq) : 0.0f;
}

// Sleep timer. A dynamic body rests through each stretch of half
// time_to_sleep_s in which no point of it strays further than
// sleep_threshold_mps times the stretch from where the stretch began (its
// sleep pose): its average speed over the stretch is below the threshold.
// Straying further restarts the count from where it stands; a full
// stretch starts the next one there. Measured by displacement, not by
// each tick's velocity, so a body that trembles in place (a thin limb's
// spin about its own axis flickering on and off, a limb shaking on the
// heap it lies on) or creeps slower than the threshold comes to rest,
// while one that goes somewhere does not; two stretches to sleep keep a
// small pendulum's turning point (slow, but not for long) from passing
// for rest. Kinematic bodies rest only when not driven at all.
//
// A point's move is bounded by the centre's plus the chord the turn sweeps
// at the point's distance from the turn's axis, 2 sin(angle / 2) times
// that distance; the distance is bounded by the extent, and, when that
// bound alone calls the body moving, by the reach of its mass-frame bounds
// from the turn's actual axis: a dumbbell rolling slowly about
// its long axis moves its surface by its bells' radius per radian, not by
// its length.
void update_sleep_timer(const WorldConfig& config, BodyKind kind, float extent, const Shape& shape,
                        const SolverBody& b, float tick, BodySim& sim) {
  const float before = sim.sleep_time;
  if (kind != BodyKind::kDynamic) {
    const bool still = b.linear_velocity == Vec3{} && b.angular_velocity == Vec3{};
    sim.sleep_time = still ? sim.sleep_time + tick : 0.0f;
  } else {
    const float half_time = 0.5f * config.time_to_sleep_s;
    const float stretch = half_time > tick ? half_time : tick;
    const float limit = config.sleep_threshold_mps * stretch;
    // sin(angle / 2) is the length of the turn's vector part, whose
    // direction is the turn's axis in the body frame.
    const Quat turn = conjugate(sim.sleep_rotation) * sim.rotation;
    const Vec3 spin{turn.x, turn.y, turn.z};
    const float moved = length(sim.position - sim.sleep_position);
    const float sin_half = length(spin);
    float strayed = moved + 2.0f * extent * sin_half;
    // Only a body whose centre stayed within the limit can be saved by a
    // tighter bound on its turn (most moving bodies are not).
    if (strayed > limit && moved <= limit && sin_half > 0.0f) {
      const Vec3 half = shape_ops(shape.type).half_bounds(shape, Mat3{});
      const float reach = reach_from_axis(half, spin * (1.0f / sin_half));
      if (reach < extent) strayed = moved + 2.0f * reach * sin_half;
    }
    if (strayed <= limit) {
      sim.sleep_time += tick;
      if (std::floor(sim.sleep_time / stretch) == std::floor(before / stretch)) return;
    } else {
      sim.sleep_time = 0.0f;
    }
  }
  sim.sleep_position = sim.position;
  sim.sleep_rotation = sim.rotation;
}

void finalize(WorldState& state, WorldScratch& scratch, float tick) {
  const WorldConfig& config = state.config;
  for (size_t i = 1; i < scratch.solver_bodies.size(); ++i) {
    SolverBody& b = scratch.solver_bodies[i];
    uint32_t index = scratch.solver_body_ids[i];
    BodySim& sim = state.sims[index];
    const BodySim before = sim;
    sim.position += b.delta_position;
    sim.rotation = normalize(b.delta_rotation * sim.rotation);
    sim.linear_velocity = b.linear_velocity;
    sim.angular_velocity = b.angular_velocity;
    const uint8_t locks = state.infos[index].lock_rotation;
    if (locks != 0) {
      // A locked body turns only about its free axes, with the inertia the
      // solver used: no gyroscopic carry, which would lean it onto a
      // locked axis.
      sim.angular_velocity = without_locked_axes(locks, sim.angular_velocity);
    } else if (state.infos[index].kind == BodyKind::kDynamic && !b.jointed) {
      // (A jointed body keeps the velocity its joints left it: the carry
      // models a free body, and applied after the joints it would undo
      // their motors and, for a body at rest, turn it by noise.)
      const Spin spin = carry_angular_momentum(state.masses[index], before.rotation, sim.rotation,
                                               b.angular_velocity, tick);
      sim.angular_velocity = spin.angular_velocity;
      sim.rotation = spin.rotation;
      // The turn the tick made after the carry's correction: continuous
      // collision sweeps a body from where it started by this turn (read
      // by nothing else after the solve).
      b.delta_rotation = normalize(sim.rotation * conjugate(before.rotation));
    }
    sim.force = {};
    sim.torque = {};
    // Solver bodies are in ascending body index, so events are too.
    if (settle_body(config, before, state.infos[index], sim)) {
      scratch.body_events.push_back(
          {BodyEventType::kLeftBounds, {index, state.infos[index].generation}, sim.position});
      continue;
    }
    update_sleep_timer(config, state.infos[index].kind, state.masses[index].extent,
                       state.infos[index].shape, b, tick, sim);
  }
}

}  // namespace

void solve(WorldState& state, WorldScratch& scratch) {
  const WorldConfig& config = state.config;
  const float tick = config.tick_seconds;
  const float h = tick / static_cast<float>(config.substeps);
  const float inv_h = 1.0f / h;
  prepare(state, scratch, h);
  prepare_joints(state, scratch, h);
  build_batches(scratch);
  const bool joints = !scratch.joint_constraints.empty();
  for (const ContactConstraint& c : scratch.constraints) {
    scratch.solver_bodies[c.body_a].contacted = true;
    scratch.solver_bodies[c.body_b].contacted = true;
  }
  scratch.solver_bodies[0].contacted = false;
  const float slop = config.linear_slop_m;
  scratch.pushing = false;
  bool ordered = false;
  for (int32_t s = 0; s < config.substeps; ++s) {
    integrate_velocities(scratch, h);
    if (joints) warm_start_joints(state, scratch);
    warm_start_batches(scratch);
    if (joints) solve_joints(state, scratch, true);
    solve_batches(scratch, inv_h);
    // The joints again after the contacts, so the velocities the bodies
    // move by hold the joints. A contact sees a limb as a free body: a
    // capsule's long-axis inertia is tiny, so the friction of whatever
    // slides across a forearm rolls it at tens of rad/s where the elbow
    // would turn the whole arm (its hinge locks that roll). Moved by the
    // contacts' velocities, the elbow twisted by up to 0.5 rad within a
    // substep and its projection, clamped, lagged behind. Solved last,
    // the joints (a tree exactly) hand the contacts' impulse on to the
    // bodies they join; the contacts' slop, speculative margin and
    // push-out absorb what this leaves them. (Joints no contact acts on
    // are where the first pass left them.)
    if (joints) solve_joints(state, scratch, true, true);
    // Until some point overlaps past the slop, every push velocity and
    // impulse is zero and a push-out pass would leave them so: resting
    // scenes skip it. Likewise the push-out from the ground up, and the
    // order it needs (a function of this tick's contacts alone, so
    // computing it when first needed gives the order of the tick's start),
    // wait for a deep overlap.
    if (scratch.pushing || scratch.overlapping) {
      scratch.pushing = true;
      if (scratch.deep_overlap) {
        if (!ordered) order_push_out(scratch);
        ordered = true;
        push_out_deep(scratch, config, inv_h);
      }
      push_batches(scratch, config, inv_h);
    }
    integrate_positions(scratch, h);
    scratch.joint_frames_fresh = false;
    // The trees' rows where the bodies now stand, for their relax and
    // projection.
    if (joints) refresh_joint_rows(state, scratch, true);
    if (config.relax_iterations > 0) {
      update_separations_and_relax(scratch, slop, inv_h);
    } else {
      update_separations(scratch, slop);
    }
    // Joints relax at least once, and after the contacts (as above: the
    // velocities the step ends with, and the next substep starts from,
    // hold them): their soft bias must not stay behind as velocity,
    // whatever the contacts do.
    if (joints) solve_joints(state, scratch, false);
    for (int32_t r = 1; r < config.relax_iterations; ++r) {
      solve_batches(scratch, inv_h);
      if (joints) solve_joints(state, scratch, false);
    }
    if (joints) {
      project_joints(state, scratch);
      sum_joint_impulses(scratch);
    }
  }
  unpack_batches(scratch);
  apply_restitution(scratch, config);
  store_impulses(state, scratch);
  if (joints) store_joint_impulses(state, scratch);
  finalize(state, scratch, tick);
}

}  // namespace rwd::sim::d3
