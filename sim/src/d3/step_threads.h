// SPDX-License-Identifier: MIT
#pragma once
// The step's threads (World3D::set_thread_pool): the stages hand ranges of
// independent work to the pool when the world has one, else run them on
// the stepping thread. Either way each range writes only what it owns, so
// the result is the same bit for bit.
#include <cstdint>

#include "d3/world_scratch.h"
#include "rewind/sim/thread_pool.h"

namespace rwd::sim::d3 {

/// Calls fn(begin, end) on ranges of at most `grain` items covering
/// [0, count), on the step's threads (ThreadPool::parallel_for).
template <class Fn>
void for_ranges(const WorldScratch& scratch, uint32_t count, uint32_t grain, Fn&& fn) {
  if (scratch.pool != nullptr) {
    scratch.pool->parallel_for(count, grain, fn);
    return;
  }
  if (count > 0) fn(uint32_t{0}, count);
}

}  // namespace rwd::sim::d3
