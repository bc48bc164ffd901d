// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/sim/body.h"

namespace rwd::sim {

/// Which bodies a query may report.
struct QueryFilter {
  uint32_t layer_mask = 0xFFFFFFFFu;  ///< body.layer & layer_mask must be non-zero
  bool include_sensors = false;
  /// Bodies by kind: a character or a vehicle may look for the level
  /// alone (static only), or skip what it could push (dynamic).
  bool include_static = true;
  bool include_kinematic = true;
  bool include_dynamic = true;
  /// One body to skip (the caller's own body: a chassis, a character's
  /// capsule); the null id skips none.
  BodyId ignore;
};

/// A ray from `origin` along `direction` (normalized by the query; a zero
/// direction is an invalid argument) up to `max_distance` metres.
struct Ray {
  Vec3 origin;
  Vec3 direction{0.0f, -1.0f, 0.0f};
  float max_distance = 1000.0f;
};

struct RayHit {
  BodyId body;
  float distance = 0.0f;  ///< metres along the normalized direction
  Vec3 point;             ///< world position of the hit
  Vec3 normal;            ///< outward surface normal at the hit
};

/// Where a swept shape first touches a body (World3D::shape_cast).
struct ShapeCastHit {
  BodyId body;
  /// Metres the shape travels along the translation before it touches;
  /// 0 when it starts touching or overlapping the body.
  float distance = 0.0f;
  Vec3 point;   ///< world, the contact point on the body's surface then
  Vec3 normal;  ///< unit, the body's surface normal there (toward the swept shape)
};

/// Where two bodies touch, as the narrowphase sees them: one normal and up
/// to four points (World3D::contact_manifold).
struct ContactManifold {
  static constexpr uint32_t kMaxPoints = 4;
  struct Point {
    Vec3 position;     ///< world, midway between the two surfaces
    float separation;  ///< metres, negative where the bodies overlap
  };
  Vec3 normal;  ///< unit, from the first body toward the second
  uint32_t point_count = 0;
  Point points[kMaxPoints];
};

/// The nearest surface point of a body to a query point.
struct PointHit {
  BodyId body;
  float distance = 0.0f;  ///< metres to the surface; negative inside the body (behind a
                          ///< mesh, under a height field: World3D::signed_distance)
  Vec3 point;             ///< the nearest point on the body's surface
  Vec3 normal;            ///< the surface's outward normal there
};

}  // namespace rwd::sim
