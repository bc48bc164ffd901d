// SPDX-License-Identifier: MIT
// Sleeping islands. Each step, the awake dynamic bodies joined by touching
// contacts or joints form islands (union-find, roots by lowest index, so
// the grouping depends on the state alone); an island whose every body has
// been slow for time_to_sleep falls asleep whole. A sleeping body costs no
// integration, no collision and no solving; its contacts are kept. It
// wakes, with everything it touches or is joined to, when a moving body
// touches it, a joint ties it to one, or the game changes it.
#include "body_math2d.h"
#include "pipeline2d.h"
#include "shape_bounds2d.h"

namespace rwd::sim2d::detail {

namespace {

bool is_dynamic(const BodyRecord2D& body) {
  return body.kind == BodyKind2D::kDynamic && (body.flags & kBodyLive) &&
         (body.flags & kBodyEnabled);
}

bool links(const ContactRecord2D& c) {
  return (c.flags & kContactTouching) && !(c.flags & kContactSensor);
}

bool joint_links(const JointRecord2D& j) {
  return (j.flags & kJointLive) && !(j.flags & kJointBroken);
}

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

void unite(std::vector<uint32_t>& parent, uint32_t a, uint32_t b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a == b) return;
  if (a < b) {
    parent[b] = a;
  } else {
    parent[a] = b;
  }
}

// The farthest a point of the shape lies from the centre of mass (an upper
// bound from the shape's bounds): turning at w moves it at w times this.
W rim_distance(const BodyRecord2D& body) {
  const Box2W box = shape_bounds(body.shape, Xf{});
  const W dx =
      wmax(wabs(box.lower.x - body.local_center.x), wabs(box.upper.x - body.local_center.x));
  const W dy =
      wmax(wabs(box.lower.y - body.local_center.y), wabs(box.upper.y - body.local_center.y));
  return vlength({dx, dy});
}

}  // namespace

void wake_touched(World2DState& state, StepScratch2D& scratch) {
  auto& bodies = state.bodies;
  auto& work = scratch.wake_list;
  work.clear();
  auto seed = [&](uint32_t moving, uint32_t other) {
    BodyRecord2D& body = bodies[other];
    if (is_moving(bodies[moving]) && is_dynamic(body) && !(body.flags & kBodyAwake)) {
      wake(body);
      work.push_back(other);
    }
  };
  for (const ContactRecord2D& c : state.contacts) {
    if (!links(c)) continue;
    seed(c.a, c.b);
    seed(c.b, c.a);
  }
  for (const JointRecord2D& j : state.joints) {
    if (!joint_links(j)) continue;
    seed(j.a, j.b);
    seed(j.b, j.a);
  }
  if (work.empty()) return;

  // Flood through the sleeping bodies' own contacts and joints: the whole
  // island wakes this step. Adjacency is built only when something woke.
  const size_t n = bodies.size();
  auto& offsets = scratch.adjacency_offsets;
  auto& edges = scratch.adjacency;
  offsets.assign(n + 1, 0);
  auto each_edge = [&](auto&& visit) {
    for (const ContactRecord2D& c : state.contacts) {
      if (links(c)) visit(c.a, c.b);
    }
    for (const JointRecord2D& j : state.joints) {
      if (joint_links(j)) visit(j.a, j.b);
    }
  };
  each_edge([&](uint32_t a, uint32_t b) {
    ++offsets[a + 1];
    ++offsets[b + 1];
  });
  for (size_t i = 0; i < n; ++i) offsets[i + 1] += offsets[i];
  edges.assign(offsets[n], 0);
  auto& fill = scratch.adjacency_fill;
  fill.assign(offsets.begin(), offsets.end() - 1);
  each_edge([&](uint32_t a, uint32_t b) {
    edges[fill[a]++] = b;
    edges[fill[b]++] = a;
  });
  for (size_t k = 0; k < work.size(); ++k) {
    const uint32_t i = work[k];
    for (uint32_t e = offsets[i]; e < offsets[i + 1]; ++e) {
      BodyRecord2D& next = bodies[edges[e]];
      if (is_dynamic(next) && !(next.flags & kBodyAwake)) {
        wake(next);
        work.push_back(edges[e]);
      }
    }
  }
}

void update_sleep(World2DState& state, StepScratch2D& scratch) {
  auto& bodies = state.bodies;
  const World2DConfig& config = state.config;
  if (!config.enable_sleep) {
    for (BodyRecord2D& body : bodies) body.sleep_time = 0;
    return;
  }
  const W threshold = w_from(config.sleep_threshold);
  const W dt = w_ratio(1, config.tick_hz);
  for (BodyRecord2D& body : bodies) {
    if (!is_dynamic(body) || !(body.flags & kBodyAwake)) continue;
    const bool fast = vlength_sq(body.velocity) > wmul(threshold, threshold) ||
                      wmul(wabs(body.angular_velocity), rim_distance(body)) > threshold;
    body.sleep_time = fast ? 0 : body.sleep_time + dt;
  }
  // Nothing sleeps on a moving kinematic body: it carries what it touches.
  for (const ContactRecord2D& c : state.contacts) {
    if (!links(c)) continue;
    BodyRecord2D& a = bodies[c.a];
    BodyRecord2D& b = bodies[c.b];
    if (a.kind == BodyKind2D::kKinematic && is_moving(a)) b.sleep_time = 0;
    if (b.kind == BodyKind2D::kKinematic && is_moving(b)) a.sleep_time = 0;
  }

  auto& parent = scratch.island_parent;
  auto& least = scratch.island_sleep;
  const size_t n = bodies.size();
  parent.resize(n);
  for (uint32_t i = 0; i < n; ++i) parent[i] = i;
  auto awake_dynamic = [&](uint32_t i) {
    return is_dynamic(bodies[i]) && (bodies[i].flags & kBodyAwake);
  };
  for (const ContactRecord2D& c : state.contacts) {
    if (links(c) && awake_dynamic(c.a) && awake_dynamic(c.b)) unite(parent, c.a, c.b);
  }
  for (const JointRecord2D& j : state.joints) {
    if (joint_links(j) && awake_dynamic(j.a) && awake_dynamic(j.b)) unite(parent, j.a, j.b);
  }
  least.assign(n, W{INT64_MAX});
  for (uint32_t i = 0; i < n; ++i) {
    if (!awake_dynamic(i)) continue;
    const uint32_t root = find_root(parent, i);
    least[root] = wmin(least[root], bodies[i].sleep_time);
  }
  const W time_to_sleep = w_from(config.time_to_sleep);
  for (uint32_t i = 0; i < n; ++i) {
    if (!awake_dynamic(i) || least[find_root(parent, i)] < time_to_sleep) continue;
    BodyRecord2D& body = bodies[i];
    body.flags &= static_cast<uint8_t>(~kBodyAwake);
    body.velocity = {};
    body.angular_velocity = 0;
  }
}

}  // namespace rwd::sim2d::detail
