// SPDX-License-Identifier: MIT
#pragma once
// The step's threads (World3D::set_thread_pool): the stages hand ranges of
// independent work to the pool when the world has one, else run them on
// the stepping thread. Either way each range writes only what it owns, so
// the result is the same bit for bit.
#include <cstdint>

#include "d3/world_scratch.h"
#include "rewind/core/thread_pool.h"

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

// Batches per range when a colour is cut across the step's threads: enough
// work (256 constraints) to outweigh moving their bodies between cores.
inline constexpr uint32_t kBatchGrain = 32;

/// Calls fn(first, last) on ranges of contact batches that cover each
/// colour in turn, a colour's ranges at the same time on the step's threads
/// (they share no movable body, so how the colour is cut changes nothing),
/// then the overflow's batches, in order, on this thread. Without threads,
/// one call over every batch (they are stored colour by colour): a small
/// world's passes cost no walk over the colours.
template <class Fn>
void for_colors(const WorldScratch& scratch, Fn fn) {
  const uint32_t all = scratch.batch_start[kColorCount + 1];
  if (scratch.pool == nullptr || all == 0) {
    if (all > 0) fn(0, all);
    return;
  }
  for (uint32_t col = 0; col < kColorCount; ++col) {
    const uint32_t begin = scratch.batch_start[col];
    const uint32_t end = scratch.batch_start[col + 1];
    for_ranges(scratch, end - begin, kBatchGrain,
               [&](uint32_t first, uint32_t last) { fn(begin + first, begin + last); });
  }
  fn(scratch.batch_start[kColorCount], all);
}

}  // namespace rwd::sim::d3
