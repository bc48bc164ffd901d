// SPDX-License-Identifier: MIT
#pragma once
// The server's secure front door (net/secure_channel.h): between the socket
// and the match host when the server has a key. It answers handshakes
// without keeping state until a client proves it holds its token's keys,
// then keeps one session per slot and per address, opens payloads into
// envelopes for the host (with the slot and client the token names), and
// seals what the host sends. Anything else is dropped and counted, so a
// forged, altered, replayed or spoofed datagram never reaches the match.
//
// Who may connect, after netcode.io's server:
//   - a token connects once: its MAC is remembered from the connection
//     until the token expires (net::UsedTokens), so a copy of it, keys
//     included, is refused, and a client that comes back (a new process, a
//     lost connection) needs a fresh token from its backend, minted for the
//     same client id and slot;
//   - a request for a client id that is connected is ignored;
//   - a slot held by a client id takes tokens for that client id only, until
//     the match drops the holder (its peer timeout, or a goodbye); then any
//     token for the slot. The match is asked (Options::seated), so the
//     gateway and the match agree on who holds a slot, and a token for
//     another client never cuts a holder off, talking or silent.
// No socket and no clock: the shell passes datagrams and the time in.
#include <asio/ip/udp.hpp>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "rewind/net/connect_token.h"
#include "rewind/net/secure_channel.h"
#include "rewind/net/used_tokens.h"

namespace rwd::server {

using Endpoint = asio::ip::udp::endpoint;

/// Who sent a payload: what its connect token names. On a tokenless server
/// (TokenlessGateway) only its presence counts: the sender's address
/// answered a cookie.
struct Admission {
  uint32_t slot = 0;
  uint64_t client_id = 0;
};

class SecureGateway {
 public:
  using SendFn = std::function<void(const Endpoint&, std::span<const uint8_t>)>;
  using DeliverFn =
      std::function<void(std::span<const uint8_t> envelope, const Endpoint&, const Admission&)>;
  /// The match's word on a session: whether the client at `endpoint` holds
  /// `slot` now (joined, not dropped by the peer timeout, not gone).
  using SeatedFn = std::function<bool(uint32_t slot, const Endpoint& endpoint)>;

  struct Options {
    /// Tokens for slots at or past it are refused.
    uint32_t slots = 0;
    /// How long a session the match has not seated (its join on the way)
    /// keeps its slot and client id, seconds; without `seated`, how long a
    /// session holds after its last word. The match's peer timeout.
    int64_t join_grace_s = 5;
    /// Asked on handshakes (and until a session is first seated); empty: a
    /// session holds while heard within join_grace_s.
    SeatedFn seated;
    /// Tokens remembered at most (see net::UsedTokens).
    size_t used_token_capacity = net::UsedTokens::kDefaultCapacity;
  };

  SecureGateway(const net::Key& server_key, std::string_view match_id, Options options,
                SendFn send);

  /// One datagram from the socket at `now_unix_s` (wall-clock seconds, for
  /// token expiry): handshakes are answered, payloads of a session opened
  /// and handed to `deliver`, everything else dropped.
  void on_datagram(std::span<const uint8_t> bytes, const Endpoint& from, int64_t now_unix_s,
                   const DeliverFn& deliver);
  /// Seals `envelope` for `to` and sends it; dropped when `to` holds no
  /// session (nothing is ever sent in the clear).
  void send(const Endpoint& to, std::span<const uint8_t> envelope);

  struct Stats {
    uint64_t challenges = 0;  ///< requests answered
    uint64_t connects = 0;    ///< sessions opened (new or replacing)
    /// Handshake packets refused: malformed, foreign, expired, a token used
    /// before, a client id connected already, a slot another client holds.
    uint64_t refused = 0;
    uint64_t reused = 0;   ///< of those, tokens used before
    uint64_t dropped = 0;  ///< payloads that did not open, other datagrams
  };
  const Stats& stats() const { return stats_; }
  /// Sessions held now.
  size_t sessions() const { return clients_.size(); }
  /// Tokens remembered now.
  size_t used_tokens() const { return used_.size(); }

 private:
  struct Client {
    Endpoint endpoint;
    uint64_t client_id = 0;
    uint32_t slot = 0;
    int64_t connected_unix_s = 0;   ///< the handshake
    int64_t last_heard_unix_s = 0;  ///< the handshake, then each payload that opened
    bool seated_once = false;       ///< the match has seated it (Options::seated)
    std::array<uint8_t, net::kSaltBytes> salt{};
    net::SecureSession session;
  };

  /// Why a token naming `client_id` and `slot` may not connect now, or
  /// nullptr when it may.
  const char* refusal(uint64_t client_id, uint32_t slot, const net::TokenMac& mac,
                      int64_t now_unix_s);
  /// Whether `client` still holds its slot and client id.
  bool holds(const Client& client, int64_t now_unix_s) const;
  void on_request(std::span<const uint8_t> bytes, const Endpoint& from, int64_t now_unix_s);
  void on_response(std::span<const uint8_t> bytes, const Endpoint& from, int64_t now_unix_s);
  Client* find(const Endpoint& endpoint);

  net::ServerGate gate_;
  Options options_;
  SendFn send_;
  std::vector<Client> clients_;
  net::UsedTokens used_;
  std::vector<uint8_t> buffer_;
  std::vector<uint8_t> plain_;
  Stats stats_;
};

/// A UDP endpoint as the secure channel binds it (IPv4 mapped into IPv6).
net::PeerAddress peer_address(const Endpoint& endpoint);

}  // namespace rwd::server
