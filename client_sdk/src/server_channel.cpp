// SPDX-License-Identifier: MIT
#include "server_channel.h"

#include <chrono>

#include "rewind/net/envelope_codec.h"

namespace rwd::client {
namespace {

// A tokenless server takes a cookie for one to two of its windows: a join
// still unanswered after this long asks for a fresh one first.
constexpr auto kCookieRefresh = std::chrono::seconds(3);
static_assert(kCookieRefresh < std::chrono::seconds(net::kCookieWindowS));

}  // namespace

bool ServerChannel::prepare_join(TimePoint now) {
  if (handshake_ && !handshake_->session()) {
    transmit(handshake_->request());  // until a challenge comes back
    return false;
  }
  if (!handshake_ && (!cookie_ || now - cookie_at_ >= kCookieRefresh)) {
    cookie_.reset();
    if (hello_.empty()) hello_ = net::make_hello();
    transmit(hello_);  // until a cookie comes back
    return false;
  }
  // Until the server speaks, it may have missed our response.
  if (handshake_ && !secure_confirmed_) transmit(handshake_response_);
  return true;
}

void ServerChannel::send(v1::Envelope& envelope, TimePoint now) {
  connection_.stamp(envelope, now);
  if (!net::encode_envelope(envelope, encode_buffer_).ok()) return;
  if (!handshake_) {
    if (envelope.has_join_request() && cookie_) {
      net::frame_join(*cookie_, encode_buffer_, framed_buffer_);
      transmit(framed_buffer_);
      return;
    }
    transmit(encode_buffer_);
    return;
  }
  if (!handshake_->session()) return;  // nothing leaves in the clear
  handshake_->session()->seal(encode_buffer_, sealed_buffer_);
  transmit(sealed_buffer_);
}

void ServerChannel::transmit(std::span<const uint8_t> datagram) {
  if (!outbox_.push(datagram)) {
    ++datagrams_dropped_;
    return;
  }
  ++packets_sent_;
}

ServerChannel::Opened ServerChannel::open(std::span<const uint8_t> datagram, bool joining,
                                          TimePoint now) {
  if (handshake_) {
    // A secure server: a challenge answers our request; anything else must
    // be a payload sealed for our session.
    const std::optional<net::SecurePacket> kind = net::secure_packet_kind(datagram);
    if (kind == net::SecurePacket::kChallenge && joining) {
      if (!handshake_->on_challenge(datagram, handshake_response_).ok()) return {};
      transmit(handshake_response_);
      return {Inbound::kJoinSoon, {}};
    }
    if (kind != net::SecurePacket::kPayload || !handshake_->session() ||
        !handshake_->session()->open(datagram, opened_buffer_).ok()) {
      return {};
    }
    secure_confirmed_ = true;
    return {Inbound::kEnvelope, opened_buffer_};
  }
  if (net::cookie_packet_kind(datagram) == net::CookiePacket::kCookie) {
    // A tokenless server's answer to our Hello: the join goes out at once
    // with it (a second cookie, the answer to a resent Hello, only renews).
    const std::optional<net::AddressCookie> cookie = net::read_cookie(datagram);
    if (!cookie || !joining) return {};
    const bool first = !cookie_;
    cookie_ = *cookie;
    cookie_at_ = now;
    return {first ? Inbound::kJoinNow : Inbound::kConsumed, {}};
  }
  return {Inbound::kEnvelope, datagram};
}

ServerChannel::Admission ServerChannel::admit(const v1::Envelope& envelope, TimePoint now) {
  if (connection_.connection_id() == 0 || envelope.connection_id() != connection_.connection_id()) {
    return Admission::kForeign;
  }
  return connection_.on_receive(envelope, now).is_new() ? Admission::kNew : Admission::kRepeat;
}

}  // namespace rwd::client
