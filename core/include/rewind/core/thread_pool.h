// SPDX-License-Identifier: MIT
#pragma once
// Worker threads a world's step hands its independent pieces of work to.
//
// The step cuts work only where the pieces write disjoint data and read
// nothing another piece writes (the narrowphase's pairs, the bodies of a
// step's integration, the contact batches of one colour), so which thread
// runs a piece, and how many threads there are, never changes a result: a
// world steps bit for bit the same on 1, 2, 4 or 8 threads, and with no
// pool at all.
//
// Lifetime and use: a pool outlives every world it is given to
// (World3D::set_thread_pool). One thread at a time runs parallel_for on a
// pool; worlds stepped one after another on the same thread may share it.
// Workers spin for a short while after a piece of work (the next one
// usually follows within microseconds), then sleep until the next.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <type_traits>

namespace rwd {

class ThreadPool {
 public:
  /// Most threads a pool runs (the caller included).
  static constexpr uint32_t kMaxThreads = 31;

  /// A pool of `threads` threads counting the caller of parallel_for, so
  /// `threads - 1` workers are started; 1 runs everything on the caller.
  /// Clamped to [1, kMaxThreads]; when the system refuses a thread, the
  /// pool runs with the ones it got (threads() says how many).
  explicit ThreadPool(uint32_t threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// Threads that run a parallel_for (workers and the caller).
  uint32_t threads() const { return threads_; }

  /// Calls fn(begin, end) on consecutive ranges that cover [0, count) once
  /// each and returns when every range is done. [0, count) is cut into
  /// equal ranges, one per thread at most and none shorter than `grain`
  /// (at least 1) items, that run at the same time, the k-th on thread k
  /// when it is free (the caller is thread 0), so a pass that cuts the same
  /// data the same way as the pass before finds it in the same core's
  /// cache. When that makes a single range, it runs on the caller alone
  /// and no worker is woken. fn must write only what its own range owns,
  /// and must not call parallel_for on the same pool.
  template <class Fn>
  void parallel_for(uint32_t count, uint32_t grain, Fn&& fn) {
    if (grain == 0) grain = 1;
    const uint32_t ranges = std::min(threads_, count / grain);
    if (ranges <= 1) {
      if (count > 0) fn(uint32_t{0}, count);
      return;
    }
    using F = std::remove_reference_t<Fn>;  // may be const
    run(count, ranges, &call<F>, const_cast<void*>(static_cast<const void*>(&fn)));
  }

 private:
  using RangeFn = void (*)(void* context, uint32_t begin, uint32_t end);
  template <class Fn>
  static void call(void* context, uint32_t begin, uint32_t end) {
    (*static_cast<Fn*>(context))(begin, end);
  }
  void run(uint32_t count, uint32_t ranges, RangeFn fn, void* context);

  struct Shared;
  uint32_t threads_ = 1;
  std::unique_ptr<Shared> shared_;
};

}  // namespace rwd
