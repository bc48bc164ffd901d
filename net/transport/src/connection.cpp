// SPDX-License-Identifier: MIT
#include "rewind/net/connection.h"

#include <algorithm>
#include <cstdlib>

#include "rewind/net/envelope_codec.h"

namespace rwd::net {
namespace {

// Each ack_bits word covers the 32 sequences before `ack`.
constexpr uint32_t kAckBits = 32;
// RFC 6298 clock granularity term G and our clamps (games need far shorter
// timeouts than TCP's 1 s minimum; 3 s caps a wild variance).
constexpr int64_t kRtoGranularityUs = 1'000;
constexpr int64_t kMinRtoUs = 10'000;
constexpr int64_t kMaxRtoUs = 3'000'000;
constexpr int64_t kInitialRtoUs = 1'000'000;
constexpr int64_t kMaxRttSampleUs = 60'000'000;
// Loss EWMA weight: ~32 packets of memory, half a second at 60 Hz.
constexpr double kLossWeight = 1.0 / 32.0;

}  // namespace

Connection::Connection(TimePoint created, uint64_t connection_id, uint32_t first_sequence)
    : connection_id_(connection_id),
      next_sequence_(first_sequence),
      unresolved_(first_sequence),
      last_receive_time_(created) {}

uint32_t Connection::stamp(v1::Envelope& envelope, TimePoint now) {
  const uint32_t sequence = next_sequence_;
  // The slot about to be reused holds sequence - kSendRingSize: count its
  // fate (and anything older) before its record is overwritten.
  resolve_until(sequence - kSendRingSize + 1);
  SentPacket& p = slot(sequence);
  p.sequence = sequence;
  p.in_use = true;
  p.acked = false;
  p.sent_at = now;
  ++next_sequence_;
  ++stats_.sent;

  envelope.set_protocol_version(kProtocolVersion);
  envelope.set_connection_id(connection_id_);
  envelope.set_sequence(sequence);
  envelope.set_ack(has_received_ ? remote_newest_ : 0);
  envelope.set_ack_bits(has_received_ ? remote_bits_ : 0);
  return sequence;
}

ReceiveResult Connection::on_receive(const v1::Envelope& envelope, TimePoint now) {
  ReceiveResult result;
  const uint32_t sequence = envelope.sequence();
  if (!has_received_) {
    has_received_ = true;
    remote_newest_ = sequence;
    remote_bits_ = 0;
    result.newest = true;
  } else {
    // C++20 defines the modular conversion, so this is the signed distance.
    const auto delta = static_cast<int32_t>(sequence - remote_newest_);
    if (delta == 0) {
      result.kind = ReceiveKind::kDuplicate;
    } else if (delta > 0) {
      const auto shift = static_cast<uint32_t>(delta);
      if (shift < kAckBits) {
        remote_bits_ = (remote_bits_ << shift) | (1u << (shift - 1));
      } else if (shift == kAckBits) {
        remote_bits_ = 1u << (kAckBits - 1);  // only the old newest stays in the window
      } else {
        remote_bits_ = 0;
      }
      remote_newest_ = sequence;
      result.newest = true;
    } else {
      const int64_t age = -static_cast<int64_t>(delta);
      if (age > static_cast<int64_t>(kAckBits)) {
        result.kind = ReceiveKind::kTooOld;
      } else {
        const uint32_t bit = 1u << (age - 1);
        if ((remote_bits_ & bit) != 0) {
          result.kind = ReceiveKind::kDuplicate;
        } else {
          remote_bits_ |= bit;
        }
      }
    }
  }

  switch (result.kind) {
    case ReceiveKind::kDuplicate:
      ++stats_.duplicates;
      return result;
    case ReceiveKind::kTooOld:
      ++stats_.too_old;
      return result;
    case ReceiveKind::kNew:
      break;
  }
  ++stats_.received;
  last_receive_time_ = now;
  apply_acks(envelope.ack(), envelope.ack_bits(), now, result);
  return result;
}

void Connection::apply_acks(uint32_t ack, uint32_t ack_bits, TimePoint now, ReceiveResult& result) {
  // An ack for a sequence we have not sent is forged or garbage; one older
  // than the ring tells us nothing we can still use.
  const uint32_t age = next_sequence_ - ack;  // >= 1 when `ack` was sent
  if (!sequence_less(ack, next_sequence_) || age > kSendRingSize) return;

  for (uint32_t i = 0; i <= kAckBits; ++i) {
    if (i > 0 && (ack_bits & (1u << (i - 1))) == 0) continue;
    const uint32_t sequence = ack - i;
    SentPacket& p = slot(sequence);
    if (!p.in_use || p.sequence != sequence || p.acked) continue;
    p.acked = true;
    ++stats_.acked;
    result.acked_storage[result.acked_count++] = sequence;
    // Only the newest ack times a packet: older ones reached us through
    // ack_bits of later packets, so their delay includes the peer's wait.
    if (i == 0) {
      const auto rtt = std::chrono::duration_cast<std::chrono::microseconds>(now - p.sent_at);
      add_rtt_sample(std::max<int64_t>(0, rtt.count()));
    }
  }
  // Sequences older than ack - 32 can no longer be acknowledged by any
  // packet newer than this one: their fate is known now.
  resolve_until(ack - kAckBits);
}

void Connection::resolve_until(uint32_t end) {
  while (sequence_less(unresolved_, end) && sequence_less(unresolved_, next_sequence_)) {
    resolve_one(unresolved_);
    ++unresolved_;
  }
}

void Connection::resolve_one(uint32_t sequence) {
  const SentPacket& p = slot(sequence);
  if (!p.in_use || p.sequence != sequence) return;
  const double lost = p.acked ? 0.0 : 1.0;
  if (!p.acked) ++stats_.lost;
  loss_ += kLossWeight * (lost - loss_);
}

void Connection::add_rtt_sample(int64_t rtt_us) {
  // A minute bounds the arithmetic below; no live peer answers that slowly.
  rtt_us = std::min(rtt_us, kMaxRttSampleUs);
  last_rtt_us_ = rtt_us;
  if (!has_rtt_) {
    has_rtt_ = true;
    srtt_us_ = rtt_us;
    rttvar_us_ = rtt_us / 2;
    return;
  }
  // RFC 6298 section 2.3 with alpha = 1/8, beta = 1/4; RTTVAR uses the old SRTT.
  rttvar_us_ = (3 * rttvar_us_ + std::llabs(srtt_us_ - rtt_us) + 2) / 4;
  srtt_us_ = (7 * srtt_us_ + rtt_us + 4) / 8;
}

int64_t Connection::retransmit_timeout_us() const {
  if (!has_rtt_) return kInitialRtoUs;
  const int64_t rto = srtt_us_ + std::max(kRtoGranularityUs, 4 * rttvar_us_);
  return std::clamp(rto, kMinRtoUs, kMaxRtoUs);
}

}  // namespace rwd::net
