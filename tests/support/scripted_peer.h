// SPDX-License-Identifier: MIT
#pragma once
// A protocol peer without a simulation, for whole matches that must cost
// the host's work and little else (headless matches, the host and density
// benchmarks): it speaks the real envelope codec and connection layer,
// joins, sends its scripted inputs a little ahead of the server's clock
// (every unacknowledged one, in one frame a tick), acknowledges the final
// ticks it got and leaves at the end. SecurePeer puts it behind the secure
// handshake and seals what it sends, as a client with a connect token does.
// No socket and no clock: datagrams and the time come in, datagrams go out
// through a callback.
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/tick.h"
#include "rewind/net/address_cookie.h"
#include "rewind/net/clock.h"
#include "rewind/net/connection.h"
#include "rewind/net/secure_channel.h"

namespace rwd::test {

using TimePoint = net::TimePoint;

/// Inputs as a pure function of the player slot and the tick.
using InputScript = std::function<rwd::PlayerInput(uint32_t player, Tick tick)>;

class ScriptedPeer {
 public:
  using SendFn = std::function<void(std::span<const uint8_t>)>;
  struct Settings {
    std::string game;
    std::string name;
    uint64_t nonce = 0;       ///< the join request's
    InputScript inputs;       ///< neutral when empty
    double lead_ticks = 2.0;  ///< inputs this far ahead of the server's clock as last heard
    std::chrono::nanoseconds period{16'666'667};  ///< the server's tick
    /// Tokenless: ask for an address cookie (a padded hello) and frame the
    /// join with it, as the client SDK does. SecurePeer turns it off: its
    /// handshake proves the address instead.
    bool address_cookie = true;
  };

  ScriptedPeer(Settings settings, SendFn send);

  /// Starts joining (the join request is resent until answered).
  void start(TimePoint now);
  /// One envelope from the server (undecodable ones are ignored).
  void receive(std::span<const uint8_t> envelope, TimePoint now);
  /// Sends what is due: a join request, or this tick's input frame.
  void update(TimePoint now);
  /// Has left the match (said goodbye, or given up).
  bool done() const { return done_; }
  /// The match has started for it (MatchStart heard).
  bool started() const { return started_; }
  /// Every final tick up to this one was received.
  Tick contiguous() const { return contiguous_; }

 private:
  void hear_server_tick(int32_t tick, TimePoint now);
  void on_final_ticks(const v1::FinalTicks& finals);
  void say_goodbye(TimePoint now);
  void send(v1::Envelope& envelope, TimePoint now);

  Settings settings_;
  SendFn send_;
  net::Connection connection_;
  std::vector<uint8_t> buffer_;
  std::vector<uint8_t> framed_;
  std::optional<net::AddressCookie> cookie_;  // the server's, for our join
  bool joining_ = false;
  bool started_ = false;
  bool ending_ = false;
  bool done_ = false;
  bool sent_once_ = false;
  uint32_t player_ = 0;
  TimePoint last_join_;
  TimePoint last_frame_;
  TimePoint heard_at_;
  TimePoint ending_deadline_;
  int32_t server_tick_ = 0;
  Tick input_ack_ = kNoTick;
  Tick contiguous_ = kNoTick;
  Tick end_tick_ = kNoTick;
  std::set<Tick> ahead_;  // final ticks received beyond a gap
};

/// A ScriptedPeer with a connect token: the handshake first (its request
/// resent until a challenge comes, its response until the server speaks),
/// then every envelope sealed each way with the session's keys.
class SecurePeer {
 public:
  using SendFn = ScriptedPeer::SendFn;

  SecurePeer(const net::ConnectToken& token, ScriptedPeer::Settings settings, SendFn send);
  SecurePeer(const SecurePeer&) = delete;
  SecurePeer& operator=(const SecurePeer&) = delete;

  void start(TimePoint now);
  /// One datagram from the server: a challenge, or a sealed envelope.
  void receive(std::span<const uint8_t> datagram, TimePoint now);
  void update(TimePoint now);
  bool done() const { return peer_.done(); }
  bool started() const { return peer_.started(); }
  const ScriptedPeer& peer() const { return peer_; }

 private:
  SendFn send_;
  net::ClientHandshake handshake_;
  std::vector<uint8_t> response_;
  bool heard_ = false;  ///< a sealed datagram from the server opened
  TimePoint last_handshake_;
  std::vector<uint8_t> sealed_;
  std::vector<uint8_t> plain_;
  ScriptedPeer peer_;
};

}  // namespace rwd::test
