// SPDX-License-Identifier: MIT
#pragma once
// Durations of the server's tick loop on the wall clock (how long a tick
// took, how late it started), kept as a Prometheus histogram: fixed
// buckets, so recording a tick never allocates.
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>

namespace rwd::server {

class TickHistogram {
 public:
  /// Bucket bounds for the time a tick takes: 25 µs to 10 ms, around the
  /// 16.7 ms a tick may take at 60 Hz.
  static constexpr std::array<int64_t, 9> kBoundsNs = {
      25'000, 50'000, 100'000, 250'000, 500'000, 1'000'000, 2'500'000, 5'000'000, 10'000'000};
  /// Bucket bounds for how late a tick starts: a timer's wake-up (tens of
  /// microseconds) to several periods at 60 Hz (a tick a period or more
  /// late ran back to back with the one before it).
  static constexpr std::array<int64_t, 10> kLatenessBoundsNs = {
      50'000,    100'000,   250'000,    500'000,    1'000'000,
      2'500'000, 5'000'000, 10'000'000, 25'000'000, 100'000'000};
  static constexpr size_t kMaxBounds = 15;

  /// `bounds`: ascending upper bounds in nanoseconds, at most kMaxBounds,
  /// in storage that outlives the histogram (one of the arrays above).
  explicit TickHistogram(std::span<const int64_t> bounds = kBoundsNs) : bounds_(bounds) {
    if (bounds_.size() > kMaxBounds) bounds_ = bounds_.first(kMaxBounds);
  }

  void observe(std::chrono::nanoseconds elapsed) {
    const int64_t ns = elapsed.count() < 0 ? 0 : elapsed.count();
    size_t bucket = 0;
    while (bucket < bounds_.size() && ns > bounds_[bucket]) ++bucket;
    ++counts_[bucket];
    ++count_;
    sum_ns_ += static_cast<uint64_t>(ns);
    if (ns > max_ns_) max_ns_ = ns;
  }

  std::span<const int64_t> bounds() const { return bounds_; }
  /// Observations of at most bounds()[bucket] (not cumulative; the last
  /// bucket holds the larger ones).
  uint64_t bucket_count(size_t bucket) const { return counts_[bucket]; }
  size_t bucket_total() const { return bounds_.size() + 1; }
  uint64_t count() const { return count_; }
  uint64_t sum_ns() const { return sum_ns_; }
  int64_t max_ns() const { return max_ns_; }

 private:
  std::span<const int64_t> bounds_;
  std::array<uint64_t, kMaxBounds + 1> counts_{};
  uint64_t count_ = 0;
  uint64_t sum_ns_ = 0;
  int64_t max_ns_ = 0;
};

}  // namespace rwd::server
