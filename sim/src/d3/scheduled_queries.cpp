// SPDX-License-Identifier: MIT
// Scheduled queries: rays and overlaps the step runs at a fixed phase.
// The schedule is state (WorldState::queries, in ticket order), so it rolls
// back with the bodies; the answers are per-step output in scratch, like
// the contact events. Each query is the same call the game could make by
// hand (raycast, raycast_all, overlap) at the same moment, so a scheduled
// answer is bit for bit the immediate one; scheduling only fixes when.
#include <algorithm>
#include <optional>
#include <span>
#include <string>

#include "d3/pipeline.h"
#include "d3/shape_ops.h"
#include "d3/state_rules.h"
#include "d3/world_scratch.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

Status invalid(const std::string& what) {
  return Status::Error(ErrorCode::kInvalidArgument, what);
}

Status check_phase_and_repeat(QueryPhase phase, QueryRepeat repeat) {
  if (phase != QueryPhase::kPrePhysics && phase != QueryPhase::kPostPhysics) {
    return invalid("unknown query phase");
  }
  if (repeat != QueryRepeat::kOnce && repeat != QueryRepeat::kEveryStep) {
    return invalid("unknown query repeat");
  }
  return Status::Ok();
}

ScheduledQueryRecord ray_record(ScheduledQueryKind kind, const Ray& ray, const QueryFilter& filter,
                                QueryPhase phase, uint64_t user_tag, QueryRepeat repeat) {
  ScheduledQueryRecord q;
  q.kind = kind;
  q.phase = phase;
  q.repeat = repeat == QueryRepeat::kEveryStep ? 1 : 0;
  q.user_tag = user_tag;
  q.filter = filter;
  q.ray = {quantize(ray.origin), quantize(ray.direction), quantize(ray.max_distance)};
  return q;
}

// Where a ticket is in the schedule (kept in ticket order), or end.
auto find_ticket(const std::vector<ScheduledQueryRecord>& queries, QueryTicket ticket) {
  const auto at =
      std::lower_bound(queries.begin(), queries.end(), ticket.id,
                       [](const ScheduledQueryRecord& q, uint64_t id) { return q.ticket < id; });
  return at != queries.end() && at->ticket == ticket.id && !ticket.is_null() ? at : queries.end();
}

}  // namespace

Result<QueryTicket> World3D::add_scheduled_query(const ScheduledQueryRecord& record) {
  if (state_.queries.size() >= kMaxScheduledQueries) {
    return Status::Error(ErrorCode::kCapacity, "too many scheduled queries (65536 pending)");
  }
  if (state_.last_query_ticket == ~0ull) {
    return Status::Error(ErrorCode::kCapacity, "query tickets exhausted");
  }
  ScheduledQueryRecord q = record;
  q.ticket = state_.last_query_ticket + 1;
  // The rule a snapshot's queries are held to holds for every one made.
  if (Status s = d3::check_query(*geometry_, q, q.ticket, nullptr); !s.ok()) return s;
  state_.last_query_ticket = q.ticket;
  state_.queries.push_back(q);
  return QueryTicket{q.ticket};
}

Result<QueryTicket> World3D::schedule_raycast(const Ray& ray, const QueryFilter& filter,
                                              QueryPhase phase, uint64_t user_tag,
                                              QueryRepeat repeat) {
  if (Status s = check_phase_and_repeat(phase, repeat); !s.ok()) return s;
  if (Status s = d3::check_query_ray(ray); !s.ok()) return s;
  return add_scheduled_query(
      ray_record(ScheduledQueryKind::kRaycast, ray, filter, phase, user_tag, repeat));
}

Result<QueryTicket> World3D::schedule_raycast_all(const Ray& ray, const QueryFilter& filter,
                                                  QueryPhase phase, uint64_t user_tag,
                                                  QueryRepeat repeat) {
  if (Status s = check_phase_and_repeat(phase, repeat); !s.ok()) return s;
  if (Status s = d3::check_query_ray(ray); !s.ok()) return s;
  return add_scheduled_query(
      ray_record(ScheduledQueryKind::kRaycastAll, ray, filter, phase, user_tag, repeat));
}

