// SPDX-License-Identifier: MIT
// The order the push-out solves contacts in, from the ground up.
//
// Every solver body gets a support level: 0 for the immovable body (static
// and sleeping bodies) and kinematic bodies, then one more per contact away
// from them (a breadth-first search over this step's contacts, visiting
// neighbours in constraint order, so the levels are a function of the
// contact list alone). Bodies touching nothing that rests are left at
// kNoSupport.
//
// The push-out then visits contacts by ascending lower level and, for a
// deep overlap across two levels, moves only the upper body: the lower one
// counts as fixed (shock propagation, Guendelman, Bridson and Fedkiw 2003).
// A column of boxes created inside each other then comes apart in one pass
// from the ground up, instead of the lowest box being pushed back down by
// every box above it until the column buckles sideways. Only the push-out
// works this way; the real velocities see ordinary two-sided contacts.
#include "d3/pipeline.h"

namespace rwd::sim::d3 {

void order_push_out(WorldScratch& scratch) {
  const uint32_t bodies = static_cast<uint32_t>(scratch.solver_bodies.size());
  const uint32_t count = static_cast<uint32_t>(scratch.constraints.size());
  std::vector<uint32_t>& level = scratch.support_level;
  level.assign(bodies, kNoSupport);

  // Adjacency in compressed rows: the constraints touching each body.
  std::vector<uint32_t>& start = scratch.adjacency_start;
  std::vector<uint32_t>& edges = scratch.adjacency;
  start.assign(bodies + 1, 0);
  for (const ContactConstraint& c : scratch.constraints) {
    ++start[c.body_a + 1];
    ++start[c.body_b + 1];
  }
  for (uint32_t i = 0; i < bodies; ++i) start[i + 1] += start[i];
  edges.resize(2 * static_cast<size_t>(count));
  std::vector<uint32_t>& fill = scratch.adjacency_fill;
  fill.assign(start.begin(), start.end() - 1);
  for (uint32_t k = 0; k < count; ++k) {
    edges[fill[scratch.constraints[k].body_a]++] = k;
    edges[fill[scratch.constraints[k].body_b]++] = k;
  }

  // Breadth-first from everything that cannot move.
  std::vector<uint32_t>& queue = scratch.support_queue;
  queue.clear();
  for (uint32_t i = 0; i < bodies; ++i) {
    if (scratch.solver_bodies[i].inv_mass == 0.0f) {
      level[i] = 0;
      queue.push_back(i);
    }
  }
  for (size_t head = 0; head < queue.size(); ++head) {
    const uint32_t body = queue[head];
    for (uint32_t e = start[body]; e < start[body + 1]; ++e) {
      const ContactConstraint& c = scratch.constraints[edges[e]];
      const uint32_t other = c.body_a == body ? c.body_b : c.body_a;
      if (level[other] == kNoSupport) {
        level[other] = level[body] + 1;
        queue.push_back(other);
      }
    }
  }

  // Each contact's lower level, and which side the push-out holds fixed.
  // Then a counting sort by that level (stable: equal levels keep
  // constraint order).
  std::vector<uint32_t>& key = scratch.push_key;
  key.resize(count);
  uint32_t max_key = 0;
  for (uint32_t k = 0; k < count; ++k) {
    ContactConstraint& c = scratch.constraints[k];
    const uint32_t la = level[c.body_a];
    const uint32_t lb = level[c.body_b];
    c.push_fixed = la < lb ? kPushFixedA : (lb < la ? kPushFixedB : kPushFixedNone);
    key[k] = la < lb ? la : lb;
    if (key[k] == kNoSupport) key[k] = bodies;  // after every supported contact
    if (key[k] > max_key) max_key = key[k];
  }
  std::vector<uint32_t>& bucket = scratch.push_bucket;
  bucket.assign(static_cast<size_t>(max_key) + 2, 0);
  for (uint32_t k = 0; k < count; ++k) ++bucket[key[k] + 1];
  for (uint32_t i = 0; i <= max_key; ++i) bucket[i + 1] += bucket[i];
  scratch.push_order.resize(count);
  for (uint32_t k = 0; k < count; ++k) scratch.push_order[bucket[key[k]]++] = k;
}

}  // namespace rwd::sim::d3
