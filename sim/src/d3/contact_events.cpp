// SPDX-License-Identifier: MIT
// Contact events: a merge of last step's cache and this step's, both sorted
// by (index_a, index_b, part). Events are per body pair: a pair with a
// compound may hold several records (parts), and touches while any of them
// does; its event's details come from all of them. A pair that keeps its
// indices but changed
// generation (a body destroyed and its slot reused) is two different pairs:
// the old one exits and the new one enters. Events are built after the
// solve: a pair the solver pushed apart this tick touches this tick
// (mark_pushed_contacts), so an impact stopped by a speculative contact
// before the surfaces met enters in the tick its impulse is applied. An event is made when either
// body's mask (BodyInfo::event_mask) has its type's bit; the details of
// enter and stay events (point, normal, depth, impulse) are filled after
// the solve, from the contact cache (fill_event_details).
#include <algorithm>

#include "d3/body_storage.h"
#include "d3/pipeline.h"

namespace rwd::sim::d3 {
namespace {

uint64_t key(const ContactRecord& r) {
  return (static_cast<uint64_t>(r.index_a) << 32) | r.index_b;
}

// One body pair's records in a cache: [begin, end), parts in a row.
struct PairSpan {
  size_t begin = 0;
  size_t end = 0;
  bool touching = false;  ///< any part touches
};

// A cache's records as one list in cache order: a whole vector, or the
// records at some of its positions (the steady path's view; a pair's parts
// are all in it or all out).
struct CacheView {
  const std::vector<ContactRecord>& records;
  const std::vector<uint32_t>* at = nullptr;  ///< null: every record
  size_t size() const { return at != nullptr ? at->size() : records.size(); }
  const ContactRecord& operator[](size_t k) const {
    return at != nullptr ? records[(*at)[k]] : records[k];
  }
  uint32_t position(size_t k) const { return at != nullptr ? (*at)[k] : static_cast<uint32_t>(k); }
};

template <class Records>
PairSpan pair_at(const Records& records, size_t begin) {
  PairSpan p;
  p.begin = begin;
  p.end = begin;
  const uint64_t k = key(records[begin]);
  while (p.end < records.size() && key(records[p.end]) == k) {
    p.touching = p.touching || records[p.end].touching != 0;
    ++p.end;
  }
  return p;
}

ContactEvent make_event(ContactEventType type, const ContactRecord& r) {
  ContactEvent e;
  e.type = type;
  e.a = {r.index_a, r.generation_a};
  e.b = {r.index_b, r.generation_b};
  e.sensor = r.sensor != 0;
  return e;
}

bool same_bodies(const ContactRecord& x, const ContactRecord& y) {
  return x.generation_a == y.generation_a && x.generation_b == y.generation_b;
}

// The mask of body (index, generation); a body destroyed since (its slot
// dead or reused) asks for everything, so its exits are not lost.
EventMask mask_of(const WorldState& state, uint32_t index, uint32_t generation) {
  const BodyInfo& info = state.infos[index];
  if (info.alive == 0 || info.generation != generation) return kEventAll;
  return info.event_mask;
}

// A pair neither of whose bodies moves this step (asleep or static): it
// reports no stay. Its touch goes on unchanged until one of them wakes,
// and a world of sleeping bodies then reports nothing at all.
bool resting(const WorldState& state, const ContactRecord& r) {
  return !is_active(state.infos[r.index_a]) && !is_active(state.infos[r.index_b]);
}

bool reported(const WorldState& state, const ContactRecord& r, ContactEventType type) {
  const EventMask bit = event_mask_bit(type, r.sensor != 0);
  return ((mask_of(state, r.index_a, r.generation_a) | mask_of(state, r.index_b, r.generation_b)) &
          bit) != 0;
}

}  // namespace

void mark_pushed_contacts(WorldState& state, WorldScratch& scratch) {
  scratch.pushed_records.clear();
  for (const ContactConstraint& c : scratch.constraints) {
    ContactRecord& rec = state.contacts[c.record];
    if (rec.touching != 0) continue;
    float sum = 0.0f;
    for (uint32_t p = 0; p < c.point_count; ++p) sum += c.points[p].tick_normal_impulse;
    if (sum > 0.0f) {
      rec.touching = 1;
      scratch.pushed_records.push_back(c.record);
    }
  }
  // Constraints come in solver order; the event merge wants record order.
  std::sort(scratch.pushed_records.begin(), scratch.pushed_records.end());
}

void build_events(const WorldState& state, WorldScratch& scratch) {
  std::vector<ContactEvent>& events = scratch.events;
  std::vector<uint32_t>& records = scratch.event_records;
  events.clear();
  records.clear();
  // An event of this step's record `index`, or of last step's (no record
  // now: an exit), if either body reports.
  const auto add = [&](ContactEventType type, const ContactRecord& r, uint32_t index) {
    if (!reported(state, r, type)) return;
    events.push_back(make_event(type, r));
    records.push_back(index);
  };
  if (scratch.contacts_unchanged) {
    // The cache carried over whole, every pair in it resting: no stays;
    // only those the solve pushed apart first this tick would enter.
    // A pair enters when every part of it that touches was pushed.
    uint32_t touching = 0;
    size_t pushed = 0;
    const std::vector<ContactRecord>& now = state.contacts;
    for (size_t k = 0; k < now.size();) {
      const PairSpan p = pair_at(now, k);
      bool any = false;
      bool only_pushed = true;
      for (size_t r = p.begin; r < p.end; ++r) {
        if (now[r].touching == 0) continue;
        ++touching;
        any = true;
        while (pushed < scratch.pushed_records.size() && scratch.pushed_records[pushed] < r) {
          ++pushed;
        }
        const bool was_pushed =
            pushed < scratch.pushed_records.size() && scratch.pushed_records[pushed] == r;
        only_pushed = only_pushed && was_pushed;
      }
      if (any && only_pushed) {
        add(ContactEventType::kEnter, now[p.begin], static_cast<uint32_t>(p.begin));
      }
      k = p.end;
    }
    scratch.stats.touching_manifolds = touching;
    scratch.last_touching = touching;
    return;
  }
  // A step that wrote its records in place changed those alone: the rest
  // rest, unchanged, and report nothing, so only the two views are merged.
  const bool in_place = scratch.contacts_in_place;
  const CacheView old{scratch.other_contacts};
  const CacheView now{state.contacts, in_place ? &scratch.steady_view : nullptr};
  uint32_t touching = 0;
  for (size_t k = 0; k < now.size(); ++k) touching += now[k].touching != 0 ? 1u : 0u;
  if (in_place) {
    for (size_t k = 0; k < old.size(); ++k) touching -= old[k].touching != 0 ? 1u : 0u;
    touching += scratch.last_touching;
  }
  size_t i = 0;
  size_t j = 0;
  // Each side's current pair, found once as its cursor reaches it.
  PairSpan o = old.size() == 0 ? PairSpan{} : pair_at(old, 0);
  PairSpan c = now.size() == 0 ? PairSpan{} : pair_at(now, 0);
  const auto next_old = [&] {
    i = o.end;
    if (i < old.size()) o = pair_at(old, i);
  };
  const auto next_now = [&] {
    j = c.end;
    if (j < now.size()) c = pair_at(now, j);
  };
  while (i < old.size() || j < now.size()) {
    bool take_old = j == now.size() || (i < old.size() && key(old[i]) < key(now[j]));
    bool take_new = i == old.size() || (j < now.size() && key(now[j]) < key(old[i]));
    const uint32_t at = j < now.size() ? now.position(j) : 0;
    if (take_old) {
      if (o.touching) add(ContactEventType::kExit, old[i], kNoRecord);
      next_old();
    } else if (take_new) {
      if (c.touching) add(ContactEventType::kEnter, now[j], at);
      next_now();
    } else {
      const bool was = o.touching;
      const bool is = c.touching;
      if (same_bodies(old[i], now[j])) {
        if (is && !was) add(ContactEventType::kEnter, now[j], at);
        if (is && was && !resting(state, now[j])) add(ContactEventType::kStay, now[j], at);
        if (was && !is) add(ContactEventType::kExit, old[i], kNoRecord);
      } else {
        // Type order within a key: enter (0) before exit (2).
        if (is) add(ContactEventType::kEnter, now[j], at);
        if (was) add(ContactEventType::kExit, old[i], kNoRecord);
      }
      next_old();
      next_now();
    }
  }
  scratch.stats.touching_manifolds = touching;
  scratch.last_touching = touching;
}

void fill_event_details(const WorldState& state, WorldScratch& scratch) {
  const float substeps = static_cast<float>(state.config.substeps);
  if (scratch.events.empty()) return;
  // The tick's normal impulse of each record the solver handled: every
  // substep's, and the bounce's; a record it did not (both bodies asleep)
  // falls back to the last substep's times the substeps.
  std::vector<float>& tick_impulse = scratch.record_impulse;
  tick_impulse.assign(state.contacts.size(), -1.0f);
  for (const ContactConstraint& c : scratch.constraints) {
    float sum = 0.0f;
    for (uint32_t p = 0; p < c.point_count; ++p) sum += c.points[p].tick_normal_impulse;
    tick_impulse[c.record] = sum;
  }
  for (size_t e = 0; e < scratch.events.size(); ++e) {
    const uint32_t index = scratch.event_records[e];
    if (index == kNoRecord) continue;
    ContactEvent& event = scratch.events[e];
    const ContactRecord& rec = state.contacts[index];
    if (rec.point_count > 0) {
      // The manifolds as the cache keeps them, on A as A stands now: the
      // deepest point of all the pair's parts, and the impulse of them all.
      const BodySim& a = state.sims[rec.index_a];
      const PairSpan pair = pair_at(state.contacts, index);
      const ContactRecord* deepest_rec = &rec;
      uint32_t deepest = 0;
      float impulse = 0.0f;
      float tick_sum = 0.0f;
      bool solved = false;
      for (size_t r = pair.begin; r < pair.end; ++r) {
        const ContactRecord& part = state.contacts[r];
        for (uint32_t p = 0; p < part.point_count; ++p) {
          if (part.points[p].separation < deepest_rec->points[deepest].separation) {
            deepest_rec = &part;
            deepest = p;
          }
          impulse += part.points[p].normal_impulse;
        }
        if (tick_impulse[r] >= 0.0f) {
          tick_sum += tick_impulse[r];
          solved = true;
        }
      }
      const CachedContactPoint& cp = deepest_rec->points[deepest];
      const Vec3 n = deepest_rec->frame_normal;
      event.normal = rotate(a.rotation, n);
      event.point = a.position + rotate(a.rotation, cp.local_a + n * (0.5f * cp.separation));
      event.depth = cp.separation < 0.0f ? -cp.separation : 0.0f;
      event.impulse = solved ? tick_sum : impulse * substeps;
      continue;
    }
    // A sensor pair: the overlap as this step's manifold saw it.
    if (index >= scratch.geometry.size() || scratch.geometry[index].valid == 0) continue;
    const Manifold& m = scratch.geometry[index].manifold;
    if (m.point_count == 0) continue;
    uint32_t deepest = 0;
    for (uint32_t p = 1; p < m.point_count; ++p) {
      if (m.points[p].separation < m.points[deepest].separation) deepest = p;
    }
    event.normal = m.normal;
    event.point = m.points[deepest].point;
    event.depth = m.points[deepest].separation < 0.0f ? -m.points[deepest].separation : 0.0f;
  }
}

}  // namespace rwd::sim::d3
