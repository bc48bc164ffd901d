// SPDX-License-Identifier: MIT
#pragma once
// A static level of boxes in Jolt Physics and the four scene queries
// rewind_query_bench times (closest ray, every hit along a ray, shape cast,
// sphere overlap), for the Jolt rows beside Rewind's and Bullet's. Built
// with rewind_jolt_engine (REWIND_JOLT_DIR); Jolt's headers stay in the .cpp.
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"
#include "rewind/sim/world3d.h"

namespace rwd::bench {

/// One static box of the level, as Rewind kept it.
struct JoltLevelBox {
  sim::Vec3 position;
  sim::Quat rotation;
  sim::Vec3 half_extents;
};

/// The level's boxes as Rewind kept them (quantized on creation), in the
/// order of `body_of_box`.
inline std::vector<JoltLevelBox> kept_boxes(const sim::World3D& world,
                                            const std::vector<sim::BodyId>& body_of_box) {
  std::vector<JoltLevelBox> boxes;
  for (sim::BodyId id : body_of_box) {
    boxes.push_back({world.position(id), world.rotation(id), world.shape(id)->half_extents});
  }
  return boxes;
}

/// A query's answer: the level box's number (its place in the boxes given)
/// and metres along the ray or sweep.
struct JoltLevelHit {
  int box = -1;
  float distance = 0.0f;
};

class JoltQueryLevel {
 public:
  /// The boxes at Jolt's defaults (BoxShape, 5 cm convex radius inside the
  /// half extents: rays and casts see the sharp box), broadphase optimised
  /// once after loading, as Jolt advises.
  explicit JoltQueryLevel(std::span<const JoltLevelBox> boxes);
  ~JoltQueryLevel();
  JoltQueryLevel(const JoltQueryLevel&) = delete;
  JoltQueryLevel& operator=(const JoltQueryLevel&) = delete;

  /// NarrowPhaseQuery::CastRay, closest hit.
  std::optional<JoltLevelHit> closest(sim::Vec3 origin, sim::Vec3 direction, float length) const;
  /// CastRay with an all-hits collector (unsorted), reused from ray to ray.
  size_t all(sim::Vec3 origin, sim::Vec3 direction, float length, std::vector<JoltLevelHit>& out);
  /// CastShape, closest hit, of a sphere or box (Jolt's default shape-cast
  /// settings: the full shape, not shrunk by its convex radius).
  std::optional<JoltLevelHit> cast(const sim::Shape& shape, sim::Vec3 origin, sim::Quat rotation,
                                   sim::Vec3 translation);
  /// CollideShape of a sphere: the boxes it touches or overlaps (Jolt's
  /// default maximum separation, 0), in no order.
  size_t overlap(sim::Vec3 centre, float radius, std::vector<int>& out);

 private:
  struct World;
  std::unique_ptr<World> world_;
};

}  // namespace rwd::bench
