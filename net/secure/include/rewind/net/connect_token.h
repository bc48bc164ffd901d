// SPDX-License-Identifier: MIT
#pragma once
// Connect tokens. A match backend that shares a 32-byte secret key with
// the game server mints one token per client and hands it over a secure
// channel (HTTPS, the platform's session). The token holds:
//   - in the clear, for the client: the match, the slot, the expiry and
//     two fresh random keys (client to server, server to client);
//   - sealed for the server (XChaCha20-Poly1305 under the server key, with
//     the match, slot and expiry as associated data): the same slot, client
//     id and keys.
// The client sends only the sealed part. Whoever copies it off the wire
// lacks the keys, so cannot answer the server's challenge nor read or
// forge a packet: a token works only for the client holding its keys. And
// it works once: the server remembers a token that connected until it
// expires (UsedTokens), so a client that comes back needs a fresh token,
// minted for the same client id and slot.
//
// Wire layout of a serialized token (little-endian), kConnectTokenBytes:
//   version u8 | match tag u64 | expiry i64 | slot u32 | client id u64 |
//   client-to-server key 32 | server-to-client key 32 | nonce 24 |
//   sealed private part (client id u64, slot u32, both keys) + 16-byte tag
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/status.h"

namespace rwd::net {

inline constexpr size_t kKeyBytes = 32;
using Key = std::array<uint8_t, kKeyBytes>;

/// 2: the handshake's challenge token carries the token's MAC (tokens
/// connect once); version 1 tokens and requests are refused.
inline constexpr uint8_t kConnectTokenVersion = 2;
inline constexpr size_t kTokenNonceBytes = 24;
/// The sealed private part: client id, slot, both keys, the AEAD tag.
inline constexpr size_t kSealedTokenBytes = 8 + 4 + 2 * kKeyBytes + 16;
inline constexpr size_t kConnectTokenBytes =
    1 + 8 + 8 + 4 + 8 + 2 * kKeyBytes + kTokenNonceBytes + kSealedTokenBytes;
/// Longest a token may live, seconds (a day): a leaked token is useless
/// after that whatever the backend asked for.
inline constexpr int64_t kMaxTokenLifetimeS = 24 * 3600;

/// What a client holds: everything it needs to connect.
struct ConnectToken {
  uint64_t match_tag = 0;      ///< connect_match_tag(match id)
  int64_t expiry_unix_s = 0;   ///< the server refuses it from this second on
  uint32_t slot = 0;           ///< the player slot it takes
  uint64_t client_id = 0;      ///< the backend's id of the client (never 0)
  Key client_to_server_key{};  ///< seals what the client sends
  Key server_to_client_key{};  ///< seals what the server sends
  std::array<uint8_t, kTokenNonceBytes> nonce{};
  std::array<uint8_t, kSealedTokenBytes> sealed{};  ///< for the server only
};

/// What the server finds inside the sealed part.
struct PrivateToken {
  uint64_t client_id = 0;
  uint32_t slot = 0;
  Key client_to_server_key{};
  Key server_to_client_key{};
};

/// 64-bit tag of a match id, bound into tokens and packets (keyed BLAKE2b
/// of the id: tokens for one match never open in another).
uint64_t connect_match_tag(std::string_view match_id);

/// A fresh random key (the server key, or a per-process challenge key).
Key generate_key();

/// Mints a token for `slot` in `match_id`, valid until `expiry_unix_s`
/// (exclusive; at most kMaxTokenLifetimeS after `now_unix_s`).
/// kInvalidArgument for an empty match id, a client id of 0, an expiry not
/// after now or too far ahead.
Result<ConnectToken> make_connect_token(const Key& server_key, std::string_view match_id,
                                        uint32_t slot, uint64_t client_id, int64_t expiry_unix_s,
                                        int64_t now_unix_s);

/// Serializes a token (kConnectTokenBytes) / reads one back (kCorrupt for
/// a wrong size or version, a client id of 0).
std::vector<uint8_t> write_connect_token(const ConnectToken& token);
Result<ConnectToken> read_connect_token(std::span<const uint8_t> bytes);

/// Opens the sealed part for the server: kInvalidArgument when it was not
/// sealed under `server_key` for exactly this match tag, slot and expiry
/// (any byte changed), or when the expiry has passed.
Result<PrivateToken> open_private_token(const Key& server_key, uint64_t match_tag,
                                        int64_t expiry_unix_s, uint32_t slot,
                                        std::span<const uint8_t, kTokenNonceBytes> nonce,
                                        std::span<const uint8_t, kSealedTokenBytes> sealed,
                                        int64_t now_unix_s);

/// Lower-case hex, and back (kCorrupt for odd lengths or other characters;
/// surrounding whitespace is ignored), for key and token files.
std::string to_hex(std::span<const uint8_t> bytes);
Result<std::vector<uint8_t>> from_hex(std::string_view text);
/// A key from its 64 hex digits (kCorrupt otherwise).
Result<Key> key_from_hex(std::string_view text);

}  // namespace rwd::net
