// SPDX-License-Identifier: MIT
#pragma once
// The server's secure front door (net/secure_channel.h): between the socket
// and the match host when the server has a key. It answers handshakes
// without keeping state until a client proves it holds its token's keys,
// then keeps one session per slot and per address, opens payloads into
// envelopes for the host (with the slot and client the token names), and
// seals what the host sends. Anything else is dropped and counted, so a
// forged, altered, replayed or spoofed datagram never reaches the match.
// No socket and no clock: the shell passes datagrams and the time in.
#include <asio/ip/udp.hpp>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "rewind/net/connect_token.h"
#include "rewind/net/secure_channel.h"

namespace rwd::server {

using Endpoint = asio::ip::udp::endpoint;

/// Who sent a payload: what its connect token names.
struct Admission {
  uint32_t slot = 0;
  uint64_t client_id = 0;
};

class SecureGateway {
 public:
  using SendFn = std::function<void(const Endpoint&, std::span<const uint8_t>)>;
  using DeliverFn =
      std::function<void(std::span<const uint8_t> envelope, const Endpoint&, const Admission&)>;

  /// A slot's session gives way to another client's handshake (a second
  /// token minted for the slot) only after this long without a word.
  static constexpr int64_t kHolderQuietS = 10;

  /// `slots`: tokens for slots at or past it are refused.
  SecureGateway(const net::Key& server_key, std::string_view match_id, uint32_t slots, SendFn send);

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
    uint64_t refused = 0;     ///< handshake packets refused
    uint64_t dropped = 0;     ///< payloads that did not open, other datagrams
  };
  const Stats& stats() const { return stats_; }
  /// Sessions held now.
  size_t sessions() const { return clients_.size(); }

 private:
  struct Client {
    Endpoint endpoint;
    uint64_t client_id = 0;
    uint32_t slot = 0;
    int64_t last_heard_unix_s = 0;  ///< the handshake, then each payload that opened
    std::array<uint8_t, net::kSaltBytes> salt{};
    net::SecureSession session;
  };

  void on_response(std::span<const uint8_t> bytes, const Endpoint& from, int64_t now_unix_s);
  Client* find(const Endpoint& endpoint);

  net::ServerGate gate_;
  uint32_t slots_;
  SendFn send_;
  std::vector<Client> clients_;
  std::vector<uint8_t> buffer_;
  std::vector<uint8_t> plain_;
  Stats stats_;
};

/// A UDP endpoint as the secure channel binds it (IPv4 mapped into IPv6).
net::PeerAddress peer_address(const Endpoint& endpoint);

}  // namespace rwd::server
