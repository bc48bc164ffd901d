// SPDX-License-Identifier: MIT
// Shape casts: a shape swept along a straight line against the world's
// bodies. The swept shape is convex or a compound (swept_shape.h). The
// broadphase (broadphase.h) gives the bodies whose bounds the shape's
// bounds meet on the way; each is swept in closed form where the pair has
// one (a sphere or a box against a sphere or a box: cast_exact.h), else by
// conservative advancement on GJK (gjk.h), and ties go to the lower index
// whatever the trees' shapes: all hits in index order, the closest near to
// far.
#include <algorithm>
#include <cmath>

#include "d3/body_storage.h"
#include "d3/cast_exact.h"
#include "d3/gjk.h"
#include "d3/mass_frame.h"
#include "d3/pipeline.h"
#include "d3/query_filter.h"
#include "d3/shape_ops.h"
#include "d3/state_rules.h"
#include "d3/swept_shape.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

// Longest sweep a query takes, m: the diagonal of the largest world.
constexpr float kMaxCastLength = 1e5f;

struct CastSetup {
  explicit CastSetup(d3::SweptShape& room) : swept(room) {}
  Shape shape;
  d3::SweptShape& swept;  ///< the world's scratch room (WorldScratch::cast_shape)
  Vec3 translation;
  float length = 0.0f;
  d3::Aabb start_bounds;
};

Status prepare_cast(const GeometryStore& store, const Shape& shape, Vec3 position, Quat rotation,
                    Vec3 translation, CastSetup& c) {
  if (Status s = d3::check_shape(shape, store); !s.ok()) return s;
  if (!d3::can_sweep(shape)) {
    return Status::Error(
        ErrorCode::kInvalidArgument,
        "a mesh or a height field cannot be swept (convex shapes and compounds can)");
  }
  if (!is_finite(position) || !is_finite(rotation) || !is_finite(translation)) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "position, rotation and translation must be finite");
  }
  const Quat q = normalize(rotation);
  if (q == Quat{} && !(rotation == Quat{})) {
    return Status::Error(ErrorCode::kInvalidArgument, "rotation must not be zero");
  }
  c.length = length(translation);
  if (!(c.length <= kMaxCastLength)) {
    return Status::Error(ErrorCode::kInvalidArgument, "translation longer than 1e5 m");
  }
  c.shape = shape;
  d3::shape_ops(c.shape.type).canonical(c.shape, store);
  Vec3 p;
  Quat r;
  d3::authored_to_mass(d3::mass_frame(c.shape, store), position, q, p, r);
  const Mat3 axes = mat3_from_quat(r);
  d3::make_swept_shape(c.shape, store, p, axes, c.swept);
  c.translation = translation;
  c.start_bounds = d3::shape_aabb(c.shape, p, axes);
  return Status::Ok();
}

// The first touch of the cast against body i, no later than max_fraction.
d3::ShapeCastOutput sweep_body(const WorldState& state, const GeometryStore& store,
                               const CastSetup& c, uint32_t i, float max_fraction) {
  const BodyInfo& info = state.infos[i];
  const BodySim& sim = state.sims[i];
  const Mat3 axes = mat3_from_quat(sim.rotation);
  d3::ShapeCastOutput hit;
  if (c.swept.count == 1 && d3::cast_exact(info.shape, sim.position, axes, c.shape,
                                           c.swept.parts[0], c.translation, max_fraction, hit)) {
    return hit;
  }
  return d3::sweep_against(info.shape, store, sim.position, axes, c.swept, c.translation,
                           max_fraction);
}

// Calls visit(hit) for every body the sweep touches, in index order.
template <class Visit>
void sweep(const WorldState& state, WorldScratch& scratch, const CastSetup& c,
           const QueryFilter& filter, Visit&& visit) {
  d3::prepare_queries(state, scratch);
  std::vector<uint32_t>& candidates = scratch.query_hits;
  candidates.clear();
  const auto collect = [&](uint32_t i) {
    if (d3::query_accepts(state, filter, i)) candidates.push_back(i);
  };
  scratch.broadphase.sweep_query(c.start_bounds, c.translation, collect);
  std::sort(candidates.begin(), candidates.end());
  for (const uint32_t i : candidates) {
    const BodyInfo& info = state.infos[i];
    const d3::ShapeCastOutput hit = sweep_body(state, *scratch.store, c, i, 1.0f);
    if (!hit.hit) continue;
    visit(ShapeCastHit{BodyId{i, info.generation}, hit.fraction * c.length, hit.point, hit.normal});
  }
}

bool nearer(const ShapeCastHit& l, const ShapeCastHit& r) {
  return l.distance < r.distance || (l.distance == r.distance && l.body.index < r.body.index);
}

}  // namespace

Status World3D::shape_cast(const Shape& shape, Vec3 position, Quat rotation, Vec3 translation,
                           const QueryFilter& filter, std::optional<ShapeCastHit>& out) const {
  out.reset();
  CastSetup c(scratch_->cast_shape);
  if (Status s = prepare_cast(*geometry_, shape, position, rotation, translation, c); !s.ok()) {
    return s;
  }
  d3::prepare_queries(state_, *scratch_);
  // The trees are walked near to far and each body is swept no further
  // than the best hit so far (a sweep's answer does not depend on how far
  // it may go, only whether it gets there; an equal fraction still
  // counts): the nearest hit wins, ties to the lower index, as if every
  // body on the way were swept in index order (shape_cast_all).
  float reach = 1.0f;  // a fraction of the translation
  const auto test = [&](uint32_t i) {
    if (!d3::query_accepts(state_, filter, i)) return;
    const BodyInfo& info = state_.infos[i];
    const d3::ShapeCastOutput hit = sweep_body(state_, *scratch_->store, c, i, reach);
    if (!hit.hit) return;
    const ShapeCastHit found{BodyId{i, info.generation}, hit.fraction * c.length, hit.point,
                             hit.normal};
    if (out && !nearer(found, *out)) return;
    out = found;
    reach = hit.fraction;
  };
  scratch_->broadphase.sweep_query_nearest(c.start_bounds, c.translation, reach, test);
  return Status::Ok();
}

Status World3D::shape_cast_all(const Shape& shape, Vec3 position, Quat rotation, Vec3 translation,
                               const QueryFilter& filter, std::vector<ShapeCastHit>& out) const {
  out.clear();
  CastSetup c(scratch_->cast_shape);
  if (Status s = prepare_cast(*geometry_, shape, position, rotation, translation, c); !s.ok()) {
    return s;
  }
  sweep(state_, *scratch_, c, filter, [&out](const ShapeCastHit& hit) { out.push_back(hit); });
  std::sort(out.begin(), out.end(), nearer);  // a total order: ties by index
  return Status::Ok();
}

}  // namespace rwd::sim
