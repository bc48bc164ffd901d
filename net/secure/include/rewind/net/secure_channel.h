// SPDX-License-Identifier: MIT
#pragma once
// Secure connections without sockets or clocks (the callers pass bytes,
// addresses and the time in, and send what comes out), after netcode.io:
//
//   client                                   server
//   Request   (sealed token, padded) ---->   opens the token; keeps nothing
//             <----  Challenge (smaller, sealed with the server-to-client
//                     key: a salt and a challenge token only the server
//                     can open, bound to the client's address)
//   Response  (the challenge token, and a tag under the client-to-server
//             key)                   ---->   opens the challenge token,
//                                            checks the tag: connected
//   Payload   <---->  every later packet, sealed with session keys
//
// The server keeps no state and never sends more bytes than it received
// until the client has proved, from its own address, that it holds the
// token's keys. A token connects once: the challenge token carries the
// token's MAC (the tag of its sealed part, unique to each minted token) so
// that the server's caller (SecureGateway) can remember it from the moment
// a key holder connected, and refuse the token again until it expires.
// Session keys are derived from the token's keys and the server's salt, so
// every handshake gets fresh keys (no nonce is ever reused under one key). Payload packets are
// ChaCha20-Poly1305 with the packet sequence as nonce and a replay window:
// a forged, altered or replayed datagram is dropped before any game code
// sees it.
//
// Packet layouts (little-endian; the first byte names the packet):
//   Request   0xC1 | version u8 | match tag u64 | expiry i64 | slot u32 |
//             nonce 24 | sealed token | zero padding to kRequestBytes
//   Challenge 0xC2 | nonce 24 | sealed(server-to-client key:
//             salt 16 | challenge token) + 16   (XChaCha20-Poly1305)
//             (the version byte of a Request is kConnectTokenVersion: it
//             names the handshake's layouts as well as the token's)
//   Response  0xC3 | challenge token | tag 16 (keyed BLAKE2b under the
//             client-to-server key over the challenge token)
//   Payload   0xC4 | sequence u64 | sealed(session key: bytes) + 16
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/net/connect_token.h"

namespace rwd::net {

enum class SecurePacket : uint8_t {
  kRequest = 0xC1,
  kChallenge = 0xC2,
  kResponse = 0xC3,
  kPayload = 0xC4,
};

/// A request is padded to this size, so no answer to it is ever larger.
inline constexpr size_t kRequestBytes = 1000;
/// Salt, and the challenge token: client id u64, slot u32, both keys,
/// token expiry i64, challenge expiry i64, address 19, salt 16, token MAC
/// 16, sealed with a random nonce (24) and a tag (16).
inline constexpr size_t kSaltBytes = 16;
inline constexpr size_t kAddressBytes = 19;
inline constexpr size_t kTokenMacBytes = 16;
inline constexpr size_t kChallengeTokenBytes =
    24 + (8 + 4 + 2 * kKeyBytes + 8 + 8 + kAddressBytes + kSaltBytes + kTokenMacBytes) + 16;
inline constexpr size_t kChallengeBytes = 1 + 24 + kSaltBytes + kChallengeTokenBytes + 16;
inline constexpr size_t kResponseBytes = 1 + kChallengeTokenBytes + 16;
/// Bytes a payload packet adds to what it carries.
inline constexpr size_t kPayloadOverhead = 1 + 8 + 16;
/// A challenge token is good for this long after it was issued.
inline constexpr int64_t kChallengeLifetimeS = 10;

/// What identifies one minted token: the tag that authenticates its sealed
/// part (random-looking, and different for every token minted).
using TokenMac = std::array<uint8_t, kTokenMacBytes>;

/// Where a datagram came from, as the transport saw it: IPv4 addresses
/// are mapped into IPv6 (\::ffff:a.b.c.d) so one form serves both.
struct PeerAddress {
  std::array<uint8_t, 16> ip{};
  uint16_t port = 0;
  bool operator==(const PeerAddress&) const = default;
};

/// Which of the last kWindow sequences arrived: a packet older than the
/// window, or one already seen, is refused.
class ReplayWindow {
 public:
  static constexpr uint64_t kWindow = 256;
  /// Whether `sequence` is new (call before trusting the packet).
  bool fresh(uint64_t sequence) const;
  /// Records `sequence` (after the packet authenticated).
  void accept(uint64_t sequence);

