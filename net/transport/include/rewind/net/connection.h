// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>

#include "rewind/net/clock.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::net {

/// True when sequence `a` is older than `b`, with 32-bit wrap-around (RFC
/// 1982 serial arithmetic: `a` is older if b - a, mod 2^32, is in [1, 2^31)).
constexpr bool sequence_less(uint32_t a, uint32_t b) {
  return a != b && static_cast<uint32_t>(b - a) < 0x8000'0000u;
}

/// How a received packet relates to the packets received before it.
enum class ReceiveKind : uint8_t {
  kNew,        ///< never seen: process it
  kDuplicate,  ///< already received: drop it
  kTooOld,     ///< older than the 33-packet ack window: cannot tell, drop it
};

/// What on_receive learned from one packet.
struct ReceiveResult {
  /// At most the peer's `ack` plus its 32 `ack_bits`.
  static constexpr size_t kMaxAcked = 33;

  ReceiveKind kind = ReceiveKind::kNew;
  /// The packet is the newest the peer has sent so far (false when it
  /// arrived out of order or was dropped).
  bool newest = false;
  std::array<uint32_t, kMaxAcked> acked_storage{};
  uint8_t acked_count = 0;

  /// Our sequences that this packet acknowledged for the first time, newest
  /// first. Higher layers stop resending what these packets carried.
  std::span<const uint32_t> acked() const& { return {acked_storage.data(), acked_count}; }
  /// Deleted: a span into a temporary result would dangle (e.g. in a
  /// range-for over `conn.on_receive(...).acked()`).
  std::span<const uint32_t> acked() const&& = delete;
  bool is_new() const { return kind == ReceiveKind::kNew; }
};

/// Per-peer packet protocol state without sockets (GGPO's udp_proto / GGRS's
/// protocol.rs without the socket): numbers outgoing packets, tracks which
/// incoming ones arrived (newest `ack` + 32 `ack_bits`, duplicate detection),
/// learns from the peer's acks which of ours arrived, and estimates RTT (RFC
/// 6298) and packet loss. Not thread-safe; one instance per peer.
class Connection {
 public:
  /// Send times and ack flags of the last kSendRingSize outgoing packets.
  static constexpr uint32_t kSendRingSize = 256;

  /// `created` starts the receive-timeout clock. `connection_id` is written
  /// into every stamped envelope (0 before the handshake). `first_sequence`
  /// is the sequence of the first packet sent; it starts at 1 so that a
  /// peer's initial ack of 0 acknowledges nothing.
  explicit Connection(TimePoint created, uint64_t connection_id = 0, uint32_t first_sequence = 1);

  uint64_t connection_id() const { return connection_id_; }
  /// The client learns its id from JoinAccept.
  void set_connection_id(uint64_t id) { connection_id_ = id; }

  /// Fills protocol_version, connection_id, sequence, ack and ack_bits of an
  /// outgoing envelope and records its send time. Returns its sequence.
  /// Every stamped envelope must be sent (or counted lost by the caller's
  /// link): sequences are never reused.
  uint32_t stamp(rwd::v1::Envelope& envelope, TimePoint now);

  /// Processes a decoded envelope from this peer: classifies its sequence,
  /// and for new packets applies the peer's ack/ack_bits (reporting newly
  /// acknowledged sequences and taking an RTT sample from the `ack` packet's
  /// send time). Duplicates and too-old packets change nothing but counters.
  ReceiveResult on_receive(const rwd::v1::Envelope& envelope, TimePoint now);

  /// The sequence the next stamp() will use.
  uint32_t next_sequence() const { return next_sequence_; }
  /// Newest sequence received from the peer (meaningful when has_received()).
  uint32_t remote_ack() const { return remote_newest_; }
  /// Bit i set: sequence remote_ack() - 1 - i was received too.
  uint32_t remote_ack_bits() const { return remote_bits_; }
  bool has_received() const { return has_received_; }
  /// Time of the last new packet from the peer (`created` before any).
  TimePoint last_receive_time() const { return last_receive_time_; }
  /// True when nothing new arrived from the peer for at least `timeout`.
  bool timed_out(TimePoint now, std::chrono::microseconds timeout) const {
    return now - last_receive_time_ >= timeout;
  }

  /// True once at least one RTT sample was taken.
  bool has_rtt() const { return has_rtt_; }
  /// Smoothed round-trip time in microseconds (RFC 6298 SRTT; 0 before the
  /// first sample).
  int64_t smoothed_rtt_us() const { return srtt_us_; }
  /// Round-trip time variation in microseconds (RFC 6298 RTTVAR).
  int64_t rtt_variance_us() const { return rttvar_us_; }
  /// Last raw RTT sample in microseconds.
  int64_t last_rtt_us() const { return last_rtt_us_; }
  /// RFC 6298 retransmission timeout SRTT + max(1 ms, 4 * RTTVAR), clamped to
  /// [10 ms, 3 s]; 1 s before the first sample (RFC 6298 initial value).
  int64_t retransmit_timeout_us() const;

  /// Estimated fraction of our packets the peer never acknowledged, in
  /// [0, 1]: exponential moving average (weight 1/32) over packets whose
  /// fate is known, i.e. acked or too old to be acked any more.
  double packet_loss() const { return loss_; }

  /// Counters since construction.
  struct Stats {
    uint64_t sent = 0;
    uint64_t received = 0;    ///< new packets
    uint64_t duplicates = 0;  ///< ReceiveKind::kDuplicate
    uint64_t too_old = 0;     ///< ReceiveKind::kTooOld
    uint64_t acked = 0;       ///< our packets acknowledged
    uint64_t lost = 0;        ///< our packets that fell out of the ack window unacknowledged
  };
  const Stats& stats() const { return stats_; }

 private:
  struct SentPacket {
    uint32_t sequence = 0;
    bool in_use = false;
    bool acked = false;
    TimePoint sent_at{};
  };

  SentPacket& slot(uint32_t sequence) { return sent_[sequence % kSendRingSize]; }
  void apply_acks(uint32_t ack, uint32_t ack_bits, TimePoint now, ReceiveResult& result);
  void resolve_until(uint32_t end);
  void resolve_one(uint32_t sequence);
  void add_rtt_sample(int64_t rtt_us);

  uint64_t connection_id_;
  uint32_t next_sequence_;
  // Oldest sent sequence whose fate (acked or lost) is not yet counted.
  uint32_t unresolved_;

  bool has_received_ = false;
  uint32_t remote_newest_ = 0;
  uint32_t remote_bits_ = 0;
  TimePoint last_receive_time_{};

  bool has_rtt_ = false;
  int64_t srtt_us_ = 0;
  int64_t rttvar_us_ = 0;
  int64_t last_rtt_us_ = 0;
  double loss_ = 0.0;

  std::array<SentPacket, kSendRingSize> sent_{};
  Stats stats_;
};

}  // namespace rwd::net
