// SPDX-License-Identifier: MIT
// The sign test, chosen once for every face contact:
//  - a vertex is kept when its distance is <= 0: one lying exactly on the
//    plane is inside, so a corner resting on a side plane keeps its own
//    feature id rather than being replaced by a crossing with another id;
//  - a crossing is made only where the two ends of a side lie strictly on
//    opposite sides. With the inclusive test there too (as box-box and the
//    triangle outline had it), a vertex on the plane was kept and also
//    doubled by a crossing at t = 0 or 1: two points at one place with
//    different ids, which took manifold slots and left the reduction to
//    four to choose between them by rounding.
// A NaN distance is neither kept nor crossed, so bad input shrinks the
// polygon instead of spreading NaN points.
//
// The capacity guard: a convex polygon gains at most one vertex per cut,
// and every caller sizes its arrays for that, but rounding can make a
// nearly degenerate polygon (a sliver face, a hull's tiny loop side) gain
// more; vertices past the capacity are dropped rather than written beyond it.
#include "d3/polygon_clip.h"

namespace rwd::sim::d3 {

int clip_by_plane(const float* dist, int count, ClipStep* steps, int capacity) {
  // A segment has one side (0 -> 1); a point none.
  const int sides = count >= 3 ? count : count - 1;
  int n = 0;
  for (int m = 0; m < count; ++m) {
    const float dp = dist[m];
    if (dp <= 0.0f && n < capacity) {
      steps[n++] = {ClipStep::kKept, static_cast<uint16_t>(m), static_cast<uint16_t>(m), 0.0f};
    }
    if (m >= sides) continue;
    const int next = m + 1 == count ? 0 : m + 1;
    const float dq = dist[next];
    const bool leaving = dp < 0.0f && dq > 0.0f;
    const bool entering = dp > 0.0f && dq < 0.0f;
    if ((leaving || entering) && n < capacity) {
      // The signs differ strictly, so dp - dq != 0 and t lies in [0, 1].
      steps[n++] = {leaving ? ClipStep::kLeaving : ClipStep::kEntering, static_cast<uint16_t>(m),
                    static_cast<uint16_t>(next), dp / (dp - dq)};
    }
  }
  return n;
}

}  // namespace rwd::sim::d3
