// SPDX-License-Identifier: MIT
#pragma once
// What the 2D world's read-only queries take and give back (World2D's
// raycast, raycast_all, query_aabb, overlap, shape_cast, nearest_body and
// signed_distance). Values are Q16.16 (Fx) in metres; the queries work in
// Q32.32 inside and round once when they hand a value back, so a query
// gives the same bits on every machine. A query never changes the world.
#include <cstdint>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/vec2.h"
#include "rewind/sim2d/body2d.h"

namespace rwd::sim2d {

/// Which bodies a query may find. Disabled bodies are never found.
struct QueryFilter2D {
  /// A body is found only when (body layer & layer_mask) != 0.
  uint32_t layer_mask = 0xFFFFFFFFu;
  /// Sensors (triggers) are skipped unless asked for.
  bool include_sensors = false;
  /// Triggers (BodyDef2D::trigger) are skipped unless asked for.
  bool include_triggers = false;
  /// Skipped bodies by kind: the character controller, for one, ignores
  /// dynamic bodies when it is told to.
  bool include_static = true;
  bool include_kinematic = true;
  bool include_dynamic = true;
  /// One body to skip (the caller's own body); the null id skips none.
  BodyId2D ignore;
};

/// Where a ray first enters a body's shape.
struct RayHit2D {
  BodyId2D body;
  Vec2 point;   ///< m, on the surface
  Vec2 normal;  ///< unit surface normal there, facing the ray's origin side
  /// Position along the ray in [0, 1] of its translation (0 = origin).
  Fx fraction;
  Fx distance;  ///< m from the origin, fraction x |translation|
};

/// Where a moving shape first touches a body.
struct ShapeHit2D {
  BodyId2D body;
  Vec2 point;   ///< m, on the hit body's surface
  Vec2 normal;  ///< unit, out of the hit body toward the moving shape
  /// In [0, 1]: the moving shape stops at position + fraction x translation.
  Fx fraction;
};

/// The body nearest a point and how far its surface is (m, >= 0; 0 when
/// the point is inside it).
struct NearestBody2D {
  BodyId2D body;
  Fx distance;
  Vec2 point;  ///< m, the nearest point of its surface (the point itself when inside)
};

}  // namespace rwd::sim2d
