// SPDX-License-Identifier: MIT
#include "rewind/net/join_token.h"

#include <array>
#include <cstring>
#include <string>

// Header-only use keeps libxxhash out of the link line.
#define XXH_INLINE_ALL
#include <xxhash.h>

namespace rwd::net {
namespace {

constexpr size_t kBodyBytes = 1 + 4 + 8 + 8;
constexpr size_t kTagBytes = 16;
static_assert(kBodyBytes + kTagBytes == kJoinTokenBytes);
constexpr size_t kSlotOffset = 1;
constexpr size_t kExpiryOffset = 5;
constexpr size_t kMatchOffset = 13;

// Domain separation: a token tag can never equal some other keyed hash made
// from the same server secret.
constexpr std::string_view kDomain = "rewind.join_token.v1";

void put_le(uint8_t* out, uint64_t value, size_t bytes) {
  for (size_t i = 0; i < bytes; ++i) out[i] = static_cast<uint8_t>(value >> (8 * i));
}

uint64_t get_le(const uint8_t* in, size_t bytes) {
  uint64_t value = 0;
  for (size_t i = 0; i < bytes; ++i) value |= uint64_t{in[i]} << (8 * i);
  return value;
}

uint64_t match_tag(std::string_view match_id) {
  return XXH3_64bits(match_id.data(), match_id.size());
}

std::array<uint8_t, kTagBytes> compute_tag(std::string_view secret, const uint8_t* body) {
  // Key material = domain | secret, stretched into a full-entropy XXH3 secret.
  std::string key_material(kDomain);
  key_material.append(secret);
  std::array<uint8_t, XXH3_SECRET_DEFAULT_SIZE> xxh_secret{};
  (void)XXH3_generateSecret(xxh_secret.data(), xxh_secret.size(), key_material.data(),
                            key_material.size());
  const XXH128_hash_t h =
      XXH3_128bits_withSecret(body, kBodyBytes, xxh_secret.data(), xxh_secret.size());
  std::array<uint8_t, kTagBytes> tag{};
  put_le(tag.data(), h.low64, 8);
  put_le(tag.data() + 8, h.high64, 8);
  return tag;
}

// Always touches every byte, so the time taken does not reveal how long a
// prefix of a forged tag was right.
bool equal_constant_time(const uint8_t* a, const uint8_t* b, size_t n) {
  volatile uint8_t diff = 0;
  for (size_t i = 0; i < n; ++i) diff = static_cast<uint8_t>(diff | (a[i] ^ b[i]));
  return diff == 0;
}

Status bad(ErrorCode code, const std::string& message) {
  return Status::Error(code, "join token: " + message);
}

}  // namespace

Result<std::vector<uint8_t>> make_join_token(std::string_view secret, uint32_t player_slot,
                                             std::string_view match_id, int64_t expiry_unix_s) {
  if (secret.empty()) return bad(ErrorCode::kInvalidArgument, "empty server secret");
  std::vector<uint8_t> token(kJoinTokenBytes);
  token[0] = kJoinTokenVersion;
  put_le(token.data() + kSlotOffset, player_slot, 4);
  put_le(token.data() + kExpiryOffset, static_cast<uint64_t>(expiry_unix_s), 8);
  put_le(token.data() + kMatchOffset, match_tag(match_id), 8);
  const auto tag = compute_tag(secret, token.data());
  std::memcpy(token.data() + kBodyBytes, tag.data(), kTagBytes);
  return token;
}

Result<uint32_t> verify_join_token(std::string_view secret, std::span<const uint8_t> token,
                                   std::string_view match_id, int64_t now_unix_s) {
  if (secret.empty()) return bad(ErrorCode::kInvalidArgument, "empty server secret");
  if (token.size() != kJoinTokenBytes) {
    return bad(ErrorCode::kCorrupt, "bad length " + std::to_string(token.size()) + ", expected " +
                                        std::to_string(kJoinTokenBytes));
  }
  if (token[0] != kJoinTokenVersion) {
    return bad(ErrorCode::kCorrupt, "unknown version " + std::to_string(token[0]));
  }
  const auto tag = compute_tag(secret, token.data());
  if (!equal_constant_time(tag.data(), token.data() + kBodyBytes, kTagBytes)) {
    return bad(ErrorCode::kInvalidArgument, "bad MAC (forged, tampered or other secret)");
  }
  if (get_le(token.data() + kMatchOffset, 8) != match_tag(match_id)) {
    return bad(ErrorCode::kInvalidArgument, "wrong match");
  }
  const auto expiry = static_cast<int64_t>(get_le(token.data() + kExpiryOffset, 8));
  if (now_unix_s >= expiry) {
    return bad(ErrorCode::kInvalidArgument,
               "expired at " + std::to_string(expiry) + ", now " + std::to_string(now_unix_s));
  }
  return static_cast<uint32_t>(get_le(token.data() + kSlotOffset, 4));
}

}  // namespace rwd::net
