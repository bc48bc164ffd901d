// SPDX-License-Identifier: MIT
#pragma once
// How long the server's tick callbacks take on the wall clock, kept as a
// Prometheus histogram: fixed buckets, so recording a tick never allocates.
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>

namespace rwd::server {

class TickHistogram {
 public:
  /// Upper bounds of the buckets (a last, unbounded one follows): 25 µs to
  /// 10 ms, around the 16.7 ms a tick may take at 60 Hz.
  static constexpr std::array<int64_t, 9> kBoundsNs = {
      25'000, 50'000, 100'000, 250'000, 500'000, 1'000'000, 2'500'000, 5'000'000, 10'000'000};

  void observe(std::chrono::nanoseconds elapsed) {
    const int64_t ns = elapsed.count() < 0 ? 0 : elapsed.count();
    size_t bucket = 0;
    while (bucket < kBoundsNs.size() && ns > kBoundsNs[bucket]) ++bucket;
    ++counts_[bucket];
    ++count_;
    sum_ns_ += static_cast<uint64_t>(ns);
    if (ns > max_ns_) max_ns_ = ns;
  }

  /// Ticks that took at most kBoundsNs[bucket] (not cumulative; the last
  /// bucket holds the slower ones).
  uint64_t bucket_count(size_t bucket) const { return counts_[bucket]; }
  static constexpr size_t bucket_total() { return kBoundsNs.size() + 1; }
  uint64_t count() const { return count_; }
  uint64_t sum_ns() const { return sum_ns_; }
  int64_t max_ns() const { return max_ns_; }

 private:
  std::array<uint64_t, kBoundsNs.size() + 1> counts_{};
  uint64_t count_ = 0;
  uint64_t sum_ns_ = 0;
  int64_t max_ns_ = 0;
};

}  // namespace rwd::server
