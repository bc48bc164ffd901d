// SPDX-License-Identifier: MIT
// Rolling resistance (Material::rolling_resistance), after the solve: for
// each touching solid contact whose materials ask for it (combined by
// maximum), the bodies' relative angular velocity in the contact plane is
// taken out by an angular impulse along it, at most c * N * r: c the
// coefficient, N the normal impulse the solver applied over the tick, r the
// lever from the rolling body's centre of mass to the contact. Spin about
// the normal is left to the game (angular damping), as the seeds specify.
// Contacts in cache order, so the result is a pure function of state. A
// world where no body has rolling resistance skips the stage after one scan
// of its bodies per edit.
#include <cmath>

#include "d3/body_storage.h"
#include "d3/pipeline.h"
#include "d3/state_rules.h"

namespace rwd::sim::d3 {
namespace {

bool any_rolling(const WorldState& state, WorldScratch& scratch) {
  if (scratch.rolling_serial == scratch.edit_serial) return scratch.rolling_any;
  bool any = false;
  for (const BodyInfo& info : state.infos) {
    if (info.alive != 0 && info.material.rolling_resistance > 0.0f) {
      any = true;
      break;
    }
  }
  scratch.rolling_any = any;
  scratch.rolling_serial = scratch.edit_serial;
  return any;
}

void keep_within_rule(Vec3& w, Vec3 change) {
  const Vec3 next = w + change;
  if (is_finite(next) && length_squared(next) <= kMaxSpeed * kMaxSpeed) w = next;
}

}  // namespace

void apply_rolling_resistance(WorldState& state, WorldScratch& scratch) {
  if (!any_rolling(state, scratch)) return;
  // The contacts the tick solved, in record order.
  for (const ContactConstraint& con : scratch.constraints) {
    const ContactRecord& rec = state.contacts[con.record];
    if (rec.touching == 0 || rec.sensor != 0 || rec.point_count == 0) continue;
    const BodyInfo& ia = state.infos[rec.index_a];
    const BodyInfo& ib = state.infos[rec.index_b];
    const float c = ia.material.rolling_resistance > ib.material.rolling_resistance
                        ? ia.material.rolling_resistance
                        : ib.material.rolling_resistance;
    if (c <= 0.0f) continue;
    const bool move_a = is_active(ia) && ia.kind == BodyKind::kDynamic;
    const bool move_b = is_active(ib) && ib.kind == BodyKind::kDynamic;
    if (!move_a && !move_b) continue;
    BodySim& a = state.sims[rec.index_a];
    BodySim& b = state.sims[rec.index_b];
    // The normal impulse over the tick: what the substeps warm-started
    // with, summed (a rolling body's contact lifts off its anchor late in
    // the tick, so the last substep's impulse alone can be zero).
    float normal_impulse = 0.0f;
    Vec3 local;
    for (uint32_t p = 0; p < con.point_count; ++p) {
      normal_impulse += con.points[p].tick_normal_impulse;
    }
    for (uint32_t p = 0; p < rec.point_count; ++p) local += rec.points[p].local_a;
    if (normal_impulse <= 0.0f) continue;
    const Vec3 point =
        a.position + rotate(a.rotation, local * (1.0f / static_cast<float>(rec.point_count)));
    const Vec3 n = rotate(a.rotation, rec.frame_normal);
    const Mat3 inv_a =
        move_a ? lock_inverse_inertia(ia.lock_rotation,
                                      world_inverse_inertia(state.masses[rec.index_a], a.rotation))
               : mat3_zero();
    const Mat3 inv_b =
        move_b ? lock_inverse_inertia(ib.lock_rotation,
                                      world_inverse_inertia(state.masses[rec.index_b], b.rotation))
               : mat3_zero();
    const Vec3 relative = b.angular_velocity - a.angular_velocity;
    const Vec3 rolling = relative - n * dot(relative, n);
    const float speed = length(rolling);
    if (speed < 1e-6f) continue;
    const Vec3 d = rolling * (1.0f / speed);
    const float k = dot(d, inv_a * d) + dot(d, inv_b * d);
    if (k <= 0.0f) continue;
    float lever = 0.0f;
    if (move_a) lever = length(point - a.position);
    if (move_b) {
      const float lb = length(point - b.position);
      if (lb > lever) lever = lb;
    }
    float impulse = speed / k;
    const float limit = c * normal_impulse * lever;
    if (impulse > limit) impulse = limit;
    // The state rule's speed bound holds after the solve; a turn that would
    // break it (a body already at the limit) is not taken.
    if (move_a) keep_within_rule(a.angular_velocity, inv_a * (d * impulse));
    if (move_b) keep_within_rule(b.angular_velocity, -(inv_b * (d * impulse)));
  }
}

}  // namespace rwd::sim::d3
