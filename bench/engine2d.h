// SPDX-License-Identifier: MIT
#pragma once
// What the 2D benchmarks need of an engine: build a Scene2D, step it, read
// poses back. Rewind's 2D lane and Box2D 2.4 each implement it, so every
// scene is built from one description on both.
#include <cstdint>
#include <string>

#include "scene2d.h"

namespace rwd::bench {

/// A body pose in metres and radians (floating point: measurement only).
struct Pose2D {
  double x = 0;
  double y = 0;
  double angle = 0;
};

class Engine2D {
 public:
  virtual ~Engine2D() = default;
  virtual std::string name() const = 0;
  /// The solver settings, e.g. "substeps=4 relax=1".
  virtual std::string settings() const = 0;
  virtual bool is_default() const = 0;
  /// Replaces the world by the scene's bodies; false with `error` set when
  /// the engine refuses one.
  virtual bool build(const Scene2D& scene, std::string& error) = 0;
  /// Adds scene.waves[wave]'s bodies and joints; false with `error` set
  /// when the engine refuses one.
  virtual bool add_wave(const Scene2D& scene, uint32_t wave, std::string& error) = 0;
  /// Destroys the bodies (and with them the joints) that wave `wave` added.
  virtual void remove_wave(uint32_t wave) = 0;
  /// One 60 Hz tick.
  virtual void step() = 0;
  /// The pose of the scene's body `index` (its origin, as described).
  virtual Pose2D pose(uint32_t index) const = 0;
  /// The pose of body `index` of scene.waves[wave], while it is in the
  /// world.
  virtual Pose2D wave_pose(uint32_t wave, uint32_t index) const = 0;
  /// The engine's own checksum of its world state (Rewind's; 0 for an
  /// engine without one): identical figures prove a change kept results.
  virtual uint64_t checksum() const { return 0; }
  /// The closest hit of the ray from (x0, y0) to (x1, y1): true with the
  /// fraction of the way along it, false when it hits nothing.
  virtual bool raycast(double x0, double y0, double x1, double y1, double& fraction) const = 0;
};

}  // namespace rwd::bench
