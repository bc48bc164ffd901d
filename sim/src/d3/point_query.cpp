// SPDX-License-Identifier: MIT
// Point and pair queries: the signed distance from a point to a body's
// surface, the body nearest a point, and the manifold of two bodies. To a solid, a point is a
// sphere of radius zero, so the collide table's sphere routines give the answer: the separation is
// the signed distance, the manifold point lies midway between the query point and the surface (so
// the surface point is twice it less the query point), and the normal runs from the point toward
// the body. A mesh or a height field has its own routine (ShapeOps::signed_distance), which knows
// which side of the surface is behind it.
#include <algorithm>
#include <cmath>

#include "d3/body_storage.h"
#include "d3/manifold.h"
#include "d3/pipeline.h"
#include "d3/query_filter.h"
#include "d3/shape_ops.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

// The point's distance to body i, if within `reach` (or inside). A surface
// is measured whatever the reach (its nearest triangle is searched for
// outward from the point, so a reach would save little); the caller
// decides whether it counts.
std::optional<PointHit> point_to_body(const WorldState& state, const GeometryStore& store,
                                      uint32_t i, Vec3 point, float reach) {
  const BodyInfo& info = state.infos[i];
  const BodySim& sim = state.sims[i];
  const d3::ShapeOps& ops = d3::shape_ops(info.shape.type);
  if (ops.signed_distance != nullptr) {
    d3::SurfaceDistance s;
    if (!ops.signed_distance(info.shape, store, sim.position, mat3_from_quat(sim.rotation), point,
                             s)) {
      return std::nullopt;
    }
    return PointHit{BodyId{i, info.generation}, s.distance, s.point, s.normal};
  }
  Shape dot = Shape::make_sphere(0.0f);
  d3::Manifold m;
  d3::collide_shapes(dot, {point, Quat{}, Mat3{}}, info.shape,
                     {sim.position, sim.rotation, mat3_from_quat(sim.rotation)}, reach, m, &store);
  if (m.point_count == 0) return std::nullopt;
  const d3::ManifoldPoint& p = m.points[0];
  return PointHit{BodyId{i, info.generation}, p.separation, p.point * 2.0f - point, -m.normal};
}

}  // namespace

std::optional<PointHit> World3D::signed_distance(BodyId id, Vec3 point) const {
  if (!d3::is_live(state_, id) || !is_finite(point)) return std::nullopt;
  // Far enough to reach any surface of a shape the rule allows.
  const float reach = length(point - state_.sims[id.index].position) + 4.0f * 1000.0f;
  return point_to_body(state_, *geometry_, id.index, point, reach);
}

std::optional<PointHit> World3D::nearest_body(Vec3 point, float max_distance,
                                              const QueryFilter& filter) const {
  if (!is_finite(point) || !std::isfinite(max_distance) || max_distance < 0.0f) {
    return std::nullopt;
  }
  WorldScratch& scratch = *scratch_;
  d3::prepare_queries(state_, scratch);
  std::vector<uint32_t>& candidates = scratch.query_hits;
  candidates.clear();
  const Vec3 r{max_distance, max_distance, max_distance};
  const d3::Aabb box{point - r, point + r};
  const auto collect = [&](uint32_t i) {
    if (d3::query_accepts(state_, filter, i)) candidates.push_back(i);
  };
  scratch.broadphase.query(box, collect);
  std::sort(candidates.begin(), candidates.end());
  std::optional<PointHit> best;
  for (const uint32_t i : candidates) {
    const std::optional<PointHit> hit = point_to_body(state_, *geometry_, i, point, max_distance);
    if (!hit || hit->distance > max_distance) continue;
    // A surface has no inside: it counts when it is within reach on either
    // side, so whether it does never depends on how far the broadphase's
    // bounds reach below it.
    const bool surface = d3::shape_ops(state_.infos[i].shape.type).signed_distance != nullptr;
    if (surface && -hit->distance > max_distance) continue;
    if (!best || hit->distance < best->distance) best = hit;
  }
  return best;
}

std::optional<ContactManifold> World3D::contact_manifold(BodyId a, BodyId b,
                                                         float max_separation) const {
  if (!d3::is_live(state_, a) || !d3::is_live(state_, b) || a == b) return std::nullopt;
  if (!(std::isfinite(max_separation) && max_separation >= 0.0f && max_separation <= 1000.0f)) {
    return std::nullopt;
  }
  const BodyInfo& ia = state_.infos[a.index];
  const BodyInfo& ib = state_.infos[b.index];
  const BodySim& sa = state_.sims[a.index];
  const BodySim& sb = state_.sims[b.index];
  d3::Manifold m;
  d3::collide_shapes(ia.shape, {sa.position, sa.rotation, mat3_from_quat(sa.rotation)}, ib.shape,
                     {sb.position, sb.rotation, mat3_from_quat(sb.rotation)}, max_separation, m,
                     geometry_.get());
  ContactManifold out;
  out.normal = m.normal;
  for (uint32_t p = 0; p < m.point_count; ++p) {
    if (m.points[p].separation > max_separation) continue;
    out.points[out.point_count++] = {m.points[p].point, m.points[p].separation};
  }
  if (out.point_count == 0) return std::nullopt;
  return out;
}

}  // namespace rwd::sim
