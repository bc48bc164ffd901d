// SPDX-License-Identifier: MIT
#pragma once
// Proof of address for a tokenless server, after QUIC's Retry token and
// netcode.io's challenge. A tokenless server seats whoever asks, so before
// it sends anything to an address that address must show it receives what
// is sent there: otherwise one datagram with a forged source would make
// the server stream a match to a victim, or fill a lobby with nobody.
// Stateless, like the secure handshake: the cookie is a keyed MAC of the
// address, the port and a coarse time window, under a per-process key.
//
//   client                                   server
//   Hello   (padded to kHelloBytes)   ---->   keeps nothing
//           <----  Cookie (MAC of address, port, time window; never
//                  larger than the Hello)
//   Join    (the cookie and the JoinRequest envelope)  ---->  the cookie
//           must be this address's, from this window or the one before:
//           only then is the join seen and answered
//   envelopes  <---->  in the clear; the join's connection id and address
//                      name the client from then on
//
// This proves an address, not an identity: anyone who sees the traffic can
// still act for a client (tokenless mode is for trusted networks).
//
// Packet layouts (the first byte names the packet; an Envelope begins with
// 0x08, its protocol_version field):
//   Hello   0xB1 | version u8 | zero padding to kHelloBytes
//   Cookie  0xB2 | cookie 16
//   Join    0xB3 | cookie 16 | envelope (a JoinRequest)
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/net/connect_token.h"
#include "rewind/net/secure_channel.h"

namespace rwd::net {

enum class CookiePacket : uint8_t {
  kHello = 0xB1,
  kCookie = 0xB2,
  kJoin = 0xB3,
};

inline constexpr uint8_t kAddressCookieVersion = 1;
inline constexpr size_t kCookieBytes = 16;
inline constexpr size_t kCookieReplyBytes = 1 + kCookieBytes;
/// A Hello is padded to this size, so the Cookie answering it is smaller.
inline constexpr size_t kHelloBytes = 64;
static_assert(kCookieReplyBytes <= kHelloBytes);
inline constexpr size_t kJoinOverhead = 1 + kCookieBytes;
/// A cookie is made for a window of this many seconds and accepted in that
/// window and the next: it lives between one and two windows.
inline constexpr int64_t kCookieWindowS = 4;

using AddressCookie = std::array<uint8_t, kCookieBytes>;

/// The server's side. Stateless: it holds only its key.
class AddressCookieGate {
 public:
  /// `key`: a fresh generate_key() per process (a restart voids only the
  /// cookies in flight).
  explicit AddressCookieGate(const Key& key) : key_(key) {}

  /// A Hello from `from` at `now_s` (seconds on any clock that does not go
  /// back): the Cookie to send back into `reply`, or kCorrupt (not a Hello
  /// of this version and size) and nothing to send.
  Status on_hello(std::span<const uint8_t> packet, const PeerAddress& from, int64_t now_s,
                  std::vector<uint8_t>& reply) const;
  /// A Join from `from`: the envelope it carries (a view into `packet`),
  /// or kCorrupt (malformed) / kInvalidArgument (a cookie not made for
  /// this address and port, or too old).
  Result<std::span<const uint8_t>> open_join(std::span<const uint8_t> packet,
                                             const PeerAddress& from, int64_t now_s) const;

 private:
  AddressCookie cookie(const PeerAddress& address, int64_t window) const;

  Key key_;
};

/// The client's side: the Hello to send until a Cookie comes back.
std::vector<uint8_t> make_hello();
/// The cookie in a Cookie packet; nullopt for anything else.
std::optional<AddressCookie> read_cookie(std::span<const uint8_t> packet);
/// A Join carrying `cookie` and `envelope`, into `out` (replacing it).
void frame_join(const AddressCookie& cookie, std::span<const uint8_t> envelope,
                std::vector<uint8_t>& out);

/// The first byte of a datagram as a cookie packet kind, if it is one.
std::optional<CookiePacket> cookie_packet_kind(std::span<const uint8_t> datagram);

}  // namespace rwd::net
