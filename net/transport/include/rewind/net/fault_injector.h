// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>

#include "rewind/core/status.h"
#include "rewind/net/fault_config.h"

namespace rwd::net {

/// What happens to one packet.
struct PacketFate {
  bool dropped = false;
  bool duplicated = false;  ///< a second copy is delivered after duplicate_delay_ms
  bool reordered = false;   ///< delay_ms includes reorder_hold_ms
  uint32_t delay_ms = 0;
  uint32_t duplicate_delay_ms = 0;

  /// Copies that reach the wire: 0, 1 or 2.
  int copies() const { return dropped ? 0 : (duplicated ? 2 : 1); }
};

/// Decides packet fates from a seeded xoshiro256** stream, without sockets or
/// clocks. Every decide() consumes the same number of draws whatever the
/// outcome, so the n-th fate depends only on the seed and n.
class FaultInjector {
 public:
  /// Errors: those of validate_fault_config().
  static Result<FaultInjector> create(const FaultConfig& config);

  /// The fate of the next packet.
  PacketFate decide();
  const FaultConfig& config() const { return config_; }

 private:
  explicit FaultInjector(const FaultConfig& config);
  uint64_t next();
  double next_unit();        // [0, 1)
  uint32_t next_delay_ms();  // latency +- jitter, >= 0

  FaultConfig config_;
  uint64_t state_[4] = {};
};

/// Wraps a send function with a FaultInjector: drops, duplicates, delays and
/// reorders datagrams on the caller's io_context (one steady_timer for the
/// whole queue). At most `max_queued` datagrams wait at once; more are
/// dropped and counted. Use from the io_context's thread only. Datagrams
/// still queued when the link is destroyed are discarded.
class FaultyLink {
 public:
  using Endpoint = asio::ip::udp::endpoint;
  /// The real send path, usually UdpEndpoint::send_to.
  using SendFunction = std::function<void(std::span<const uint8_t> bytes, const Endpoint& to)>;
  static constexpr size_t kDefaultMaxQueued = 4096;
  /// Largest UDP payload; bigger sends are refused and counted.
  static constexpr size_t kMaxPayloadBytes = 65507;

  /// Errors: those of validate_fault_config(); kInvalidArgument for an empty
  /// send function or max_queued 0.
  static Result<FaultyLink> create(asio::io_context& io, const FaultConfig& config,
                                   SendFunction send, size_t max_queued = kDefaultMaxQueued);

  FaultyLink(FaultyLink&&) noexcept = default;
  FaultyLink& operator=(FaultyLink&&) noexcept;
  FaultyLink(const FaultyLink&) = delete;
  FaultyLink& operator=(const FaultyLink&) = delete;
  ~FaultyLink();

  /// Offers one datagram to the link. Zero-delay copies go out before this
  /// returns; the rest when their timer expires.
  void send(std::span<const uint8_t> bytes, const Endpoint& to);

  /// Datagrams waiting for their delay to pass.
  size_t queued() const;

  /// Counters since create().
  struct Stats {
    uint64_t offered = 0;
    uint64_t dropped_loss = 0;
    uint64_t dropped_overflow = 0;  ///< queue full or payload too large
    uint64_t duplicated = 0;
    uint64_t reordered = 0;
    uint64_t delivered = 0;  ///< copies handed to the send function
  };
  const Stats& stats() const;

 private:
  struct State;
  explicit FaultyLink(std::shared_ptr<State> state);
  void shutdown();

  // Shared with the pending timer wait, which may complete after this
  // object is destroyed.
  std::shared_ptr<State> state_;
};

}  // namespace rwd::net
