// SPDX-License-Identifier: MIT
#include "scripted_peer.h"

#include <algorithm>
#include <cmath>

#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_wire.h"

namespace rwd::test {
namespace {

constexpr auto kJoinResend = std::chrono::milliseconds(250);
constexpr auto kEndingWait = std::chrono::milliseconds(1500);

ScriptedPeer::Settings without_cookie(ScriptedPeer::Settings settings) {
  settings.address_cookie = false;
  return settings;
}

}  // namespace

ScriptedPeer::ScriptedPeer(Settings settings, SendFn send)
    : settings_(std::move(settings)), send_(std::move(send)), connection_(TimePoint{}) {}

void ScriptedPeer::start(TimePoint now) {
  connection_ = net::Connection(now);
  joining_ = true;
  last_join_ = now - kJoinResend;
}

void ScriptedPeer::receive(std::span<const uint8_t> datagram, TimePoint now) {
  if (settings_.address_cookie) {
    if (const std::optional<net::AddressCookie> cookie = net::read_cookie(datagram)) {
      if (joining_ && !cookie_) {
        cookie_ = *cookie;
        last_join_ = now - kJoinResend;  // the join goes out on the next update
      }
      return;
    }
  }
  auto decoded = net::decode_envelope(datagram);
  if (!decoded.ok()) return;
  const v1::Envelope& e = *decoded;
  if (e.has_join_accept()) {
    if (!joining_ || e.join_accept().nonce() != settings_.nonce) return;
    connection_.set_connection_id(e.join_accept().connection_id());
  }
  if (connection_.connection_id() == 0 || e.connection_id() != connection_.connection_id()) {
    return;
  }
  if (!connection_.on_receive(e, now).is_new()) return;
  switch (e.payload_case()) {
    case v1::Envelope::kJoinAccept:
      player_ = e.join_accept().player();
      joining_ = false;
      break;
    case v1::Envelope::kMatchStart:
      started_ = true;
      hear_server_tick(e.match_start().server_tick(), now);
      break;
    case v1::Envelope::kFinalTicks:
      hear_server_tick(e.final_ticks().server_tick(), now);
      on_final_ticks(e.final_ticks());
      break;
    case v1::Envelope::kResyncChunk:
      // The server thinks we fell behind its history and restarts us from
      // a snapshot. Without a simulation there is nothing to load: take
      // the snapshot's tick as the new base, as a client would.
      if (e.resync_chunk().tick() - 1 > contiguous_) {
        contiguous_ = e.resync_chunk().tick() - 1;
        ahead_.erase(ahead_.begin(), ahead_.upper_bound(contiguous_));
      }
      break;
    case v1::Envelope::kMatchEnd:
      if (done_) {
        say_goodbye(now);  // our goodbye was lost: the server still waits
      } else if (!ending_) {
        ending_ = true;
        end_tick_ = e.match_end().last_final_tick();
        ending_deadline_ = now + kEndingWait;
      }
      break;
    case v1::Envelope::kDisconnect:
      done_ = true;
      break;
    default:
      break;  // relayed inputs and pongs: nothing to do without a simulation
  }
}

void ScriptedPeer::update(TimePoint now) {
  if (done_) return;
  if (joining_) {
    if (now - last_join_ >= kJoinResend) {
      last_join_ = now;
      if (settings_.address_cookie && !cookie_) {
        send_(net::make_hello());  // until the server's cookie comes back
        return;
      }
      v1::Envelope envelope;
      envelope.mutable_join_request()->set_game(settings_.game);
      envelope.mutable_join_request()->set_client_name(settings_.name);
      envelope.mutable_join_request()->set_nonce(settings_.nonce);
      if (!settings_.address_cookie) {
        send(envelope, now);
        return;
      }
      connection_.stamp(envelope, now);
      if (net::encode_envelope(envelope, buffer_).ok()) {
        net::frame_join(*cookie_, buffer_, framed_);
        send_(framed_);
      }
    }
    return;
  }
  if (!started_) return;
  if (ending_ && (contiguous_ >= end_tick_ || now >= ending_deadline_)) {
    say_goodbye(now);
    done_ = true;
    return;
  }
  if (sent_once_ && now - last_frame_ < settings_.period) return;
  sent_once_ = true;
  last_frame_ = now;
  // Inputs up to where the server will be when they arrive, plus a margin.
  const double elapsed_ticks = std::chrono::duration<double>(now - heard_at_).count() /
                               std::chrono::duration<double>(settings_.period).count();
  const auto target =
      static_cast<Tick>(std::floor(server_tick_ + elapsed_ticks + settings_.lead_ticks));
  const Tick first = std::max<Tick>(input_ack_ + 1, 0);
  v1::Envelope envelope;
  v1::InputFrame* frame = envelope.mutable_input_frame();
  frame->set_player(player_);
  frame->set_first_tick(first);
  frame->set_last_final_tick_seen(contiguous_);
  if (!ending_) {
    for (Tick t = first; t <= target && t < first + 64; ++t) {
      *frame->add_inputs() =
          proto::to_wire(settings_.inputs ? settings_.inputs(player_, t) : rwd::PlayerInput{});
    }
  }
  send(envelope, now);
}

void ScriptedPeer::hear_server_tick(int32_t tick, TimePoint now) {
  if (tick > server_tick_ || heard_at_ == TimePoint{}) {
    server_tick_ = tick;
    heard_at_ = now;
  }
}

void ScriptedPeer::on_final_ticks(const v1::FinalTicks& finals) {
  input_ack_ = std::max(input_ack_, finals.input_ack_tick());
  for (const v1::FinalTick& f : finals.ticks()) {
    if (f.tick() <= contiguous_) continue;
    if (f.tick() > contiguous_ + 1) {
      ahead_.insert(f.tick());
      continue;
    }
    contiguous_ = f.tick();
    while (!ahead_.empty() && *ahead_.begin() <= contiguous_ + 1) {
      contiguous_ = std::max(contiguous_, *ahead_.begin());
      ahead_.erase(ahead_.begin());
    }
  }
}

void ScriptedPeer::say_goodbye(TimePoint now) {
  v1::Envelope bye;
  bye.mutable_disconnect()->set_reason("match over");
  send(bye, now);
}

void ScriptedPeer::send(v1::Envelope& envelope, TimePoint now) {
  connection_.stamp(envelope, now);
  if (net::encode_envelope(envelope, buffer_).ok()) send_(buffer_);
}

SecurePeer::SecurePeer(const net::ConnectToken& token, ScriptedPeer::Settings settings, SendFn send)
    : send_(std::move(send)),
      handshake_(token),
      peer_(without_cookie(std::move(settings)), [this](std::span<const uint8_t> envelope) {
        // Nothing leaves in the clear: before the session, the join waits.
        if (!handshake_.session()) return;
        handshake_.session()->seal(envelope, sealed_);
        send_(sealed_);
      }) {}

void SecurePeer::start(TimePoint now) {
  peer_.start(now);
  last_handshake_ = now - kJoinResend;
}

void SecurePeer::receive(std::span<const uint8_t> datagram, TimePoint now) {
  const std::optional<net::SecurePacket> kind = net::secure_packet_kind(datagram);
  if (kind == net::SecurePacket::kChallenge) {
    if (handshake_.on_challenge(datagram, response_).ok()) send_(response_);
    return;
  }
  if (kind != net::SecurePacket::kPayload || !handshake_.session()) return;
  if (!handshake_.session()->open(datagram, plain_).ok()) return;
  heard_ = true;
  peer_.receive(plain_, now);
}

void SecurePeer::update(TimePoint now) {
  if (!heard_ && now - last_handshake_ >= kJoinResend) {
    // The request until a challenge comes, then the response until the
    // server speaks (it may have missed it).
    last_handshake_ = now;
    send_(handshake_.session() ? std::span<const uint8_t>(response_)
                               : std::span<const uint8_t>(handshake_.request()));
  }
  peer_.update(now);
}

}  // namespace rwd::test
