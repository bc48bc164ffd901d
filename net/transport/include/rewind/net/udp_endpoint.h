// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string_view>
#include <system_error>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>

#include "rewind/core/status.h"

namespace rwd::net {

/// Largest datagram the receive loop reads in bytes; bigger ones arrive
/// truncated to this size (still larger than kMaxDatagramBytes, so the
/// codec rejects them as oversize instead of misparsing a prefix).
inline constexpr size_t kReceiveBufferBytes = 2048;

/// Owns one UDP socket on a caller-provided io_context: an async receive loop
/// that hands every datagram to a handler, and non-blocking sends. Errors
/// (unreachable peers, ECONNREFUSED from ICMP, full send buffers) are counted
/// and reported to the optional error handler, never fatal. Use from the
/// io_context's thread only (one thread per endpoint). Handlers are never
/// called after close() or destruction, even if the io_context runs on.
class UdpEndpoint {
 public:
  using Endpoint = asio::ip::udp::endpoint;
  /// `bytes` is valid only during the call.
  using ReceiveHandler = std::function<void(std::span<const uint8_t> bytes, const Endpoint& from)>;
  /// `operation` is "send" or "receive".
  using ErrorHandler =
      std::function<void(std::string_view operation, const std::error_code& error)>;

  /// Binds to `address` (IPv4 or IPv6 literal, e.g. "127.0.0.1", "::",
  /// "0.0.0.0") and `port` (0 = an ephemeral port; see local_port()).
  /// Errors: kInvalidArgument for an unparsable address, kIo when the OS
  /// refuses the socket or the bind.
  static Result<UdpEndpoint> open(asio::io_context& io, std::string_view address, uint16_t port);

  UdpEndpoint(UdpEndpoint&&) noexcept = default;
  UdpEndpoint& operator=(UdpEndpoint&&) noexcept;
  UdpEndpoint(const UdpEndpoint&) = delete;
  UdpEndpoint& operator=(const UdpEndpoint&) = delete;
  ~UdpEndpoint();

  /// Starts (or restarts with a new handler) the receive loop. The handler
  /// runs inside io_context::run().
  void start_receiving(ReceiveHandler handler);
  /// Sends one datagram now without blocking. Returns false (and counts it)
  /// when the OS refused it or its buffer was full; UDP may lose it anyway.
  bool send_to(std::span<const uint8_t> bytes, const Endpoint& to);
  /// Stops receiving and closes the socket. Idempotent.
  void close();
  bool is_open() const;

  void set_error_handler(ErrorHandler handler);

  /// The bound address and port (the real port when opened with port 0).
  Endpoint local_endpoint() const;
  uint16_t local_port() const { return local_endpoint().port(); }

  /// Counters since open().
  struct Stats {
    uint64_t datagrams_sent = 0;
    uint64_t bytes_sent = 0;
    uint64_t send_errors = 0;  ///< refused or would block: not sent
    uint64_t datagrams_received = 0;
    uint64_t bytes_received = 0;
    uint64_t receive_errors = 0;
    std::error_code last_error;
  };
  const Stats& stats() const;

 private:
  struct State;
  explicit UdpEndpoint(std::shared_ptr<State> state);
  static void receive_next(const std::shared_ptr<State>& state);

  // Shared with the pending receive operation, so a completion that runs
  // after this object is gone still has valid memory to finish in.
  std::shared_ptr<State> state_;
};

}  // namespace rwd::net