 private:
  bool any_ = false;
  uint64_t newest_ = 0;
  std::array<uint64_t, kWindow / 64> seen_{};
};

/// One direction-aware end of an established connection.
class SecureSession {
 public:
  SecureSession() = default;
  SecureSession(const Key& send_key, const Key& receive_key, uint64_t match_tag);

  /// Seals `payload` into one Payload packet in `out` (replacing it).
  void seal(std::span<const uint8_t> payload, std::vector<uint8_t>& out);
  /// Opens a Payload packet into `out` (replacing it): kCorrupt when it is
  /// malformed, was not sealed with the peer's key for this match, or was
  /// altered; kInvalidArgument when its sequence was already seen or is too
  /// old. A refused packet changes nothing, `out` included.
  Status open(std::span<const uint8_t> packet, std::vector<uint8_t>& out);

  uint64_t sent() const { return next_sequence_; }

 private:
  Key send_key_{};
  Key receive_key_{};
  uint64_t match_tag_ = 0;
  uint64_t next_sequence_ = 0;
  ReplayWindow window_;
  std::vector<uint8_t> scratch_;  ///< open() decrypts here before it swaps with `out`
};

/// What an accepted Request's token names (read from its sealed part).
struct RequestedToken {
  uint64_t client_id = 0;
  uint32_t slot = 0;
  int64_t expiry_unix_s = 0;
  TokenMac mac{};
};

/// A client that proved it holds a token's keys.
struct ConnectedClient {
  uint64_t client_id = 0;
  uint32_t slot = 0;
  int64_t token_expiry_unix_s = 0;
  TokenMac token_mac{};  ///< the token it connected with
  /// The server's salt: the same handshake answered twice (a duplicated or
  /// replayed Response) carries the same salt.
  std::array<uint8_t, kSaltBytes> salt{};
  SecureSession session;  ///< the server's end
};

/// The server's side of the handshake. Stateless: it holds only its keys.
class ServerGate {
 public:
  /// `challenge_key` seals challenge tokens; a fresh generate_key() per
  /// process is right (a restart only voids handshakes in flight).
  ServerGate(const Key& server_key, const Key& challenge_key, uint64_t match_tag);

  /// A Request from `from`: the Challenge to send back into `reply`, or
  /// an error (kCorrupt: malformed; kInvalidArgument: a token this server
  /// refuses) after which nothing must be sent. `requested`, when given,
  /// receives what the token names, so the caller can still decide not to
  /// send the Challenge (a token already used, a client already connected).
  Status on_request(std::span<const uint8_t> packet, const PeerAddress& from, int64_t now_unix_s,
                    std::vector<uint8_t>& reply, RequestedToken* requested = nullptr);
  /// A Response from `from`: the client, or an error (malformed, not from
  /// the address challenged, expired, or a tag the token's key did not make).
  Result<ConnectedClient> on_response(std::span<const uint8_t> packet, const PeerAddress& from,
                                      int64_t now_unix_s);

 private:
  Key server_key_;
  Key challenge_key_;
  uint64_t match_tag_;
};

/// The client's side of the handshake.
class ClientHandshake {
 public:
  explicit ClientHandshake(const ConnectToken& token);

  /// The Request to send (again, until a Challenge arrives).
  const std::vector<uint8_t>& request() const { return request_; }
  /// A Challenge: the Response to send (again, until the server answers)
  /// in `response`, and the session is established. Only the first
  /// Challenge counts: later ones (answers to resent requests) give the
  /// same Response. kCorrupt when it is not a Challenge sealed with this
  /// token's key.
  Status on_challenge(std::span<const uint8_t> packet, std::vector<uint8_t>& response);
  /// The client's end, once a Challenge was accepted.
  std::optional<SecureSession>& session() { return session_; }

 private:
  ConnectToken token_;
  std::vector<uint8_t> request_;
  std::vector<uint8_t> response_;
  std::optional<SecureSession> session_;
};

/// The first byte of a datagram as a secure packet kind, if it is one.
std::optional<SecurePacket> secure_packet_kind(std::span<const uint8_t> datagram);

}  // namespace rwd::net
