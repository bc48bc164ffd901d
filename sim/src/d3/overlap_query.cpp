// SPDX-License-Identifier: MIT
// Overlap queries: which bodies a shape placed in the world overlaps or
// touches. The broadphase (broadphase.h) gives the bodies whose bounds
// meet the shape's; each is tested with the collide table at zero
// speculative distance (a point at separation <= 0 is an overlap), and the
// result is in index order, whatever the trees' shapes.
#include <algorithm>

#include "d3/body_storage.h"
#include "d3/manifold.h"
#include "d3/mass_frame.h"
#include "d3/pipeline.h"
#include "d3/query_filter.h"
#include "d3/shape_ops.h"
#include "d3/state_rules.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {

Status World3D::overlap(const Shape& shape, Vec3 position, Quat rotation, const QueryFilter& filter,
                        std::vector<BodyId>& out) const {
  out.clear();
  const GeometryStore& store = *geometry_;
  if (Status s = d3::check_shape(shape, store); !s.ok()) return s;
  if (!is_finite(position) || !is_finite(rotation)) {
    return Status::Error(ErrorCode::kInvalidArgument, "position and rotation must be finite");
  }
  const Quat q = normalize(rotation);
  if (q == Quat{} && !(rotation == Quat{})) {
    return Status::Error(ErrorCode::kInvalidArgument, "rotation must not be zero");
  }
  Shape query = shape;
  d3::shape_ops(query.type).canonical(query, store);
  // The pose given is the shape's authored frame; the shapes collide in
  // their mass frames.
  d3::ShapePose pose;
  d3::authored_to_mass(d3::mass_frame(query, store), position, q, pose.position, pose.rotation);
  pose.axes = mat3_from_quat(pose.rotation);
  const d3::Aabb box = d3::shape_aabb(query, pose.position, pose.axes);

  WorldScratch& scratch = *scratch_;
  d3::prepare_queries(state_, scratch);
  std::vector<uint32_t>& candidates = scratch.query_hits;
  candidates.clear();
  const auto collect = [&](uint32_t i) {
    if (d3::query_accepts(state_, filter, i)) candidates.push_back(i);
  };
  scratch.broadphase.query(box, collect);
  std::sort(candidates.begin(), candidates.end());
  d3::Manifold m;
  for (const uint32_t i : candidates) {
    const BodyInfo& info = state_.infos[i];
    const BodySim& sim = state_.sims[i];
    d3::collide_shapes(query, pose, info.shape,
                       {sim.position, sim.rotation, mat3_from_quat(sim.rotation)}, 0.0f, m, &store);
    bool touching = false;
    for (uint32_t p = 0; p < m.point_count; ++p) {
      if (m.points[p].separation <= 0.0f) touching = true;
    }
    if (touching) out.push_back(BodyId{i, info.generation});
  }
  return Status::Ok();
}

}  // namespace rwd::sim
