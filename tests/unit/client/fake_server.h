// SPDX-License-Identifier: MIT
#pragma once
// The server's end of one client connection for ClientProtocol tests,
// built from the server's own pieces (net::Connection, the envelope codec,
// the input wire format, a secure session when the client holds a token)
// and an authoritative simulation of its own: it makes the datagrams a
// server would send (JoinAccept, MatchStart, FinalTicks with the true
// checksums, ResyncChunk, MatchEnd) and reads what the client sends. No
// sockets and no clock: the test passes every time in.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rewind/game/simulation.h"
#include "rewind/net/connection.h"
#include "rewind/net/secure_channel.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::test {

struct FakeMatch {
  std::string game = "crates";
  uint32_t players = 2;
  uint64_t seed = 11;
  uint32_t tick_rate_hz = 60;
  uint32_t window_ticks = 8;
  uint64_t connection_id = 0x0123'4567'89AB'CDEFull;
};

class FakeServer {
 public:
  explicit FakeServer(const FakeMatch& match);

  /// From now on every datagram is sealed with / opened by `session`.
  void use_secure_session(net::SecureSession session) { secure_ = std::move(session); }

  /// A datagram from the client: its envelope, or nullopt when it does not
  /// open or decode. Every new one counts as received by our connection.
  std::optional<v1::Envelope> read(std::span<const uint8_t> datagram, net::TimePoint now);

  std::vector<uint8_t> join_accept(uint64_t nonce, uint32_t player, net::TimePoint now);
  std::vector<uint8_t> join_reject(uint64_t nonce, const std::string& reason);
  std::vector<uint8_t> match_start(Tick server_tick, net::TimePoint now);
  std::vector<uint8_t> match_end(Tick last_final_tick, net::TimePoint now);
  std::vector<uint8_t> disconnect(const std::string& reason, net::TimePoint now);

  /// Steps the authoritative simulation through `tick` (ticks in order,
  /// from the next unstepped one) with `inputs` (one per player) and
  /// remembers the tick's inputs and checksum.
  void step(const std::vector<rwd::PlayerInput>& inputs);
  Tick next_tick() const { return next_tick_; }
  /// The checksum after stepping `tick`.
  uint64_t checksum_after(Tick tick) const { return ticks_.at(tick).checksum; }

  /// A FinalTicks datagram carrying [first, last] (stepped already), each
  /// standalone, with `checksum_override` for the tick it names, and
  /// other players' runs in `relayed` (player, first tick, inputs).
  struct Relayed {
    uint32_t player = 0;
    Tick first_tick = 0;
    std::vector<rwd::PlayerInput> inputs;
  };
  std::vector<uint8_t> final_ticks(Tick first, Tick last, Tick input_ack, net::TimePoint now,
                                   std::optional<std::pair<Tick, uint64_t>> checksum_override = {},
                                   const std::vector<Relayed>& relayed = {});

  /// The serialized state at the start of `tick` (after tick - 1) and its
  /// checksum, as a resync would send it.
  const std::vector<uint8_t>& state_at(Tick tick) const { return ticks_.at(tick).state_before; }
  uint64_t checksum_at(Tick tick) const { return ticks_.at(tick).checksum_before; }
  /// The resync snapshot at `tick` in ResyncChunk datagrams, in order.
  std::vector<std::vector<uint8_t>> resync_chunks(uint32_t snapshot_id, Tick tick,
                                                  net::TimePoint now);

  /// Stamps (and seals) one envelope as the server would.
  std::vector<uint8_t> encode(v1::Envelope& envelope, net::TimePoint now);

 private:
  struct TickRecord {
    std::vector<rwd::PlayerInput> inputs;
    uint64_t checksum = 0;
    std::vector<uint8_t> state_before;
    uint64_t checksum_before = 0;
  };

  FakeMatch match_;
  net::Connection connection_;
  std::optional<net::SecureSession> secure_;
  std::unique_ptr<game::Simulation> sim_;
  Tick next_tick_ = 0;
  std::map<Tick, TickRecord> ticks_;
};

}  // namespace rwd::test
