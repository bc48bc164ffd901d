// SPDX-License-Identifier: MIT
#pragma once
#include <chrono>
#include <cstdint>
#include <random>

#include "rewind/core/splitmix64.h"

namespace rwd::net {

/// Makes 64-bit connection ids that a third party cannot predict, so a
/// spoofed datagram cannot name someone else's live connection. Each id mixes
/// a 256-bit-seeded stream, a counter and the current time through a strong
/// 64-bit finalizer; ids are never 0 (0 means "no connection yet" on the
/// wire). Unpredictable only as long as the seed is: seed from OS entropy
/// (from_os_entropy()) in a server. Ids authenticate nothing by themselves;
/// join tokens do. Not thread-safe.
class ConnectionIdGenerator {
 public:
  /// Deterministic stream for `seed` (tests); time still mixes into next().
  explicit ConnectionIdGenerator(uint64_t seed)
      : state_(splitmix64_mix(seed ^ 0x5EED'0F1D'C0DE'D00Dull)) {}

  /// Seeded from std::random_device and the clock: the constructor for servers.
  static ConnectionIdGenerator from_os_entropy() {
    std::random_device device;
    const uint64_t high = device();
    const uint64_t low = device();
    const auto now =
        static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
    return ConnectionIdGenerator((high << 32 | low) ^ splitmix64_mix(now));
  }

  /// A fresh id mixing in the current steady-clock time.
  uint64_t next() {
    return next(static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()));
  }

  /// A fresh id mixing in caller-provided `time_entropy` (e.g. a clock read
  /// in nanoseconds); deterministic for a fixed seed and inputs.
  uint64_t next(uint64_t time_entropy) {
    // Weyl step keeps the stream distinct even if time_entropy repeats; the
    // counter guarantees distinct inputs to the bijective mix within one
    // generator, so ids only collide after 2^64 calls.
    state_ += kSplitMix64Gamma;
    ++counter_;
    // splitmix64's mix is a bijection with full avalanche.
    uint64_t id = splitmix64_mix(state_ ^ splitmix64_mix(time_entropy + counter_));
    // A zero would read as "no connection"; resample rather than bias.
    while (id == 0) id = splitmix64_mix(++state_);
    return id;
  }

 private:
  uint64_t state_;
  uint64_t counter_ = 0;
};

}  // namespace rwd::net
