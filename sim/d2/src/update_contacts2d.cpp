// SPDX-License-Identifier: MIT
#include <utility>

#include "body_math2d.h"
#include "manifold2.h"
#include "pipeline2d.h"

namespace rwd::sim2d::detail {

namespace {

// Points of the new manifold take the impulses of last step's point with
// the same feature id (the features still touching), so stacks start each
// step from the impulses that held them.
void carry_impulses(const ContactRecord2D& old_contact, ContactRecord2D& contact) {
  for (int i = 0; i < contact.count; ++i) {
    ContactPoint2D& point = contact.points[i];
    for (int j = 0; j < old_contact.count; ++j) {
      if (old_contact.points[j].id != point.id) continue;
      point.normal_impulse = old_contact.points[j].normal_impulse;
      point.tangent_impulse = old_contact.points[j].tangent_impulse;
      break;
    }
  }
  contact.rolling_impulse = old_contact.rolling_impulse;
}

uint64_t key_of(const ContactRecord2D& c) {
  return (uint64_t{c.a} << 32) | c.b;
}

// A contact between bodies that do not move this step (asleep or static)
// is kept as it was: nothing collides them, and waking picks it up again.
void carry_if_frozen(const World2DState& state, const ContactRecord2D& old,
                     std::vector<ContactRecord2D>& contacts) {
  if (is_moving(state.bodies[old.a]) || is_moving(state.bodies[old.b])) return;
  contacts.push_back(old);
}

// Pairs per range when the shapes are collided on the step's threads.
constexpr uint32_t kPairGrain = 32;

// Every pair's manifold into scratch.manifolds, on the step's threads when
// it has them: each range writes only its own pairs' manifolds, so the cut
// never changes a result.
void collide_pairs(const World2DState& state, StepScratch2D& scratch, W speculative) {
  const uint32_t count = static_cast<uint32_t>(scratch.pairs.size());
  scratch.manifolds.resize(count);
  // Polygons and capsules are widened to W once per body, not once per
  // pair (a box in a stack meets four or more neighbours), and only the
  // bodies in a pair (a sleeping heap's are in none).
  auto& wide = scratch.wide_shapes;
  auto& widened = scratch.widened;
  wide.resize(state.bodies.size());
  widened.assign(state.bodies.size(), 0);
  for (const uint64_t key : scratch.pairs) {
    for (const uint32_t i : {static_cast<uint32_t>(key >> 32), static_cast<uint32_t>(key)}) {
      if (widened[i] || !widens(state.bodies[i].shape)) continue;
      widen(state.bodies[i].shape, wide[i]);
      widened[i] = 1;
    }
  }
  const auto collide_range = [&](uint32_t begin, uint32_t end) {
    for (uint32_t k = begin; k < end; ++k) {
      const uint32_t a = static_cast<uint32_t>(scratch.pairs[k] >> 32);
      const uint32_t b = static_cast<uint32_t>(scratch.pairs[k]);
      const BodyRecord2D& body_a = state.bodies[a];
      const BodyRecord2D& body_b = state.bodies[b];
      if (widens(body_a.shape) && widens(body_b.shape)) {
        collide_wide(wide[a], origin_transform(body_a), wide[b], origin_transform(body_b),
                     speculative, scratch.manifolds[k]);
      } else {
        collide(body_a.shape, origin_transform(body_a), body_b.shape, origin_transform(body_b),
                speculative, scratch.manifolds[k]);
      }
    }
  };
  if (scratch.pool != nullptr) {
    scratch.pool->parallel_for(count, kPairGrain, collide_range);
  } else {
    collide_range(0, count);
  }
}

}  // namespace

void update_contacts(World2DState& state, StepScratch2D& scratch) {
  const W speculative = w_from(state.config.speculative_distance);
  const W slop = w_from(state.config.linear_slop);
  const auto& old_contacts = state.contacts;
  auto& contacts = scratch.next_contacts;
  contacts.clear();
  size_t old_index = 0;
  collide_pairs(state, scratch, speculative);
  for (size_t k = 0; k < scratch.pairs.size(); ++k) {
    const uint64_t key = scratch.pairs[k];
    const uint32_t a = static_cast<uint32_t>(key >> 32);
    const uint32_t b = static_cast<uint32_t>(key);
    const BodyRecord2D& body_a = state.bodies[a];
    const BodyRecord2D& body_b = state.bodies[b];
    const Xf xa = origin_transform(body_a);
    const Xf xb = origin_transform(body_b);
    const Manifold2& manifold = scratch.manifolds[k];
    if (manifold.count == 0) continue;

    ContactRecord2D contact;
    contact.a = a;
    contact.b = b;
    contact.normal = manifold.normal;
    contact.count = static_cast<uint8_t>(manifold.count);
    // Sensors report overlaps and never push: their contacts are not solved.
    const bool sensor = ((body_a.flags | body_b.flags) & kBodySensor) != 0;
    W deepest = manifold.points[0].separation;
    if (manifold.count > 1) deepest = wmin(deepest, manifold.points[1].separation);
    if (sensor) contact.flags |= kContactSensor;
    if ((body_a.flags | body_b.flags) & kBodyTrigger) contact.flags |= kContactTrigger;
    if (deepest < (sensor ? 0 : slop)) contact.flags |= kContactTouching;
    // Anchors from the manifold are from each body's origin; the solver
    // works from the centres of mass.
    const V2 offset_a = body_a.center - xa.p;
    const V2 offset_b = body_b.center - xb.p;
    for (int i = 0; i < manifold.count; ++i) {
      const ManifoldPoint2& mp = manifold.points[i];
      contact.points[i].anchor_a = mp.anchor_a - offset_a;
      contact.points[i].anchor_b = mp.anchor_b - offset_b;
      contact.points[i].separation = mp.separation;
      contact.points[i].id = mp.id;
    }
    while (old_index < old_contacts.size() && key_of(old_contacts[old_index]) < key) {
      carry_if_frozen(state, old_contacts[old_index++], contacts);
    }
    if (old_index < old_contacts.size() && old_contacts[old_index].a == a &&
        old_contacts[old_index].b == b) {
      carry_impulses(old_contacts[old_index], contact);
    }
    contacts.push_back(contact);
  }
  while (old_index < old_contacts.size())
    carry_if_frozen(state, old_contacts[old_index++], contacts);
  collect_events(state, contacts, scratch.events);
  std::swap(state.contacts, contacts);
}

}  // namespace rwd::sim2d::detail
