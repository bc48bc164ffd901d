// SPDX-License-Identifier: MIT
#pragma once
// The network conditions a FaultyLink simulates, apart from the link itself
// so that configurations (ClientConfig::faults) can be named without
// pulling in sockets.
#include <cstdint>

#include "rewind/core/status.h"

namespace rwd::net {

/// Network conditions to simulate on a send path.
struct FaultConfig {
  uint32_t latency_ms = 0;  ///< one-way base delay, [0, 10000] ms
  uint32_t jitter_ms = 0;   ///< delay varies uniformly by +-jitter_ms (floored at 0), [0, 10000]
  double loss = 0.0;        ///< probability a packet is dropped, [0, 1]
  double duplicate = 0.0;   ///< probability a sent packet is delivered twice, [0, 1]
  double reorder = 0.0;     ///< probability a packet is held back so later ones overtake it, [0, 1]
  uint64_t seed = 1;        ///< same seed + same sequence of sends => same fates
  uint32_t reorder_hold_ms = 20;  ///< extra delay of a held-back packet, [1, 10000] ms
};

/// kInvalidArgument naming the field when a probability is outside [0, 1]
/// (or NaN), a delay is above 10000 ms, or reorder_hold_ms is 0.
Status validate_fault_config(const FaultConfig& config);

}  // namespace rwd::net
