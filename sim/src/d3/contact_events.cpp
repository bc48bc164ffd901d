// SPDX-License-Identifier: MIT
// Contact events: a merge of last step's cache and this step's, both sorted
// by (index_a, index_b). A pair that keeps its indices but changed
// generation (a body destroyed and its slot reused) is two different pairs:
// the old one exits and the new one enters.
#include "d3/pipeline.h"

namespace rwd::sim::d3 {
namespace {

uint64_t key(const ContactRecord& r) {
  return (static_cast<uint64_t>(r.index_a) << 32) | r.index_b;
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

}  // namespace

void build_events(const WorldState& state, WorldScratch& scratch) {
  std::vector<ContactEvent>& events = scratch.events;
  events.clear();
  if (scratch.contacts_unchanged) {
    // The cache carried over whole: every touching pair stays.
    uint32_t touching = 0;
    for (const ContactRecord& r : state.contacts) {
      if (r.touching == 0) continue;
      events.push_back(make_event(ContactEventType::kStay, r));
      ++touching;
    }
    scratch.stats.touching_manifolds = touching;
    return;
  }
  const std::vector<ContactRecord>& old = scratch.other_contacts;
  const std::vector<ContactRecord>& now = state.contacts;
  size_t i = 0;
  size_t j = 0;
  uint32_t touching = 0;
  while (i < old.size() || j < now.size()) {
    bool take_old = j == now.size() || (i < old.size() && key(old[i]) < key(now[j]));
    bool take_new = i == old.size() || (j < now.size() && key(now[j]) < key(old[i]));
    if (take_old) {
      if (old[i].touching != 0) events.push_back(make_event(ContactEventType::kExit, old[i]));
      ++i;
    } else if (take_new) {
      if (now[j].touching != 0) {
        events.push_back(make_event(ContactEventType::kEnter, now[j]));
        ++touching;
      }
      ++j;
    } else {
      const ContactRecord& o = old[i];
      const ContactRecord& c = now[j];
      bool was = o.touching != 0;
      bool is = c.touching != 0;
      if (same_bodies(o, c)) {
        if (is)
          events.push_back(make_event(was ? ContactEventType::kStay : ContactEventType::kEnter, c));
        if (was && !is) events.push_back(make_event(ContactEventType::kExit, o));
      } else {
        // Type order within a key: enter (0) before exit (2).
        if (is) events.push_back(make_event(ContactEventType::kEnter, c));
        if (was) events.push_back(make_event(ContactEventType::kExit, o));
      }
      if (is) ++touching;
      ++i;
      ++j;
    }
  }
  scratch.stats.touching_manifolds = touching;
}

}  // namespace rwd::sim::d3
