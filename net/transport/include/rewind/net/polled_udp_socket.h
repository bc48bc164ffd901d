// SPDX-License-Identifier: MIT
#pragma once
// A UDP socket its owner reads by polling, once a tick, instead of waking
// for every datagram: the server's matches. It is not registered with any
// event loop, so a datagram arriving between ticks wakes nobody; drain()
// takes everything waiting in a batch a system call, and the datagrams a
// tick sends are queued and leave together (recvmmsg/sendmmsg on Linux,
// one call a datagram elsewhere). Never blocks. Not thread-safe: one
// thread (or strand) at a time.
#include <asio/ip/udp.hpp>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <system_error>
#include <vector>

#include "rewind/core/status.h"

namespace rwd::net {

class PolledUdpSocket {
 public:
  using Endpoint = asio::ip::udp::endpoint;
  /// `bytes` and `from` are valid only during the call.
  using ReceiveHandler = std::function<void(std::span<const uint8_t> bytes, const Endpoint& from)>;

  /// Largest datagram read, in bytes; bigger ones arrive cut to this size
  /// (still larger than any valid datagram, so decoders refuse them).
  static constexpr size_t kMaxDatagram = 2048;
  /// Datagrams a system call moves at most.
  static constexpr size_t kBatch = 32;

  /// Binds `address` (IPv4 or IPv6 literal) and `port` (0 = any free port;
  /// see local_port()). kInvalidArgument for a bad address, kIo when the OS
  /// refuses the socket or the bind.
  static Result<PolledUdpSocket> open(std::string_view address, uint16_t port);

  PolledUdpSocket(PolledUdpSocket&& other) noexcept;
  PolledUdpSocket& operator=(PolledUdpSocket&& other) noexcept;
  PolledUdpSocket(const PolledUdpSocket&) = delete;
  PolledUdpSocket& operator=(const PolledUdpSocket&) = delete;
  ~PolledUdpSocket();

  /// Hands every datagram waiting now to `handler`, up to `max`; returns
  /// how many. The handler may queue sends; it must not close the socket.
  size_t drain(const ReceiveHandler& handler, size_t max = 4096);
  /// Copies a datagram into the send queue (sent by flush_sends()).
  void queue_send(std::span<const uint8_t> bytes, const Endpoint& to);
  /// Sends the queued datagrams in order; the ones the OS refuses (a full
  /// buffer, an unreachable address) are counted and dropped. Returns how
  /// many were sent. The queue is empty afterwards.
  size_t flush_sends();
  /// Closes the socket, dropping anything queued. Idempotent.
  void close();
  bool is_open() const { return fd_ >= 0; }
  uint16_t local_port() const { return local_.port(); }
  const Endpoint& local_endpoint() const { return local_; }

  /// Counters since open().
  struct Stats {
    uint64_t datagrams_sent = 0;
    uint64_t bytes_sent = 0;
    uint64_t send_errors = 0;
    uint64_t datagrams_received = 0;
    uint64_t bytes_received = 0;
    uint64_t receive_errors = 0;  ///< ICMP errors and the like; the socket goes on
    std::error_code last_error;
  };
  const Stats& stats() const { return stats_; }

 private:
  PolledUdpSocket(int fd, Endpoint local);

  struct Queued {
    size_t offset = 0;
    size_t size = 0;
    Endpoint to;
  };
  int fd_ = -1;
  Endpoint local_;
  Stats stats_;
  std::vector<uint8_t> receive_buffer_;  // kBatch datagrams of kMaxDatagram bytes
  std::vector<uint8_t> queued_bytes_;
  std::vector<Queued> queued_;
};

}  // namespace rwd::net
