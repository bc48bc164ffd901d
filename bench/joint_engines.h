// SPDX-License-Identifier: MIT
#pragma once
// The jointed scenes of rewind/scenes/joint_scenes.h on Rewind and on
// Bullet 3 behind one small interface, so one runner steps both in turns
// and measures them alike (anchor openings, chain stretch, pendulum
// period, energy) from the poses each engine reports.
//
// How a description becomes Bullet (3.24, float, Debian's libbullet-dev):
// - spheres, boxes and capsules (btCapsuleShape: along y like Rewind's,
//   its height the distance between the cap centres) of the same size,
//   mass and principal inertia (set from the description, so both engines
//   carry the same numbers), friction and angular damping (Bullet's
//   damping multiplies by (1 - d)^dt a step, Rewind's divides by 1 + d h:
//   the same to first order). Friction combines differently: Bullet
//   multiplies two bodies' coefficients, Rewind takes their geometric mean;
// - a ball joint is a btPoint2PointConstraint, a hinge a btHingeConstraint
//   (pivot and axis in each body's frame; a joint to the world uses the
//   one-body constructors); a hinge's friction torque T is its angular
//   motor at zero speed with a largest impulse of T dt;
// - a joint with limits is built on frames made as Rewind makes them (A's
//   on axis_a, B's that frame swung onto axis_b at the starting poses, so
//   angles count from there): a ball joint becomes a btConeTwistConstraint
//   (both swing spans the cone's half angle; Bullet's twist limit is
//   symmetric, so B's frame is turned by the middle of the twist range and
//   the span is half of it), a hinge a btHingeConstraint whose limit is
//   Rewind's negated ([lower, upper] is Bullet's [-upper, -lower]: Bullet
//   counts the angle the other way);
// - joined bodies do not collide (addConstraint's second argument), nor
//   bodies of one collision group (an overlap filter on their user index;
//   Rewind: layer and mask bits);
// - one step of 1/60 s per tick (stepSimulation(dt, 1, dt)), the sequential
//   impulse solver with m_numIterations iterations (10, Bullet's default,
//   or more), its default joint ERP (0.2) and CFM (0);
// - sleeping off in both engines, so both simulate every body every tick.
#include <memory>
#include <string>
#include <vector>

#include "rewind/scenes/joint_scenes.h"

namespace rwd::bench {

class JointEngine {
 public:
  virtual ~JointEngine() = default;
  virtual std::string name() const = 0;      ///< "rewind" or "bullet"
  virtual std::string settings() const = 0;  ///< "substeps=4", "iterations=10"
  virtual bool is_default() const = 0;       ///< the engine's default settings
  /// Builds `scene` (replacing what was built before); false with `error`
  /// when the engine refuses it.
  virtual bool build(const scenes::JointScene& scene, std::string& error) = 0;
  virtual void step() = 0;
  /// Every body's pose and velocities, in the scene's body order.
  virtual void states(std::vector<scenes::JointBodyState>& out) const = 0;
};

/// Rewind at `substeps` (relax 1, sleeping off).
std::unique_ptr<JointEngine> make_rewind_joint_engine(int substeps);
/// Bullet with `iterations` solver iterations (sleeping off).
std::unique_ptr<JointEngine> make_bullet_joint_engine(int iterations);

}  // namespace rwd::bench
