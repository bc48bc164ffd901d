// SPDX-License-Identifier: MIT
// Narrowphase: one manifold per broadphase pair (a solid pair with a
// compound: one per group of its children's contacts, each a record of its
// own, ContactRecord::part), merged with last step's contact cache. Both
// lists are sorted by (index_a, index_b, part), so matching is a linear
// merge (no hash map, no search). Points keep their impulses when their
// feature id reappears in any of the pair's records (warm starting); new
// points start at zero.
// Contacts whose bodies both sleep are carried over as they are: nothing
// moved, so their manifold is still valid and costs nothing.
//
// Two shortcuts, each a pure function of the state:
//  - a manifold is carried forward while its bodies barely move relative to
//    each other (manifold_reuse.h): resting and settling contacts, most of
//    a pile or a stack, cost a few quaternion products instead of a SAT and
//    a clip;
//  - a box or hull pair that last step's separating axis (a face or, for
//    boxes, an edge pair) still keeps apart is skipped
//    (scratch.separated_keys): it has no points either way, so this one
//    never changes a result.
#include <cmath>
#include <optional>

#include "d3/body_storage.h"
#include "d3/contact_cache_steady.h"
#include "d3/manifold_reuse.h"
#include "d3/pipeline.h"
#include "d3/step_threads.h"

