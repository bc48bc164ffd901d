// SPDX-License-Identifier: MIT
#pragma once
// How every part of a hosted match sends: a message to a seat goes out
// stamped by the seat's connection (sequence, acknowledgements), encoded
// and counted, through the shell's send callback; an answer to an address
// without a seat (a refused join) goes out unstamped.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "rewind/server/match_seats.h"
#include "rewind/server/match_stats.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::server {

class MatchOutbox {
 public:
  using SendFn = std::function<void(const Endpoint&, std::span<const uint8_t>)>;
  /// `stats` counts what goes out (packets_out, bytes_out); it outlives this.
  MatchOutbox(SendFn send, MatchStats& stats) : send_(std::move(send)), stats_(stats) {}

  /// Sends to the seat's holder; nothing when it has no connection. The
  /// tick's final ticks and relayed inputs were checked when they came in
  /// and packed by the host, so only their header is checked again;
  /// everything else is checked in full.
  void send(Seat& seat, v1::Envelope& envelope, TimePoint now);
  /// Sends to an address that holds no seat.
  void send_unconnected(const Endpoint& to, v1::Envelope& envelope);

 private:
  SendFn send_;
  MatchStats& stats_;
  std::vector<uint8_t> encode_buffer_;
};

}  // namespace rwd::server
