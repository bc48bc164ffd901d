// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "rewind/sim/status.h"

namespace rwd::net {

/// Size of every join token in bytes: version (1) | player slot (u32 LE) |
/// expiry unix seconds (i64 LE) | match tag (u64 LE, XXH3-64 of the match
/// id) | tag (16 bytes).
inline constexpr size_t kJoinTokenBytes = 37;
/// Token layout version in byte 0.
inline constexpr uint8_t kJoinTokenVersion = 1;

/// Issues a token that lets its bearer take `player_slot` in match
/// `match_id` until `expiry_unix_s` (exclusive, Unix seconds). The
/// matchmaker and the game server share `secret` (any bytes, non-empty).
///
/// The tag is a keyed XXH3-128: the secret is stretched into an XXH3 secret
/// with XXH3_generateSecret and the token body hashed with
/// XXH3_128bits_withSecret. That stops casual forgery and tampering but it is
/// NOT a cryptographic MAC: XXH3 makes no claim against an attacker who
/// collects tokens and searches for the key. For production, swap the tag for
/// HMAC-SHA-256 (e.g. OpenSSL HMAC or libsodium crypto_auth) truncated to
/// 16 bytes; the layout and the API stay the same.
/// Errors: kInvalidArgument for an empty secret.
Result<std::vector<uint8_t>> make_join_token(std::string_view secret, uint32_t player_slot,
                                             std::string_view match_id, int64_t expiry_unix_s);

/// Checks a token and returns its player slot. Checks in this order, each
/// with its own message: length (kCorrupt "bad length"), version (kCorrupt),
/// tag (kInvalidArgument "bad MAC", compared in constant time), match
/// (kInvalidArgument "wrong match"), expiry (kInvalidArgument "expired" when
/// now_unix_s >= expiry). An empty secret is kInvalidArgument.
Result<uint32_t> verify_join_token(std::string_view secret, std::span<const uint8_t> token,
                                   std::string_view match_id, int64_t now_unix_s);

}  // namespace rwd::net
