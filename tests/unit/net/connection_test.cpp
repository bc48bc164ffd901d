// SPDX-License-Identifier: MIT
#include "rewind/net/connection.h"
#include "rewind/net/envelope_codec.h"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

namespace rwd::net {
namespace {

using std::chrono::milliseconds;

const TimePoint kT0 = TimePoint{} + std::chrono::hours(1);

v1::Envelope packet(uint32_t sequence, uint32_t ack = 0, uint32_t ack_bits = 0) {
  v1::Envelope e;
  e.set_sequence(sequence);
  e.set_ack(ack);
  e.set_ack_bits(ack_bits);
  e.mutable_ping();
  return e;
}

std::vector<uint32_t> acked(const ReceiveResult& r) {
  return {r.acked().begin(), r.acked().end()};
}

TEST(SequenceLess, WrapsAround) {
  EXPECT_TRUE(sequence_less(1, 2));
  EXPECT_FALSE(sequence_less(2, 1));
  EXPECT_FALSE(sequence_less(5, 5));
  EXPECT_TRUE(sequence_less(0xFFFF'FFFFu, 0));
  EXPECT_TRUE(sequence_less(0xFFFF'FFF0u, 5));
  EXPECT_FALSE(sequence_less(5, 0xFFFF'FFF0u));
}

TEST(Connection, StampFillsHeaderAndCounts) {
  Connection c(kT0, 0xABCD, 10);
  v1::Envelope e;
  EXPECT_EQ(c.stamp(e, kT0), 10u);
  EXPECT_EQ(e.protocol_version(), kProtocolVersion);
  EXPECT_EQ(e.connection_id(), 0xABCDu);
  EXPECT_EQ(e.sequence(), 10u);
  EXPECT_EQ(e.ack(), 0u);
  EXPECT_EQ(e.ack_bits(), 0u);
  EXPECT_EQ(c.stamp(e, kT0), 11u);
  EXPECT_EQ(c.next_sequence(), 12u);
  EXPECT_EQ(c.stats().sent, 2u);
}

TEST(Connection, AckBitsAcrossGapsAndReordering) {
  Connection c(kT0);
  EXPECT_TRUE(c.on_receive(packet(100), kT0).is_new());
  EXPECT_EQ(c.remote_ack(), 100u);
  EXPECT_EQ(c.remote_ack_bits(), 0u);

  // 101 and 102 lost, 103 arrives: bit 2 (= 100) set.
  ReceiveResult r = c.on_receive(packet(103), kT0);
  EXPECT_TRUE(r.is_new());
  EXPECT_TRUE(r.newest);
  EXPECT_EQ(c.remote_ack(), 103u);
  EXPECT_EQ(c.remote_ack_bits(), 0b100u);

  // 101 arrives late: out of order but new.
  r = c.on_receive(packet(101), kT0);
  EXPECT_TRUE(r.is_new());
  EXPECT_FALSE(r.newest);
  EXPECT_EQ(c.remote_ack(), 103u);
  EXPECT_EQ(c.remote_ack_bits(), 0b110u);  // 101 is bit 1, 100 is bit 2

  // The header we stamp carries exactly this state.
  v1::Envelope out;
  (void)c.stamp(out, kT0);
  EXPECT_EQ(out.ack(), 103u);
  EXPECT_EQ(out.ack_bits(), 0b110u);

  // Jump by exactly 32: only the old newest survives, in the top bit.
  (void)c.on_receive(packet(135), kT0);
  EXPECT_EQ(c.remote_ack_bits(), 0x8000'0000u);
  // Jump by 33: nothing survives.
  (void)c.on_receive(packet(168), kT0);
  EXPECT_EQ(c.remote_ack_bits(), 0u);
  // Now 135 is 33 behind: too old to tell.
  r = c.on_receive(packet(135), kT0);
  EXPECT_EQ(r.kind, ReceiveKind::kTooOld);
  // 136 is exactly 32 behind: still in the window, and new.
  r = c.on_receive(packet(136), kT0);
  EXPECT_TRUE(r.is_new());
  EXPECT_EQ(c.remote_ack_bits(), 0x8000'0000u);
  EXPECT_EQ(c.stats().too_old, 1u);
}

TEST(Connection, DetectsDuplicates) {
  Connection c(kT0);
  (void)c.on_receive(packet(5), kT0);
  (void)c.on_receive(packet(7), kT0);
  EXPECT_EQ(c.on_receive(packet(7), kT0).kind, ReceiveKind::kDuplicate);  // newest again
  EXPECT_EQ(c.on_receive(packet(5), kT0).kind, ReceiveKind::kDuplicate);  // in ack_bits
  EXPECT_TRUE(c.on_receive(packet(6), kT0).is_new());
  EXPECT_EQ(c.on_receive(packet(6), kT0).kind, ReceiveKind::kDuplicate);
  EXPECT_EQ(c.stats().duplicates, 3u);
  EXPECT_EQ(c.stats().received, 3u);
  EXPECT_EQ(c.remote_ack_bits(), 0b11u);
}

TEST(Connection, DuplicatesDoNotRefreshReceiveTimeOrAcks) {
  Connection a(kT0);
  v1::Envelope out;
  (void)a.stamp(out, kT0);  // sequence 1
  ASSERT_TRUE(a.on_receive(packet(50), kT0 + milliseconds(10)).is_new());
  // A replayed copy of 50 now carrying an ack must not count.
  ReceiveResult r = a.on_receive(packet(50, 1, 0), kT0 + milliseconds(500));
  EXPECT_EQ(r.kind, ReceiveKind::kDuplicate);
  EXPECT_TRUE(r.acked().empty());
  EXPECT_EQ(a.last_receive_time(), kT0 + milliseconds(10));
  EXPECT_TRUE(a.timed_out(kT0 + milliseconds(1010), milliseconds(1000)));
  EXPECT_FALSE(a.timed_out(kT0 + milliseconds(1009), milliseconds(1000)));
}

TEST(Connection, ReceiveAcrossSequenceWrap) {
  Connection c(kT0);
  (void)c.on_receive(packet(0xFFFF'FFFEu), kT0);
  EXPECT_TRUE(c.on_receive(packet(1), kT0).is_new());  // skips 0xFFFFFFFF and 0
  EXPECT_EQ(c.remote_ack(), 1u);
  EXPECT_EQ(c.remote_ack_bits(), 0b100u);
  EXPECT_TRUE(c.on_receive(packet(0), kT0).is_new());
  EXPECT_TRUE(c.on_receive(packet(0xFFFF'FFFFu), kT0).is_new());
  EXPECT_EQ(c.remote_ack_bits(), 0b111u);
  EXPECT_EQ(c.on_receive(packet(0xFFFF'FFFFu), kT0).kind, ReceiveKind::kDuplicate);
}

// Two connections talking through a lossy, in-order pipe.
TEST(Connection, PeersLearnWhichPacketsArrived) {
  Connection a(kT0);
  Connection b(kT0);
  std::vector<uint32_t> a_acked;
  for (int i = 0; i < 10; ++i) {
    v1::Envelope to_b;
    to_b.mutable_ping();
    const uint32_t seq = a.stamp(to_b, kT0);
    if (seq % 3 != 0) (void)b.on_receive(to_b, kT0);  // b misses 3, 6, 9
    v1::Envelope to_a;
    to_a.mutable_pong();
    (void)b.stamp(to_a, kT0);
    const ReceiveResult r = a.on_receive(to_a, kT0);
    for (uint32_t s : r.acked()) a_acked.push_back(s);
  }
  // Newest first within each packet; every sequence b received, once.
  EXPECT_EQ(a_acked, (std::vector<uint32_t>{1, 2, 4, 5, 7, 8, 10}));
  EXPECT_EQ(a.stats().acked, 7u);
}

TEST(Connection, AckBitsAcknowledgeOlderPacketsNewestFirst) {
  Connection a(kT0);
  v1::Envelope out;
  for (int i = 0; i < 6; ++i) (void)a.stamp(out, kT0);  // sequences 1..6
  // Peer reports: newest 6, plus 5 (bit 0) and 2 (bit 3).
  ReceiveResult r = a.on_receive(packet(900, 6, 0b1001u), kT0);
  EXPECT_EQ(acked(r), (std::vector<uint32_t>{6, 5, 2}));
  // The same knowledge again acknowledges nothing new; 4 is new.
  r = a.on_receive(packet(901, 6, 0b1011u), kT0);
  EXPECT_EQ(acked(r), (std::vector<uint32_t>{4}));
}

TEST(Connection, IgnoresAcksForUnsentOrAncientSequences) {
  Connection a(kT0);
  v1::Envelope out;
  (void)a.stamp(out, kT0);  // 1
  // Initial ack 0 acknowledges nothing (we started at 1).
  EXPECT_TRUE(acked(a.on_receive(packet(10, 0, 0), kT0)).empty());
  // An ack for a sequence never sent is ignored.
  EXPECT_TRUE(acked(a.on_receive(packet(11, 5, 0xFFFF'FFFFu), kT0)).empty());
  EXPECT_TRUE(acked(a.on_receive(packet(12, 0x8000'0000u, 0xFFFF'FFFFu), kT0)).empty());
  EXPECT_EQ(a.stats().acked, 0u);
  EXPECT_FALSE(a.has_rtt());
  EXPECT_EQ(acked(a.on_receive(packet(13, 1, 0), kT0)), (std::vector<uint32_t>{1}));
}

TEST(Connection, SendSequenceWrapsAround) {
  Connection a(kT0, 7, 0xFFFF'FFFDu);
  v1::Envelope out;
  std::vector<uint32_t> sent;
  for (int i = 0; i < 5; ++i) sent.push_back(a.stamp(out, kT0 + milliseconds(i)));
  EXPECT_EQ(sent, (std::vector<uint32_t>{0xFFFF'FFFDu, 0xFFFF'FFFEu, 0xFFFF'FFFFu, 0, 1}));
  // Peer got all but 0xFFFFFFFF: newest 1, bits for 0 (bit 0), 0xFFFFFFFE
  // (bit 2), 0xFFFFFFFD (bit 3).
  ReceiveResult r = a.on_receive(packet(3, 1, 0b1101u), kT0 + milliseconds(50));
  EXPECT_EQ(acked(r), (std::vector<uint32_t>{1, 0, 0xFFFF'FFFEu, 0xFFFF'FFFDu}));
  ASSERT_TRUE(a.has_rtt());
  EXPECT_EQ(a.last_rtt_us(), 46'000);  // packet 1 was sent at +4 ms
}

TEST(Connection, RttFollowsRfc6298) {
  Connection a(kT0);
  EXPECT_EQ(a.retransmit_timeout_us(), 1'000'000);  // before any sample

  TimePoint now = kT0;
  v1::Envelope out;
  uint32_t remote = 1000;
  // First sample 100 ms: SRTT = R, RTTVAR = R / 2.
  uint32_t seq = a.stamp(out, now);
  now += milliseconds(100);
  (void)a.on_receive(packet(remote++, seq, 0), now);
  EXPECT_EQ(a.smoothed_rtt_us(), 100'000);
  EXPECT_EQ(a.rtt_variance_us(), 50'000);
  EXPECT_EQ(a.retransmit_timeout_us(), 300'000);

  // Second sample 60 ms: RTTVAR = 3/4*50 + 1/4*|100-60| = 47.5 ms,
  // SRTT = 7/8*100 + 1/8*60 = 95 ms.
  seq = a.stamp(out, now);
  now += milliseconds(60);
  (void)a.on_receive(packet(remote++, seq, 0), now);
  EXPECT_EQ(a.smoothed_rtt_us(), 95'000);
  EXPECT_NEAR(static_cast<double>(a.rtt_variance_us()), 47'500.0, 1.0);

  // A steady 40 ms path converges: SRTT -> 40 ms, RTTVAR -> ~0.
  for (int i = 0; i < 200; ++i) {
    seq = a.stamp(out, now);
    now += milliseconds(40);
    (void)a.on_receive(packet(remote++, seq, 0), now);
  }
  EXPECT_NEAR(static_cast<double>(a.smoothed_rtt_us()), 40'000.0, 100.0);
  EXPECT_LT(a.rtt_variance_us(), 1'000);
  EXPECT_EQ(a.last_rtt_us(), 40'000);
  // RTO = SRTT + max(G = 1 ms, 4 * RTTVAR).
  EXPECT_NEAR(static_cast<double>(a.retransmit_timeout_us()), 41'000.0, 500.0);
}

TEST(Connection, RttSampledOnlyFromNewestAck) {
  Connection a(kT0);
  v1::Envelope out;
  (void)a.stamp(out, kT0);                      // 1 at t0
  (void)a.stamp(out, kT0 + milliseconds(100));  // 2 at t0+100
  // Peer acks 2 (newest) and 1 (bit) at t0+130: sample is 30 ms, not 130.
  (void)a.on_receive(packet(50, 2, 0b1u), kT0 + milliseconds(130));
  EXPECT_EQ(a.last_rtt_us(), 30'000);
  EXPECT_EQ(a.smoothed_rtt_us(), 30'000);
}

TEST(Connection, EstimatesPacketLoss) {
  Connection a(kT0);
  Connection b(kT0);
  // 20% loss on a->b (every 5th packet), b answers each time.
  for (int i = 0; i < 2000; ++i) {
    v1::Envelope to_b;
    to_b.mutable_ping();
    const uint32_t seq = a.stamp(to_b, kT0);
    if (seq % 5 != 0) (void)b.on_receive(to_b, kT0);
    v1::Envelope to_a;
    to_a.mutable_pong();
    (void)b.stamp(to_a, kT0);
    (void)a.on_receive(to_a, kT0);
  }
  EXPECT_NEAR(a.packet_loss(), 0.2, 0.08);
  EXPECT_EQ(a.stats().acked, 1600u);
  // Losses are counted once a packet is older than the 33-packet ack window
  // of the newest ack (1999): multiples of 5 below 1967.
  EXPECT_EQ(a.stats().lost, 393u);
  EXPECT_LT(b.packet_loss(), 0.01);
}

TEST(Connection, UnackedPacketsBecomeLostWhenTheRingWraps) {
  Connection a(kT0);
  v1::Envelope out;
  // The peer never answers: after 300 sends, the 44 oldest left the ring.
  for (int i = 0; i < 300; ++i) (void)a.stamp(out, kT0);
  EXPECT_EQ(a.stats().lost, 300u - Connection::kSendRingSize);
  EXPECT_GT(a.packet_loss(), 0.7);
}

}  // namespace
}  // namespace rwd::net
