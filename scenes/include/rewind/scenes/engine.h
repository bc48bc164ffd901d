// SPDX-License-Identifier: MIT
#pragma once
// The seam between a scene and a physics engine. A scene describes its
// bodies in SI units (BodySpec), drives the world through this interface and
// reads body states back, so the same scene code runs on Rewind and on peer
// engines (bench/ only) and their results can be compared.
#include <cstdint>
#include <span>
#include <string>

#include "rewind/sim/body.h"
#include "rewind/sim/geometry.h"
#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"

namespace rwd::scenes {

using sim::BodyKind;
using sim::Quat;
using sim::Shape;
using sim::Vec3;

/// One body of a scene, engine-neutral, in SI units.
struct BodySpec {
  BodyKind kind = BodyKind::kDynamic;
  Shape shape = Shape::make_box({0.5f, 0.5f, 0.5f});
  Vec3 position;            ///< m, of the shape's centre (a hull's: the origin of its points)
  Quat rotation;            ///< unit quaternion
  Vec3 linear_velocity;     ///< m/s
  Vec3 angular_velocity;    ///< rad/s, world frame
  float density = 1000.0f;  ///< kg/m^3 (dynamic bodies)
  /// Coulomb coefficient of this surface. Two surfaces combine by geometric
  /// mean (Rewind's rule); adapters of engines with another rule map to it.
  float friction = 0.6f;
  /// Bounce of this surface; two surfaces combine by maximum (Rewind's rule).
  float restitution = 0.0f;
  /// Coefficient of rolling resistance, [0, 1] (Material::rolling_resistance).
  float rolling_resistance = 0.0f;
  /// Exponential decay rates, 1/s: without contacts v(t) = v0 exp(-c t).
  float linear_damping = 0.0f;
  float angular_damping = 0.0f;
  /// A fast projectile: the engine's continuous collision is on for this
  /// body (Rewind: BodyDef::continuous, on top of its speculative contacts;
  /// Bullet: its swept-sphere CCD).
  bool continuous = false;
};

/// The world a scene runs in.
struct WorldSpec {
  Vec3 gravity{0.0f, -9.81f, 0.0f};   ///< m/s^2
  float tick_seconds = 1.0f / 60.0f;  ///< one step()
  /// The region the scene's bodies stay in; bodies leaving it count as
  /// lost (engines with world bounds use it as theirs).
  Vec3 bounds_lower{-5000.0f, -5000.0f, -5000.0f};
  Vec3 bounds_upper{5000.0f, 5000.0f, 5000.0f};
};

/// A body of the engine's current world, numbered 0, 1, 2... in creation order.
using BodyHandle = uint32_t;

/// A physics engine as a scene sees it. Not thread-safe; one world at a time.
class Engine {
 public:
  virtual ~Engine() = default;

  /// Short engine name for tables: "rewind", "bullet".
  virtual std::string name() const = 0;
  /// The solver settings in force, as "key=value" pairs separated by spaces.
  virtual std::string settings() const = 0;

  /// Discards the current world and starts an empty one. `body_capacity` is
  /// how many bodies the scene will create.
  virtual void reset(const WorldSpec& world, uint32_t body_capacity) = 0;
  /// Registers a convex hull whose corners are `points` (m, in the frame
  /// bodies of it are placed by) for this world; bodies use it through
  /// Shape::make_hull(out). Bodies of a hull turn about its centre of mass
  /// and report the pose of the frame its points were given in. False
  /// (with a reason in `error`) if the engine refuses the points.
  virtual bool add_hull(std::span<const Vec3> points, sim::GeometryId& out, std::string& error) = 0;
  /// Registers a compound of spheres, boxes, capsules and hulls registered
  /// before it, each placed by its own pose (Shape::make_compound(out));
  /// bodies of it turn about its centre of mass (mass by child volume) and
  /// report the pose of the frame the children were placed in.
  virtual bool add_compound(std::span<const sim::CompoundChild> children, sim::GeometryId& out,
                            std::string& error) = 0;
  /// Registers a triangle mesh (`vertices` in m, three `indices` per
  /// triangle, counter-clockwise seen from the front) for static bodies
  /// (Shape::make_mesh(out)).
  virtual bool add_mesh(std::span<const Vec3> vertices, std::span<const uint32_t> indices,
                        sim::GeometryId& out, std::string& error) = 0;
  /// Registers a height field for static bodies
  /// (Shape::make_height_field(out)): `rows` x `cols` samples, row-major;
  /// sample (r, c) at (c * scale.x, height * scale.y, r * scale.z) from the
  /// body's position.
  virtual bool add_height_field(uint32_t rows, uint32_t cols, Vec3 scale,
                                std::span<const float> heights, sim::GeometryId& out,
                                std::string& error) = 0;
  /// Adds a body; false (with a reason in `error`) if the engine refuses it.
  virtual bool add_body(const BodySpec& spec, BodyHandle& out, std::string& error) = 0;
  /// Advances the world by one tick.
  virtual void step() = 0;

  virtual Vec3 position(BodyHandle body) const = 0;
  virtual Quat rotation(BodyHandle body) const = 0;
  virtual Vec3 linear_velocity(BodyHandle body) const = 0;
  virtual Vec3 angular_velocity(BodyHandle body) const = 0;
  /// False once the engine has taken the body out of the simulation (left
  /// the world bounds).
  virtual bool enabled(BodyHandle body) const = 0;

  /// Applies an impulse (N*s) at a world point of a dynamic body.
  virtual void apply_impulse(BodyHandle body, Vec3 impulse_ns, Vec3 world_point) = 0;
  /// Sets both velocities of a dynamic body (and wakes it).
  virtual void set_velocity(BodyHandle body, Vec3 linear_mps, Vec3 angular_radps) = 0;
  /// Number of dynamic bodies that are awake.
  virtual uint32_t awake_count() const = 0;
};

}  // namespace rwd::scenes
