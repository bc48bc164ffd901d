// SPDX-License-Identifier: MIT
#pragma once
// Queries attached to the step (World3D::schedule_raycast and friends):
// each runs inside step() at a fixed phase, before the step's stages or
// after them, and its answer comes out with the step's other results
// (World3D::step_queries), so a query's timing relative to integration is
// the same on every machine and in every replay.
#include <cstdint>
#include <span>

#include "rewind/sim/body.h"
#include "rewind/sim/query.h"
#include "rewind/sim/shape.h"

namespace rwd::sim {

/// When in the step a scheduled query runs.
enum class QueryPhase : uint8_t {
  kPrePhysics = 0,   ///< before the step's stages: the world as the step finds it
  kPostPhysics = 1,  ///< after them: the world as the step leaves it
};

/// How long a schedule lasts.
enum class QueryRepeat : uint8_t {
  kOnce = 0,       ///< runs in the next step only, then is gone
  kEveryStep = 1,  ///< runs in every step until World3D::cancel_query()
};

/// What a scheduled query asks.
enum class ScheduledQueryKind : uint8_t {
  kRaycast = 0,     ///< the closest hit along a ray (none or one)
  kRaycastAll = 1,  ///< every hit along a ray, near to far (ties by index)
  kOverlap = 2,     ///< every body a placed shape overlaps or touches, in index order
};

/// Handle to a scheduled query. Ids count up from 1 in scheduling order
/// and are never reused; 0 is the null ticket.
struct QueryTicket {
  uint64_t id = 0;
  bool is_null() const { return id == 0; }
  friend bool operator==(QueryTicket, QueryTicket) = default;
};

/// One scheduled query's answer in the last step (World3D::step_queries).
/// The spans point into the world's per-step buffers: valid until the next
/// step(), restore() or deserialize().
struct ScheduledQueryResult {
  QueryTicket ticket;
  uint64_t user_tag = 0;  ///< as given when scheduling
  ScheduledQueryKind kind = ScheduledQueryKind::kRaycast;
  QueryPhase phase = QueryPhase::kPrePhysics;
  std::span<const RayHit> ray_hits;  ///< rays: the hits (kRaycast: at most one)
  std::span<const BodyId> bodies;    ///< overlaps: the bodies, in index order
};

}  // namespace rwd::sim