Result<QueryTicket> World3D::schedule_overlap(const Shape& shape, Vec3 position, Quat rotation,
                                              const QueryFilter& filter, QueryPhase phase,
                                              uint64_t user_tag, QueryRepeat repeat) {
  if (Status s = check_phase_and_repeat(phase, repeat); !s.ok()) return s;
  const GeometryStore& store = *geometry_;
  if (Status s = d3::check_shape(shape, store); !s.ok()) return s;
  if (Status s = d3::check_query_pose(position, rotation); !s.ok()) return s;
  ScheduledQueryRecord q;
  q.kind = ScheduledQueryKind::kOverlap;
  q.phase = phase;
  q.repeat = repeat == QueryRepeat::kEveryStep ? 1 : 0;
  q.user_tag = user_tag;
  q.filter = filter;
  // On the grid as a body's shape and pose are (create_body).
  q.shape = shape;
  q.shape.radius = quantize(shape.radius);
  q.shape.half_extents = quantize(shape.half_extents);
  q.shape.half_height = quantize(shape.half_height);
  d3::shape_ops(q.shape.type).canonical(q.shape, store);
  q.position = quantize(position);
  const Quat r = normalize(rotation);
  q.rotation = {quantize(r.x), quantize(r.y), quantize(r.z), quantize(r.w)};
  // Quantizing can round a tiny size to zero.
  if (!d3::check_shape(q.shape, store).ok()) {
    return invalid("shape leaves the valid range on the canonical grid");
  }
  return add_scheduled_query(q);
}

Status World3D::cancel_query(QueryTicket ticket) {
  const auto at = find_ticket(state_.queries, ticket);
  if (at == state_.queries.end()) {
    return Status::Error(ErrorCode::kNotFound, "unknown, finished or cancelled query ticket");
  }
  state_.queries.erase(at);
  return Status::Ok();
}

bool World3D::is_scheduled(QueryTicket ticket) const {
  return find_ticket(state_.queries, ticket) != state_.queries.end();
}

uint32_t World3D::scheduled_query_count() const {
  return static_cast<uint32_t>(state_.queries.size());
}

std::span<const ScheduledQueryResult> World3D::step_queries() const {
  return scratch_->query_results;
}

void World3D::clear_step_queries() {
  WorldScratch& s = *scratch_;
  s.query_results.clear();
  s.query_first.clear();
  s.query_count.clear();
  s.query_ray_hits.clear();
  s.query_bodies.clear();
}

void World3D::run_scheduled_queries(QueryPhase phase) {
  WorldScratch& s = *scratch_;
  const std::vector<ScheduledQueryRecord>& queries = state_.queries;
  // One result per pending query, in its order, whichever phase fills it.
  s.query_results.resize(queries.size());
  s.query_first.resize(queries.size(), 0);
  s.query_count.resize(queries.size(), 0);
  for (size_t k = 0; k < queries.size(); ++k) {
    const ScheduledQueryRecord& q = queries[k];
    if (q.phase != phase) continue;
    ScheduledQueryResult& result = s.query_results[k];
    result = ScheduledQueryResult{};
    result.ticket = {q.ticket};
    result.user_tag = q.user_tag;
    result.kind = q.kind;
    result.phase = q.phase;
    switch (q.kind) {
      case ScheduledQueryKind::kRaycast: {
        s.query_first[k] = static_cast<uint32_t>(s.query_ray_hits.size());
        const std::optional<RayHit> hit = raycast(q.ray, q.filter);
        if (hit) s.query_ray_hits.push_back(*hit);
        s.query_count[k] = hit ? 1 : 0;
        break;
      }
      case ScheduledQueryKind::kRaycastAll:
        raycast_all(q.ray, q.filter, s.query_ray_scratch);
        s.query_first[k] = static_cast<uint32_t>(s.query_ray_hits.size());
        s.query_count[k] = static_cast<uint32_t>(s.query_ray_scratch.size());
        s.query_ray_hits.insert(s.query_ray_hits.end(), s.query_ray_scratch.begin(),
                                s.query_ray_scratch.end());
        break;
      case ScheduledQueryKind::kOverlap:
        // The schedule held it to the same rule, so it cannot be refused
        // here; were it, the answer is empty.
        (void)overlap(q.shape, q.position, q.rotation, q.filter, s.query_body_scratch);
        s.query_first[k] = static_cast<uint32_t>(s.query_bodies.size());
        s.query_count[k] = static_cast<uint32_t>(s.query_body_scratch.size());
        s.query_bodies.insert(s.query_bodies.end(), s.query_body_scratch.begin(),
                              s.query_body_scratch.end());
        break;
    }
  }
}

void World3D::finish_scheduled_queries() {
  WorldScratch& s = *scratch_;
  // The hit buffers are complete now, so spans into them stay put.
  for (size_t k = 0; k < s.query_results.size(); ++k) {
    ScheduledQueryResult& result = s.query_results[k];
    const std::span<const RayHit> rays = s.query_ray_hits;
    const std::span<const BodyId> bodies = s.query_bodies;
    if (result.kind == ScheduledQueryKind::kOverlap) {
      result.bodies = bodies.subspan(s.query_first[k], s.query_count[k]);
    } else {
      result.ray_hits = rays.subspan(s.query_first[k], s.query_count[k]);
    }
  }
  std::vector<ScheduledQueryRecord>& queries = state_.queries;
  queries.erase(std::remove_if(queries.begin(), queries.end(),
                               [](const ScheduledQueryRecord& q) { return q.repeat == 0; }),
                queries.end());
}

}  // namespace rwd::sim