namespace rwd::sim::d3 {
namespace {

uint64_t key(uint32_t a, uint32_t b) {
  return (static_cast<uint64_t>(a) << 32) | b;
}

// Extra speculative reach for a pair: how far the two bodies can close in
// one tick. The config's speculative distance alone would let a body faster
// than speculative/tick sink deep before its contact exists.
float pair_speculative(const WorldState& state, uint32_t a, uint32_t b) {
  const BodySim& sa = state.sims[a];
  const BodySim& sb = state.sims[b];
  float reach = length(sb.linear_velocity - sa.linear_velocity) +
                length(sa.angular_velocity) * state.masses[a].extent +
                length(sb.angular_velocity) * state.masses[b].extent;
  return state.config.speculative_distance_m + state.config.tick_seconds * reach;
}

// Whether a shape's contact features are fixed on it (a box's or a hull's
// faces, edges and corners, a mesh's or a height field's triangles), so a
// manifold carried forward keeps its points where they are. A round surface's contact point moves
// over it as the body rolls; carrying it would tilt the normal with the roll, so pairs with a
// sphere or a capsule are collided every step.
bool keeps_features(const Shape& shape) {
  return shape.type == ShapeType::kBox || shape.type == ShapeType::kHull ||
         shape.type == ShapeType::kMesh || shape.type == ShapeType::kHeightField;
}

// Fills `rec` from its manifold geo.manifold (friction, touching, points
// with the impulses of the same feature among the pair's `prior_count`
// records at `prior`, the manifold's frame in A's frame `axes_a`). Returns
// `carried`: a carried record keeps its points and frame as they were.
bool fill_record(const WorldState& state, const Mat3& axes_a, ContactRecord& rec,
                 ContactGeometry& geo, bool carried, const ContactRecord* prior,
                 size_t prior_count) {
  const BodyInfo& ia = state.infos[rec.index_a];
  const BodyInfo& ib = state.infos[rec.index_b];
  const Manifold& m = geo.manifold;
  geo.friction = std::sqrt(ia.material.friction * ib.material.friction);
  geo.restitution = ia.material.restitution > ib.material.restitution ? ia.material.restitution
                                                                      : ib.material.restitution;
  geo.valid = 1;
  // Touching is geometric and independent of speed: sensors need a real
  // overlap, solid pairs a point within the configured speculative distance
  // (the contact the solver is holding apart), as in Box2D.
  const float limit = rec.sensor != 0 ? 0.0f : state.config.speculative_distance_m;
  uint8_t touching = 0;
  for (uint32_t i = 0; i < m.point_count; ++i) {
    const float separation = m.points[i].separation;
    if (rec.sensor != 0 ? separation < limit : separation <= limit) touching = 1;
  }
  rec.touching = touching;
  if (carried) return true;
  rec.point_count = rec.sensor != 0 ? 0 : static_cast<uint8_t>(m.point_count);
  for (uint32_t i = 0; i < kMaxManifoldPoints; ++i) {
    CachedContactPoint& point = rec.points[i];
    point = CachedContactPoint{};
    if (i >= rec.point_count) continue;
    point.feature_id = m.points[i].feature_id;
    const CachedContactPoint* match = nullptr;
    for (size_t r = 0; r < prior_count && match == nullptr; ++r) {
      for (uint32_t j = 0; j < prior[r].point_count; ++j) {
        if (prior[r].points[j].feature_id == point.feature_id) {
          match = &prior[r].points[j];
          break;
        }
      }
    }
    if (match != nullptr) point = *match;
  }
  if (rec.point_count > 0) {
    const BodySim& sa = state.sims[rec.index_a];
    const BodySim& sb = state.sims[rec.index_b];
    record_frame(axes_a, relative_pose(sa, axes_a, sb), m, rec);
  } else {
    rec.frame_position = {};
    rec.frame_rotation = {};
    rec.frame_normal = {};
  }
  return false;
}

// Computes the manifold (or carries `old`'s forward, see the top of the
// file) and fills `rec` (ids, touching, impulses matched by feature id
// against `old`, which may be null but is never `rec` itself). Returns true
// when the manifold was carried. A pair left with no points and not
// touching is dropped by the caller, so nothing else is filled for it.
bool evaluate(const WorldState& state, WorldScratch& scratch, ContactRecord& rec,
              const ContactRecord* old, ContactGeometry& geo) {
  const BodyInfo& ia = state.infos[rec.index_a];
  const BodyInfo& ib = state.infos[rec.index_b];
  const BodySim& sa = state.sims[rec.index_a];
  const BodySim& sb = state.sims[rec.index_b];
  rec.sensor = (ia.sensor != 0 || ib.sensor != 0) ? 1 : 0;
  Manifold& m = geo.manifold;
  bool carried = false;
  const Mat3& axes_a = body_axes(state, scratch, rec.index_a);
  if (old != nullptr && rec.sensor == 0 && old->sensor == 0 && old->point_count > 0 &&
      keeps_features(ia.shape) && keeps_features(ib.shape)) {
    const RelativePose now = relative_pose(sa, axes_a, sb);
    const Quat turn = now.rotation * conjugate(old->frame_rotation);
    if (within_reuse(*old, now, turn, state.masses[rec.index_b].extent)) {
      carry_manifold(sa, axes_a, sb, *old, now, turn, m);
      m.separating_axis = kNoSeparatingAxis;
      rec = *old;  // same ids, impulses and frame
      carried = true;
    }
  }
  if (!carried) {
    collide_shapes(ia.shape, {sa.position, sa.rotation, axes_a}, ib.shape,
                   {sb.position, sb.rotation, body_axes(state, scratch, rec.index_b)},
                   pair_speculative(state, rec.index_a, rec.index_b), m, scratch.store);
    if (m.point_count == 0) {
      rec.touching = 0;
      return false;
    }
  }
  return fill_record(state, axes_a, rec, geo, carried, old, old != nullptr ? 1 : 0);
}

// Whether a pair is collided as parts (one record per group of contact
// normals): a solid pair with a compound on either side.
bool in_parts(const BodyInfo& ia, const BodyInfo& ib) {
  return (ia.shape.type == ShapeType::kCompound || ib.shape.type == ShapeType::kCompound) &&
         ia.sensor == 0 && ib.sensor == 0;
}

// Places body i's children for this step (a compound), once.
void place_body_children(const WorldState& state, WorldScratch& scratch, uint32_t i) {
  if (state.infos[i].shape.type != ShapeType::kCompound) return;
  if (scratch.children_step.size() < state.infos.size()) {
    scratch.children_at.resize(state.infos.size());
    scratch.children_step.resize(state.infos.size(), 0);
  }
  if (scratch.children_step[i] == scratch.step_serial) return;
  const BodySim& sim = state.sims[i];
  const ShapePose pose{sim.position, sim.rotation, body_axes(state, scratch, i)};
  const uint32_t at = static_cast<uint32_t>(scratch.child_frames.size());
  scratch.child_frames.resize(at + kCompoundMaxChildren);
  place_children(state.infos[i].shape, pose, *scratch.store, &scratch.child_frames[at]);
  scratch.children_at[i] = at;
  scratch.children_step[i] = scratch.step_serial;
}

// The children plan_pairs placed for compound body i.
const ChildFrame* body_children(const WorldScratch& scratch, uint32_t i) {
  return &scratch.child_frames[scratch.children_at[i]];
}

// The parts of a pair in_parts() takes (collide_compound_parts), normals
// from A to B, anchors filled as collide_shapes fills them. Returns the
// count.
uint32_t collide_parts(const WorldState& state, WorldScratch& scratch, uint32_t a, uint32_t b,
                       CompoundWork& work, Manifold parts[kMaxContactParts]) {
  const BodyInfo& ia = state.infos[a];
  const BodyInfo& ib = state.infos[b];
  const BodySim& sa = state.sims[a];
  const BodySim& sb = state.sims[b];
  const ShapePose pa{sa.position, sa.rotation, body_axes(state, scratch, a)};
  const ShapePose pb{sb.position, sb.rotation, body_axes(state, scratch, b)};
  const float speculative = pair_speculative(state, a, b);
  const bool a_leads = ia.shape.type == ShapeType::kCompound;
  const bool both = a_leads && ib.shape.type == ShapeType::kCompound;
  const uint32_t count =
      a_leads ? collide_compound_parts(ia.shape, body_children(scratch, a), ib.shape, pb,
                                       both ? body_children(scratch, b) : nullptr, speculative,
                                       *scratch.store, work, parts)
              : collide_compound_parts(ib.shape, body_children(scratch, b), ia.shape, pa, nullptr,
                                       speculative, *scratch.store, work, parts);
  for (uint32_t k = 0; k < count; ++k) {
    Manifold& m = parts[k];
    if (!a_leads) m.normal = -m.normal;
    for (uint32_t i = 0; i < m.point_count; ++i) {
      m.points[i].anchor_a = m.points[i].point - pa.position;
      m.points[i].anchor_b = m.points[i].point - pb.position;
    }
  }
  return count;
}

// Whether last step's separating axis of a pair (if it had one: box and
// hull pairs) still separates it: then the pair has no points and needs no
// manifold.
bool still_separated(const WorldState& state, WorldScratch& scratch, uint32_t a, uint32_t b,
                     uint8_t axis) {
  const BodySim& sa = state.sims[a];
  const BodySim& sb = state.sims[b];
  return shapes_still_separated(
      state.infos[a].shape, {sa.position, sa.rotation, body_axes(state, scratch, a)},
      state.infos[b].shape, {sb.position, sb.rotation, body_axes(state, scratch, b)}, axis,
      pair_speculative(state, a, b), scratch.store);
}

bool both_resting(const WorldState& state, const ContactRecord& r) {
  const BodyInfo& a = state.infos[r.index_a];
  const BodyInfo& b = state.infos[r.index_b];
  return is_simulated(a) && is_simulated(b) && a.generation == r.generation_a &&
         b.generation == r.generation_b && !is_active(a) && !is_active(b);
}

// pair_plan entries: the kind in the top two bits, an index below.
constexpr uint32_t kPlanJob = 0u << 30;
constexpr uint32_t kPlanKeepOld = 1u << 30;
constexpr uint32_t kPlanStillSeparated = 2u << 30;
constexpr uint32_t kPlanKind = 3u << 30;
// Pair jobs per range when the narrowphase is cut across the step's
// threads.
constexpr uint32_t kPairGrain = 32;

// Walks this step's pairs beside last step's records (both sorted by key)
// and plans the step's cache in that order (scratch.pair_plan): records of
// two resting bodies kept as they are, box and hull pairs last step's axis
// still separates skipped, every other pair a job. Computes the frames of the
// jobs' bodies (and places their compounds' children), so the jobs only
// read them.
void plan_pairs(const WorldState& state, WorldScratch& scratch) {
  const std::vector<ContactRecord>& old = scratch.other_contacts;
  const std::vector<BodyPair>& pairs = scratch.pairs;
  const std::vector<uint64_t>& sep_keys = scratch.separated_keys;
  std::vector<PairJob>& jobs = scratch.pair_jobs;
  std::vector<uint32_t>& plan = scratch.pair_plan;
  jobs.clear();
  plan.clear();
  scratch.child_frames.clear();  // every step places its compounds anew
  uint32_t slots = 0;
  size_t i = 0;
  size_t j = 0;
  size_t s = 0;
  while (i < pairs.size() || j < old.size()) {
    const uint64_t kp = i < pairs.size() ? key(pairs[i].a, pairs[i].b) : ~uint64_t{0};
    const uint64_t ko = j < old.size() ? key(old[j].index_a, old[j].index_b) : ~uint64_t{0};
    if (j < old.size() && (i == pairs.size() || ko < kp)) {
      if (both_resting(state, old[j])) plan.push_back(kPlanKeepOld | static_cast<uint32_t>(j));
      ++j;
      continue;
    }
    const uint32_t a = pairs[i].a;
    const uint32_t b = pairs[i].b;
    uint32_t prior = 0;
    uint32_t prior_count = 0;
    if (kp == ko) {
      size_t last = j + 1;
      while (last < old.size() && key(old[last].index_a, old[last].index_b) == ko) ++last;
      if (old[j].generation_a == state.infos[a].generation &&
          old[j].generation_b == state.infos[b].generation) {
        prior = static_cast<uint32_t>(j);
        prior_count = static_cast<uint32_t>(last - j);
      }
      j = last;
    }
    ++i;
    if (prior_count == 0) {
      while (s < sep_keys.size() && sep_keys[s] < kp) ++s;
      if (s < sep_keys.size() && sep_keys[s] == kp &&
          still_separated(state, scratch, a, b, scratch.separated_axes[s])) {
        plan.push_back(kPlanStillSeparated | static_cast<uint32_t>(s));
        continue;
      }
    }
    body_axes(state, scratch, a);
    body_axes(state, scratch, b);
    const bool parts = in_parts(state.infos[a], state.infos[b]);
    if (parts) {
      place_body_children(state, scratch, a);
      place_body_children(state, scratch, b);
    }
    plan.push_back(kPlanJob | static_cast<uint32_t>(jobs.size()));
    // Written in place: a job put together on the stack and copied in is
    // stored a field at a time and read back as a vector, a load no store
    // can forward, which stalled every pair.
    PairJob& job = jobs.emplace_back();
    job.a = a;
    job.b = b;
    job.prior = prior;
    job.prior_count = prior_count;
    job.slot = slots;
    job.parts = parts ? 1 : 0;
    slots += parts ? kMaxContactParts : 1;
  }
  if (scratch.job_records.size() < slots) scratch.job_records.resize(slots);
  if (scratch.job_geometry.size() < slots) scratch.job_geometry.resize(slots);
}

// Collides one planned pair into its result slots: its records (ids,
// touching, impulses matched by feature id against last step's records)
// and manifolds, job.count of them (0: dropped), job.carried when its
// manifold was carried forward. Reads the state, the frames plan_pairs
// computed and last step's records; writes only the job and its slots.
void collide_job(const WorldState& state, WorldScratch& scratch, PairJob& job,
                 std::optional<CompoundWork>& work) {
  const ContactRecord* prior = job.prior_count > 0 ? &scratch.other_contacts[job.prior] : nullptr;
  ContactRecord* records = &scratch.job_records[job.slot];
  ContactGeometry* geometry = &scratch.job_geometry[job.slot];
  const uint32_t generation_a = state.infos[job.a].generation;
  const uint32_t generation_b = state.infos[job.b].generation;
  if (job.parts != 0) {
    Manifold parts[kMaxContactParts];
    if (!work) work.emplace();
    const uint32_t count = collide_parts(state, scratch, job.a, job.b, *work, parts);
    for (uint32_t k = 0; k < count; ++k) {
      ContactRecord& rec = records[k];
      rec = ContactRecord{};
      rec.index_a = job.a;
      rec.index_b = job.b;
      rec.generation_a = generation_a;
      rec.generation_b = generation_b;
      rec.part = static_cast<uint8_t>(k);
      geometry[k].manifold = parts[k];
      fill_record(state, body_axes(state, scratch, job.a), rec, geometry[k], false, prior,
                  job.prior_count);
    }
    job.count = static_cast<uint8_t>(count);
    job.carried = 0;
    return;
  }
  ContactRecord& rec = records[0];
  rec = ContactRecord{};
  rec.index_a = job.a;
  rec.index_b = job.b;
  rec.generation_a = generation_a;
  rec.generation_b = generation_b;
  job.carried = evaluate(state, scratch, rec, prior, geometry[0]) ? 1 : 0;
  // Pairs whose bounds overlap but whose shapes are out of reach are not
  // kept: the cache holds only pairs that have (or had) points.
  job.count = geometry[0].manifold.point_count == 0 && rec.touching == 0 ? 0 : 1;
}

// The planned jobs, on the step's threads: each writes only its own job
// and slots, so the cut never changes a result.
void collide_jobs(const WorldState& state, WorldScratch& scratch) {
  std::vector<PairJob>& jobs = scratch.pair_jobs;
  for_ranges(scratch, static_cast<uint32_t>(jobs.size()), kPairGrain,
             [&](uint32_t begin, uint32_t end) {
               std::optional<CompoundWork> work;  // made at the range's first compound
               for (uint32_t k = begin; k < end; ++k) collide_job(state, scratch, jobs[k], work);
             });
}

// Builds the step's cache (`out`, `geometry` beside it: state.contacts and
// scratch.geometry, or the steady cache's share of them) and next step's
// separated pairs from the plan, in pair order; evaluated_records index
// `out`.
void gather_pairs(WorldScratch& scratch, std::vector<ContactRecord>& out,
                  std::vector<ContactGeometry>& geometry) {
  const std::vector<ContactRecord>& old = scratch.other_contacts;
  out.clear();
  // geometry[k] belongs to out[k]. Its slots are kept from step to step
  // (only grown here); a kept record of two resting bodies costs one byte.
  const size_t bound = old.size() + scratch.job_records.size();
  if (geometry.size() < bound) geometry.resize(bound);
  std::vector<uint64_t>& next_keys = scratch.next_separated_keys;
  std::vector<uint8_t>& next_axes = scratch.next_separated_axes;
  next_keys.clear();
  next_axes.clear();
  uint32_t reused = 0;
  for (const uint32_t entry : scratch.pair_plan) {
    const uint32_t index = entry & ~kPlanKind;
    if ((entry & kPlanKind) == kPlanKeepOld) {
      geometry[out.size()].valid = 0;
      out.push_back(old[index]);
      continue;
    }
    if ((entry & kPlanKind) == kPlanStillSeparated) {
      next_keys.push_back(scratch.separated_keys[index]);
      next_axes.push_back(scratch.separated_axes[index]);
      continue;
    }
    const PairJob& job = scratch.pair_jobs[index];
    reused += job.carried;
    if (job.count == 0 && job.parts == 0) {
      const uint8_t axis = scratch.job_geometry[job.slot].manifold.separating_axis;
      if (axis != kNoSeparatingAxis) {
        next_keys.push_back(key(job.a, job.b));
        next_axes.push_back(axis);
      }
      continue;
    }
    for (uint32_t k = 0; k < job.count; ++k) {
      geometry[out.size()] = scratch.job_geometry[job.slot + k];
      out.push_back(scratch.job_records[job.slot + k]);
      scratch.evaluated_records.push_back(static_cast<uint32_t>(out.size() - 1));
    }
  }
  scratch.separated_keys.swap(next_keys);
  scratch.separated_axes.swap(next_axes);
  scratch.stats.reused_manifolds = reused;
}

}  // namespace

void update_contacts(WorldState& state, WorldScratch& scratch) {
  // A world at rest (no pairs: nothing awake) whose every record joins two
  // sleeping bodies keeps its cache exactly as it is: no copy, no merge.
  scratch.contacts_unchanged = false;
  scratch.contacts_in_place = false;
  scratch.evaluated_records.clear();
  scratch.refreshed_records.clear();
  if (scratch.pairs.empty()) {
    bool resting = true;
    for (const ContactRecord& r : state.contacts) {
      if (!both_resting(state, r)) {
        resting = false;
        break;
      }
    }
    if (resting) {
      scratch.contacts_unchanged = true;
      if (scratch.geometry.size() < state.contacts.size()) {
        scratch.geometry.resize(state.contacts.size());
      }
      for (size_t k = 0; k < state.contacts.size(); ++k) scratch.geometry[k].valid = 0;
      scratch.separated_keys.clear();
      scratch.separated_axes.clear();
      scratch.steady_serial = 0;
      return;
    }
  }
  if (steady_cache_usable(state, scratch)) {
    // Last step's evaluated records stand in for its whole cache: the rest
    // rest, and the full merge would carry them as they are.
    steady_old_records(state, scratch);
    plan_pairs(state, scratch);
    collide_jobs(state, scratch);
    gather_pairs(scratch, scratch.steady_new, scratch.steady_geometry);
    place_steady_records(state, scratch);
  } else {
    std::vector<ContactRecord>& old = scratch.other_contacts;
    old.swap(state.contacts);  // old = last step's cache; state.contacts is rebuilt
    plan_pairs(state, scratch);
    collide_jobs(state, scratch);
    gather_pairs(scratch, state.contacts, scratch.geometry);
  }
  remember_steady(scratch);
}

void refresh_contact(WorldState& state, WorldScratch& scratch, uint32_t index) {
  ContactRecord& rec = state.contacts[index];
  const ContactRecord prior = rec;
  ContactGeometry& geo = scratch.geometry[index];
  if (in_parts(state.infos[rec.index_a], state.infos[rec.index_b])) {
    // Its own part as the pair stands now (both slept, so nothing moved:
    // the same groups in the same order).
    Manifold parts[kMaxContactParts];
    place_body_children(state, scratch, rec.index_a);
    place_body_children(state, scratch, rec.index_b);
    CompoundWork work;
    const uint32_t count = collide_parts(state, scratch, rec.index_a, rec.index_b, work, parts);
    geo.manifold = rec.part < count ? parts[rec.part] : Manifold{};
    if (geo.manifold.point_count > 0) {
      fill_record(state, body_axes(state, scratch, rec.index_a), rec, geo, false, &prior, 1);
    }
  } else {
    evaluate(state, scratch, rec, &prior, geo);
  }
  if (geo.manifold.point_count == 0) {
    // Out of reach now. The record stays in this step's cache without
    // points (it ends with an exit event, and the next step drops it).
    const ContactRecord ids = rec;
    rec = ContactRecord{};
    rec.index_a = ids.index_a;
    rec.generation_a = ids.generation_a;
    rec.index_b = ids.index_b;
    rec.generation_b = ids.generation_b;
    rec.sensor = ids.sensor;
    rec.part = ids.part;
    geo.valid = 1;
  }
}

}  // namespace rwd::sim::d3
