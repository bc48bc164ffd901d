// SPDX-License-Identifier: MIT
#pragma once
// The angular parts (joint_angular.cpp) of the point joints packed into
// lane batches (joint_point_batches.h), solved in the same lanes as their
// points: refreshed with their points (against the point's inverse mass
// just made) and warm-started with them; their passes and the hinges'
// projection run over the batches before the joints' structure, as the
// scalar path orders them (the angular parts before the points; see
// joint_point_batches.h for why not batch by batch). The maths is
// joint_angular.cpp's, each row against the point held rigid, written
// once for kLanes lanes (joint_angular_lanes.h).
//
// A batch holds joints of one kind only (PointBatch::kind): bare points,
// ball joints with an angular part, or hinges; the angular parts' data
// lives in a structure of arrays per kind, indexed from the PointBatch, so
// a batch of bare points (a grid of balls) stays as small as it was.
// Lanes differ only in their flags (limit, motor, spring), which are
// masks: every lane computes every row and keeps what its flags select.
// The limits' masses and responses are made at each refresh, for every
// lane (lazily, as the scalar path does, would need a branch per lane).
#include <cstdint>

#include "d3/wide_float.h"

namespace rwd::sim {
class WorldScratch;
struct JointRecord;
}  // namespace rwd::sim

namespace rwd::sim::d3 {

struct JointConstraint;

/// What a PointBatch's lanes are.
enum : uint8_t { kPointBare = 0, kPointBall = 1, kPointHinge = 2 };

/// A turn's response in lanes (TurnResponse, joint_solver.h): A's linear
/// and angular velocity, B's, per unit turn impulse.
struct alignas(16) LaneResponse {
  float r[12][kLanes];
};

/// Ball joints' angular parts: the cone-twist limit (slots: cone, twist
/// lower, twist upper) and the angular motor.
struct alignas(16) BallPartBatch {
  BallPartBatch() {}  // NOLINT(modernize-use-equals-default): every field is set before it is read
  // Packed once a tick.
  alignas(16) float frame_a[4][kLanes];  ///< the joint's frames at the tick's start (x, y, z, w)
  alignas(16) float frame_b[4][kLanes];
  alignas(16) float limit_on[kLanes];  ///< 1: limited
  alignas(16) float motor_on[kLanes];  ///< 1: motor
  alignas(16) float cone_angle[kLanes];
  alignas(16) float twist_lower[kLanes];
  alignas(16) float twist_upper[kLanes];
  alignas(16) float motor_velocity[3][kLanes];
  alignas(16) float max_motor[kLanes];  ///< its torque times the substep
  alignas(16) float motor_impulse[3][kLanes];
  alignas(16) float limit_impulse[3][kLanes];  ///< cone, lower, upper
  // At the refresh: each slot's row (the cone's; the twist's, lower, its
  // negation the upper's), whether it is there, its gap.
  alignas(16) float cone_row[3][kLanes];
  alignas(16) float twist_row[3][kLanes];
  alignas(16) float slot_on[3][kLanes];
  alignas(16) float gap[3][kLanes];
  alignas(16) float cone_mass[kLanes];
  alignas(16) float twist_mass[kLanes];
  LaneResponse cone_response;
  LaneResponse twist_response;
  bool any_motor = false;
  bool any_limit = false;
  /// The motor's inverse 3 x 3 against the point (columns) and the
  /// responses of the turns about the world axes.
  alignas(16) float motor_inv[9][kLanes];
  LaneResponse motor_response[3];
};

/// Hinges' angular parts: the two turns off the axis, and the spring,
/// motor and limits about it.
struct alignas(16) HingePartBatch {
  HingePartBatch() {}  // NOLINT(modernize-use-equals-default): every field is set before it is read
  // Packed once a tick.
  alignas(16) float frame_a[4][kLanes];
  alignas(16) float frame_b[4][kLanes];
  alignas(16) float limit_on[kLanes];
  alignas(16) float motor_on[kLanes];
  alignas(16) float spring_on[kLanes];
  alignas(16) float spring_soft[3][kLanes];  ///< bias rate, mass scale, impulse scale
  alignas(16) float spring_target[kLanes];
  alignas(16) float motor_speed[kLanes];
  alignas(16) float max_motor[kLanes];  ///< its torque times the substep
  alignas(16) float lower[kLanes];
  alignas(16) float upper[kLanes];
  alignas(16) float spring_impulse[kLanes];
  alignas(16) float motor_impulse[kLanes];
  alignas(16) float limit_impulse[2][kLanes];  ///< lower, upper
  /// The two turns' impulse as a vector (JointConstraint::angular_impulse),
  /// made from align_impulse at the end of each substep.
  alignas(16) float angular_impulse[3][kLanes];
  alignas(16) float tick_angular[3][kLanes];  ///< summed over the tick's substeps
  // At the refresh.
  alignas(16) float axis[3][kLanes];
  alignas(16) float angle[kLanes];
  alignas(16) float align_axis[2][3][kLanes];
  alignas(16) float align_error[2][kLanes];
  alignas(16) float align_impulse[2][kLanes];
  alignas(16) float align_inv[3][kLanes];  ///< xx, xy, yy
  alignas(16) float axial_mass[kLanes];
  LaneResponse align_response[2];
  LaneResponse axial_response;
};

/// Packs joint `c` (record `j`) into `lane` of a part batch, and an empty
/// lane (no joint: flags off, identity frames, zero impulses).
void pack_ball_lane(BallPartBatch& p, int lane, const JointRecord& j, const JointConstraint& c);
void pack_hinge_lane(HingePartBatch& p, int lane, const JointRecord& j, const JointConstraint& c);
void clear_ball_lane(BallPartBatch& p, int lane);
void clear_hinge_lane(HingePartBatch& p, int lane);
/// Writes a lane's impulses (and, for a hinge, its angular impulse and its
/// sum over the tick) back to its joint.
void store_ball_lane(const BallPartBatch& p, int lane, JointConstraint& c);
void store_hinge_lane(const HingePartBatch& p, int lane, JointConstraint& c);
/// A hinge batch's angular impulses from its turns' impulses, added to
/// their sums over the tick (once a substep, after its last pass).
void sum_hinge_part(HingePartBatch& p);

}  // namespace rwd::sim::d3
