// SPDX-License-Identifier: MIT
#pragma once
// The slab test's one step, shared by the sweeps that clip a moving point
// against slabs (a box's faces, a face's edges).

namespace rwd::sim::d3 {

/// The parameters t over which s0 + t v stays within [-extent, extent]:
/// [t0, t1], in order. v must not be zero (callers decide what a motion
/// along the slab means).
inline void slab_interval(float s0, float v, float extent, float& t0, float& t1) {
  t0 = (-extent - s0) / v;
  t1 = (extent - s0) / v;
  if (t0 > t1) {
    const float swap = t0;
    t0 = t1;
    t1 = swap;
  }
}

}  // namespace rwd::sim::d3
