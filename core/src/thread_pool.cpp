// SPDX-License-Identifier: MIT
// ThreadPool: workers that take ranges of one parallel_for at a time.
//
// A job is cut into at most one range per thread, and thread t (the caller
// is 0, the workers 1 and up) takes range t first: a step's passes cut the
// same data the same way, so each thread finds its range's data in its own
// cache from the pass before, instead of moving it from another core
// (which on a 2-core machine cost more than the second core gained). Then
// it takes any range nobody has, so a worker that is late (asleep, or its
// core busy) never holds the caller up: the caller does that range itself.
//
// Ranges are claimed in one word: the job's generation in the high 32 bits,
// a bit per claimed range in the low 31 and a closed bit. A thread claims
// range r by setting bit r with the generation it read the job under; the
// caller waits until every range is done and closes the word before it
// writes the next job, so a late worker's claim on a finished job fails.
#include "rewind/core/thread_pool.h"

#include <algorithm>
#include <atomic>
#include <system_error>
#include <thread>
#include <vector>

namespace rwd {
namespace {

// A spin-wait hint, given once every kRelaxEvery looks rather than on each:
// on virtual machines the hypervisor takes a core that runs many of them in
// a row for a lock-holder's and deschedules it (pause-loop exiting), which
// turned a 0.4 us hand-over into 2.5 us on a 2-core cloud machine.
constexpr uint32_t kRelaxEvery = 64;
void cpu_relax(uint32_t spins) {
  if (spins % kRelaxEvery != 0) return;
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Idle workers look for the next job this many times (on the order of
// 100 us: a step's jobs follow one another within microseconds) before
// sleeping.
constexpr uint32_t kWorkerSpins = 1u << 17;
// The caller looks this many times for the last ranges to finish before
// yielding its core between looks.
constexpr uint32_t kCallerSpins = 1u << 14;
constexpr uint64_t kClosedBit = uint64_t{1} << 31;

uint64_t claims_of(uint32_t generation) {
  return static_cast<uint64_t>(generation) << 32;
}

}  // namespace

struct ThreadPool::Shared {
  // Each group on a cache line of its own: idle workers read `wake` in a
  // loop, every thread writes `claims` and `done`, and the caller writes
  // the job; sharing a line would make each of those writes stall the
  // other threads' reads.
  alignas(64) std::atomic<uint64_t> claims{claims_of(0) | kClosedBit};
  // The job of the claims' generation. Stored (release) before the claims
  // word that publishes it and after the one that closed the last job, so
  // a thread that reads a newer job than its claims word fails to claim.
  alignas(64) std::atomic<RangeFn> fn{nullptr};
  std::atomic<void*> context{nullptr};
  std::atomic<uint32_t> count{0};
  std::atomic<uint32_t> ranges{0};
  alignas(64) std::atomic<uint32_t> done{0};  ///< ranges of the job finished
  alignas(64) std::atomic<uint32_t> wake{0};  ///< bumped for each job and at shutdown
  std::atomic<bool> stop{false};
  alignas(64) std::atomic<uint32_t> sleepers{0};
  uint32_t generation = 0;  ///< the caller's count of jobs
  uint32_t threads = 1;
  std::vector<std::thread> workers;

  // Runs range `r` of the published job if nobody has claimed it. Returns
  // false when the job is closed (or already a newer one's).
  bool claim_and_run(uint32_t r) {
    for (;;) {
      uint64_t c = claims.load(std::memory_order_acquire);
      const RangeFn f = fn.load(std::memory_order_acquire);
      void* const ctx = context.load(std::memory_order_acquire);
      const uint32_t n = count.load(std::memory_order_acquire);
      const uint32_t k = ranges.load(std::memory_order_acquire);
      if ((c & kClosedBit) != 0) return false;
      const uint64_t bit = uint64_t{1} << r;
      if (r >= k || (c & bit) != 0) return true;  // no such range, or taken
      if (!claims.compare_exchange_weak(c, c | bit, std::memory_order_acq_rel)) continue;
      const uint64_t begin = static_cast<uint64_t>(n) * r / k;
      const uint64_t end = static_cast<uint64_t>(n) * (r + 1) / k;
      f(ctx, static_cast<uint32_t>(begin), static_cast<uint32_t>(end));
      done.fetch_add(1, std::memory_order_release);
      return true;
    }
  }

  // Thread `self`'s own range, then every other one nobody has taken.
  void take_ranges(uint32_t self) {
    for (uint32_t k = 0; k < threads; ++k) {
      if (!claim_and_run((self + k) % threads)) return;
    }
  }

  void work(uint32_t self) {
    // The value the pool started with, not a fresh look: a worker that
    // starts after the first job (or the shutdown) was announced must
    // still see it as news.
    uint32_t seen = 0;
    for (;;) {
      uint32_t spins = 0;
      uint32_t now;
      while ((now = wake.load(std::memory_order_acquire)) == seen) {
        if (++spins < kWorkerSpins) {
          cpu_relax(spins);
          continue;
        }
        // Announced before the last look, so a caller that bumps `wake`
        // after it sees a sleeper to notify.
        sleepers.fetch_add(1, std::memory_order_seq_cst);
        if (wake.load(std::memory_order_seq_cst) == seen)
          wake.wait(seen, std::memory_order_seq_cst);
        sleepers.fetch_sub(1, std::memory_order_seq_cst);
        spins = 0;
      }
      seen = now;
      if (stop.load(std::memory_order_acquire)) return;
      take_ranges(self);
    }
  }
};

ThreadPool::ThreadPool(uint32_t threads)
    : threads_(std::clamp<uint32_t>(threads, 1, kMaxThreads)), shared_(std::make_unique<Shared>()) {
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
  // WebAssembly without pthreads has no threads to start, and there a
  // failing std::thread aborts (exceptions are off): the caller alone runs
  // everything, as a pool of one would.
  threads_ = 1;
#endif
  shared_->workers.reserve(threads_ - 1);
  for (uint32_t i = 1; i < threads_; ++i) {
    try {
      shared_->workers.emplace_back([s = shared_.get(), i] { s->work(i); });
    } catch (const std::system_error&) {
      // The system gave no more threads (a limit, or a build without
      // them, as WebAssembly without pthreads): the pool runs on those it
      // got, which changes how long a step takes, never its result.
      break;
    }
  }
  threads_ = 1 + static_cast<uint32_t>(shared_->workers.size());
  shared_->threads = threads_;
}

ThreadPool::~ThreadPool() {
  shared_->stop.store(true, std::memory_order_release);
  shared_->wake.fetch_add(1, std::memory_order_seq_cst);
  shared_->wake.notify_all();
  for (std::thread& t : shared_->workers) t.join();
}

void ThreadPool::run(uint32_t count, uint32_t ranges, RangeFn fn, void* context) {
  Shared& s = *shared_;
  const uint32_t generation = ++s.generation;
  s.fn.store(fn, std::memory_order_release);
  s.context.store(context, std::memory_order_release);
  s.count.store(count, std::memory_order_release);
  s.ranges.store(ranges, std::memory_order_release);
  s.done.store(0, std::memory_order_relaxed);
  s.claims.store(claims_of(generation), std::memory_order_release);
  s.wake.fetch_add(1, std::memory_order_seq_cst);
  if (s.sleepers.load(std::memory_order_seq_cst) > 0) s.wake.notify_all();
  s.take_ranges(0);
  uint32_t spins = 0;
  while (s.done.load(std::memory_order_acquire) < ranges) {
    if (++spins < kCallerSpins) {
      cpu_relax(spins);
    } else {
      std::this_thread::yield();
    }
  }
  // Closed before the next job is written: see Shared.
  s.claims.store(claims_of(generation) | kClosedBit, std::memory_order_seq_cst);
}

}  // namespace rwd
