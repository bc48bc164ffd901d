// SPDX-License-Identifier: MIT
#include <algorithm>

#include "body_math2d.h"
#include "pipeline2d.h"

namespace rwd::sim2d::detail {

namespace {

uint64_t key_of(const ContactRecord2D& c) {
  return (uint64_t{c.a} << 32) | c.b;
}

ContactEvent2D make_event(const World2DState& state, const ContactRecord2D& c,
                          ContactEventType2D type) {
  ContactEvent2D e;
  e.type = type;
  e.a = {c.a, state.bodies[c.a].generation};
  e.b = {c.b, state.bodies[c.b].generation};
  e.sensor = (c.flags & kContactSensor) != 0;
  e.trigger = (c.flags & kContactTrigger) != 0;
  if (type == ContactEventType2D::kExit) return e;
  int deepest = 0;
  if (c.count > 1 && c.points[1].separation < c.points[0].separation) deepest = 1;
  const ContactPoint2D& p = c.points[deepest];
  e.point = v_to_fx(state.bodies[c.a].center + p.anchor_a);
  e.normal = v_to_fx(c.normal);
  e.depth = p.separation < 0 ? w_to_fx(-p.separation) : Fx();
  return e;
}

// The exit a touching contact reports when one of its bodies goes away.
PendingExit2D exit_of(const World2DState& state, const ContactRecord2D& c) {
  return {c.a, state.bodies[c.a].generation, c.b, state.bodies[c.b].generation,
          static_cast<uint8_t>(((c.flags & kContactSensor) ? 1 : 0) |
                               ((c.flags & kContactTrigger) ? 2 : 0))};
}

}  // namespace

void collect_events(const World2DState& state, const std::vector<ContactRecord2D>& next,
                    std::vector<ContactEvent2D>& events) {
  const auto& prev = state.contacts;
  size_t i = 0;
  size_t j = 0;
  while (i < prev.size() || j < next.size()) {
    const bool take_prev =
        j == next.size() || (i < prev.size() && key_of(prev[i]) < key_of(next[j]));
    const bool take_next =
        i == prev.size() || (j < next.size() && key_of(next[j]) < key_of(prev[i]));
    if (take_prev) {
      if (prev[i].flags & kContactTouching) {
        events.push_back(make_event(state, prev[i], ContactEventType2D::kExit));
      }
      ++i;
    } else if (take_next) {
      if (next[j].flags & kContactTouching) {
        events.push_back(make_event(state, next[j], ContactEventType2D::kEnter));
      }
      ++j;
    } else {
      const bool was = (prev[i].flags & kContactTouching) != 0;
      const bool is = (next[j].flags & kContactTouching) != 0;
      const bool frozen =
          !is_moving(state.bodies[next[j].a]) && !is_moving(state.bodies[next[j].b]);
      if (is && was && frozen) {
        // A sleeping pair still touches; it is not reported every step.
      } else if (is) {
        events.push_back(make_event(state, next[j],
                                    was ? ContactEventType2D::kStay : ContactEventType2D::kEnter));
      } else if (was) {
        events.push_back(make_event(state, prev[i], ContactEventType2D::kExit));
      }
      ++i;
      ++j;
    }
  }
}

void drop_contacts_of(World2DState& state, uint32_t index) {
  auto& contacts = state.contacts;
  size_t kept = 0;
  for (size_t i = 0; i < contacts.size(); ++i) {
    const ContactRecord2D& c = contacts[i];
    if (c.a != index && c.b != index) {
      contacts[kept++] = c;
      continue;
    }
    // What rested on the body that went away wakes and falls.
    wake(state.bodies[c.a == index ? c.b : c.a]);
    if (c.flags & kContactTouching) state.pending_exits.push_back(exit_of(state, c));
  }
  contacts.resize(kept);
}

void drop_contacts_of(World2DState& state, const std::vector<uint32_t>& turn_of, uint32_t turns) {
  auto& contacts = state.contacts;
  // The exits as destroying the bodies one by one would leave them: each
  // contact goes with the first of its bodies to go (its turn), and each
  // turn's exits in contact order; so a counting sort by turn.
  std::vector<uint32_t> per_turn(static_cast<size_t>(turns) + 1, 0);
  std::vector<std::pair<uint32_t, PendingExit2D>> exits;
  size_t kept = 0;
  for (size_t i = 0; i < contacts.size(); ++i) {
    const ContactRecord2D& c = contacts[i];
    const uint32_t turn = std::min(turn_of[c.a], turn_of[c.b]);
    if (turn == UINT32_MAX) {
      contacts[kept++] = c;
      continue;
    }
    wake(state.bodies[turn_of[c.a] == turn ? c.b : c.a]);
    if (c.flags & kContactTouching) {
      exits.push_back({turn, exit_of(state, c)});
      ++per_turn[turn + 1];
    }
  }
  contacts.resize(kept);
  for (uint32_t t = 0; t < turns; ++t) per_turn[t + 1] += per_turn[t];
  const size_t first = state.pending_exits.size();
  state.pending_exits.resize(first + exits.size());
  for (const auto& [turn, exit] : exits) state.pending_exits[first + per_turn[turn]++] = exit;
}

void begin_events(World2DState& state, std::vector<ContactEvent2D>& events) {
  events.clear();
  for (const PendingExit2D& p : state.pending_exits) {
    ContactEvent2D e;
    e.type = ContactEventType2D::kExit;
    e.a = {p.a, p.generation_a};
    e.b = {p.b, p.generation_b};
    e.sensor = (p.sensor & 1) != 0;
    e.trigger = (p.sensor & 2) != 0;
    events.push_back(e);
  }
  state.pending_exits.clear();
}

void sort_events(std::vector<ContactEvent2D>& events) {
  // The key is unique (a body appears once per generation), so the order
  // depends on the events alone.
  std::sort(events.begin(), events.end(), [](const ContactEvent2D& x, const ContactEvent2D& y) {
    if (x.a.index != y.a.index) return x.a.index < y.a.index;
    if (x.b.index != y.b.index) return x.b.index < y.b.index;
    if (x.type != y.type) return x.type > y.type;  // an exit before the enter that replaces it
    if (x.a.generation != y.a.generation) return x.a.generation < y.a.generation;
    return x.b.generation < y.b.generation;
  });
}

}  // namespace rwd::sim2d::detail
