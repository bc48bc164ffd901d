// SPDX-License-Identifier: MIT
#pragma once
// ClientProtocol's channel to the server: everything between an envelope and
// the bytes on the wire, kept apart from what the envelopes mean. It owns the
// connection (sequence stamping, acks, duplicate and foreign-packet
// filtering, the silence clock), the tokenless server's address cookie and
// the Hello that fetches it, the secure handshake and the sealing/opening of
// a secure session, the encode buffers, and the outbox the caller drains.
//
// It knows nothing of phases or matches: the protocol tells it whether a
// join is under way and hears back what a handshake or cookie packet means
// for the join (the join request itself, with the game and the seat, is the
// protocol's to write). Its buffers keep their capacity, so a steady stream
// of sends and receives allocates nothing once warm.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "datagram_queue.h"
#include "rewind/net/address_cookie.h"
#include "rewind/net/clock.h"
#include "rewind/net/connect_token.h"
#include "rewind/net/connection.h"
#include "rewind/net/secure_channel.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::client {

class ServerChannel {
 public:
  using TimePoint = net::TimePoint;

  /// What a datagram from the server turned out to be (open()).
  enum class Inbound : uint8_t {
    kRejected,  ///< not for us, or not now: count it and drop it
    kConsumed,  ///< a renewed cookie: nothing more to do
    kJoinNow,   ///< the first cookie came: send the join at once
    kJoinSoon,  ///< the handshake's challenge was answered: the join may follow
    kEnvelope,  ///< an encoded envelope (opened, on a secure connection)
  };
  struct Opened {
    Inbound kind = Inbound::kRejected;
    std::span<const uint8_t> bytes;  ///< the envelope's bytes, for kEnvelope
  };
  /// What an envelope from the server is to the connection (admit()).
  enum class Admission : uint8_t { kForeign, kRepeat, kNew };

  /// At most `max_queued` datagrams wait for the caller.
  explicit ServerChannel(size_t max_queued) : outbox_(max_queued) {}

  /// Every datagram is sealed for the session the token's handshake sets up.
  void secure_with(const net::ConnectToken& token) { handshake_.emplace(token); }

  /// A new connection, its silence clock started at `now`.
  void start(TimePoint now) { connection_ = net::Connection(now); }
  uint64_t connection_id() const { return connection_.connection_id(); }
  /// The id the server's JoinAccept gave us; it filters what comes in.
  void set_connection_id(uint64_t id) { connection_.set_connection_id(id); }
  TimePoint last_receive_time() const { return connection_.last_receive_time(); }

  /// Sends what has to precede a join request (the handshake request, or a
  /// Hello for a fresh cookie, or the handshake response until the server
  /// speaks) and says whether the join request can follow now.
  bool prepare_join(TimePoint now);
  /// Stamps, encodes (and seals, on a secure connection) and queues. A join
  /// request to a tokenless server goes out framed with its cookie.
  void send(v1::Envelope& envelope, TimePoint now);
  /// Queues a datagram as is.
  void transmit(std::span<const uint8_t> datagram);

  /// Reads one datagram: handshake and cookie packets (taken only while
  /// `joining`) are answered here; a payload is opened. The bytes of a
  /// kEnvelope stay valid until the next open().
  Opened open(std::span<const uint8_t> datagram, bool joining, TimePoint now);
  /// Whether a decoded envelope belongs to this connection and is new; a
  /// new one is acknowledged and restarts the silence clock.
  Admission admit(const v1::Envelope& envelope, TimePoint now);

  /// The oldest queued datagram (ClientProtocol::next_datagram()).
  std::optional<std::span<const uint8_t>> next_datagram() { return outbox_.pop(); }
  uint64_t packets_sent() const { return packets_sent_; }
  uint64_t datagrams_dropped() const { return datagrams_dropped_; }

 private:
  net::Connection connection_{TimePoint{}};
  DatagramQueue outbox_;
  uint64_t packets_sent_ = 0;
  uint64_t datagrams_dropped_ = 0;
  std::vector<uint8_t> encode_buffer_;
  // Tokenless servers: the cookie that admits our join (net/address_cookie.h),
  // asked for with a Hello, and when it came (it is asked for again before
  // the server stops taking it).
  std::optional<net::AddressCookie> cookie_;
  TimePoint cookie_at_;
  std::vector<uint8_t> hello_;
  std::vector<uint8_t> framed_buffer_;
  // Secure connections (ClientConfig::connect_token): the handshake, its
  // response (resent with the join until the server speaks), and buffers.
  std::optional<net::ClientHandshake> handshake_;
  std::vector<uint8_t> handshake_response_;
  bool secure_confirmed_ = false;
  std::vector<uint8_t> sealed_buffer_;
  std::vector<uint8_t> opened_buffer_;
};

}  // namespace rwd::client
