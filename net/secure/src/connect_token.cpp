// SPDX-License-Identifier: MIT
#include "rewind/net/connect_token.h"

#include <cctype>

#include "sodium_util.h"

namespace rwd::net {
namespace {

using detail::Reader;
using detail::Writer;

static_assert(crypto_aead_xchacha20poly1305_ietf_NPUBBYTES == kTokenNonceBytes);
static_assert(crypto_aead_xchacha20poly1305_ietf_KEYBYTES == kKeyBytes);
constexpr size_t kPrivateBytes = kSealedTokenBytes - crypto_aead_xchacha20poly1305_ietf_ABYTES;
constexpr size_t kTokenAdBytes = 1 + 8 + 8 + 4;

// The associated data every sealed part is bound to: a token opens only
// for its own version, match, expiry and slot.
void token_ad(uint64_t match_tag, int64_t expiry, uint32_t slot, uint8_t* out) {
  Writer w{out};
  w.u8(kConnectTokenVersion);
  w.le(match_tag, 8);
  w.le(static_cast<uint64_t>(expiry), 8);
  w.le(slot, 4);
}

}  // namespace

uint64_t connect_match_tag(std::string_view match_id) {
  detail::ensure_sodium();
  // Keyed by a constant so the tag is Rewind's own, not a bare hash.
  static constexpr uint8_t kKey[16] = {'r', 'e', 'w', 'i', 'n', 'd', '.', 'm',
                                       'a', 't', 'c', 'h', '.', 't', 'a', 'g'};
  uint8_t out[8];
  crypto_generichash(out, sizeof out, reinterpret_cast<const uint8_t*>(match_id.data()),
                     match_id.size(), kKey, sizeof kKey);
  return detail::get_le(out, 8);
}

Key generate_key() {
  detail::ensure_sodium();
  Key key;
  randombytes_buf(key.data(), key.size());
  return key;
}

Result<ConnectToken> make_connect_token(const Key& server_key, std::string_view match_id,
                                        uint32_t slot, uint64_t client_id, int64_t expiry_unix_s,
                                        int64_t now_unix_s) {
  if (match_id.empty()) {
    return Status::Error(ErrorCode::kInvalidArgument, "the match id must not be empty");
  }
  if (client_id == 0) return Status::Error(ErrorCode::kInvalidArgument, "client id 0 is reserved");
  if (expiry_unix_s <= now_unix_s || expiry_unix_s - now_unix_s > kMaxTokenLifetimeS) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "the expiry must be after now and at most a day ahead");
  }
  detail::ensure_sodium();
  ConnectToken token;
  token.match_tag = connect_match_tag(match_id);
  token.expiry_unix_s = expiry_unix_s;
  token.slot = slot;
  token.client_id = client_id;
  token.client_to_server_key = generate_key();
  token.server_to_client_key = generate_key();
  randombytes_buf(token.nonce.data(), token.nonce.size());
  uint8_t plain[kPrivateBytes];
  Writer w{plain};
  w.le(client_id, 8);
  w.le(slot, 4);
  w.raw(token.client_to_server_key.data(), kKeyBytes);
  w.raw(token.server_to_client_key.data(), kKeyBytes);
  uint8_t ad[kTokenAdBytes];
  token_ad(token.match_tag, expiry_unix_s, slot, ad);
  unsigned long long sealed_size = 0;
  crypto_aead_xchacha20poly1305_ietf_encrypt(token.sealed.data(), &sealed_size, plain, sizeof plain,
                                             ad, sizeof ad, nullptr, token.nonce.data(),
                                             server_key.data());
  sodium_memzero(plain, sizeof plain);
  return token;
}

std::vector<uint8_t> write_connect_token(const ConnectToken& t) {
  std::vector<uint8_t> out(kConnectTokenBytes);
  Writer w{out.data()};
  w.u8(kConnectTokenVersion);
  w.le(t.match_tag, 8);
  w.le(static_cast<uint64_t>(t.expiry_unix_s), 8);
  w.le(t.slot, 4);
  w.le(t.client_id, 8);
  w.raw(t.client_to_server_key.data(), kKeyBytes);
  w.raw(t.server_to_client_key.data(), kKeyBytes);
  w.raw(t.nonce.data(), t.nonce.size());
  w.raw(t.sealed.data(), t.sealed.size());
  return out;
}

Result<ConnectToken> read_connect_token(std::span<const uint8_t> bytes) {
  if (bytes.size() != kConnectTokenBytes) {
    return Status::Error(ErrorCode::kCorrupt, "a connect token is " +
                                                  std::to_string(kConnectTokenBytes) +
                                                  " bytes, not " + std::to_string(bytes.size()));
  }
  Reader r{bytes.data()};
  if (r.u8() != kConnectTokenVersion) {
    return Status::Error(ErrorCode::kCorrupt, "unknown connect token version");
  }
  ConnectToken t;
  t.match_tag = r.le(8);
  t.expiry_unix_s = static_cast<int64_t>(r.le(8));
  t.slot = static_cast<uint32_t>(r.le(4));
  t.client_id = r.le(8);
  r.raw(t.client_to_server_key.data(), kKeyBytes);
  r.raw(t.server_to_client_key.data(), kKeyBytes);
  r.raw(t.nonce.data(), t.nonce.size());
  r.raw(t.sealed.data(), t.sealed.size());
  if (t.client_id == 0) return Status::Error(ErrorCode::kCorrupt, "connect token for client id 0");
  return t;
}

Result<PrivateToken> open_private_token(const Key& server_key, uint64_t match_tag,
                                        int64_t expiry_unix_s, uint32_t slot,
                                        std::span<const uint8_t, kTokenNonceBytes> nonce,
                                        std::span<const uint8_t, kSealedTokenBytes> sealed,
                                        int64_t now_unix_s) {
  detail::ensure_sodium();
  uint8_t ad[kTokenAdBytes];
  token_ad(match_tag, expiry_unix_s, slot, ad);
  uint8_t plain[kPrivateBytes];
  unsigned long long plain_size = 0;
  if (crypto_aead_xchacha20poly1305_ietf_decrypt(plain, &plain_size, nullptr, sealed.data(),
                                                 sealed.size(), ad, sizeof ad, nonce.data(),
                                                 server_key.data()) != 0) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "the token was not made for this server and match");
  }
  if (now_unix_s >= expiry_unix_s) {
    sodium_memzero(plain, sizeof plain);
    return Status::Error(ErrorCode::kInvalidArgument, "the token has expired");
  }
  PrivateToken out;
  Reader r{plain};
  out.client_id = r.le(8);
  out.slot = static_cast<uint32_t>(r.le(4));
  r.raw(out.client_to_server_key.data(), kKeyBytes);
  r.raw(out.server_to_client_key.data(), kKeyBytes);
  sodium_memzero(plain, sizeof plain);
  if (out.slot != slot || out.client_id == 0) {
    return Status::Error(ErrorCode::kInvalidArgument, "the token's sealed part disagrees");
  }
  return out;
}

std::string to_hex(std::span<const uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  out.reserve(bytes.size() * 2);
  for (const uint8_t b : bytes) {
    out.push_back(kDigits[b >> 4]);
    out.push_back(kDigits[b & 15]);
  }
  return out;
}

Result<std::vector<uint8_t>> from_hex(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) {
    text.remove_prefix(1);
  }
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) {
    text.remove_suffix(1);
  }
  if (text.size() % 2 != 0) return Status::Error(ErrorCode::kCorrupt, "odd number of hex digits");
  const auto digit = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::vector<uint8_t> out(text.size() / 2);
  for (size_t i = 0; i < out.size(); ++i) {
    const int hi = digit(text[2 * i]);
    const int lo = digit(text[2 * i + 1]);
    if (hi < 0 || lo < 0) {
      return Status::Error(ErrorCode::kCorrupt, "not a hex digit at " + std::to_string(2 * i));
    }
    out[i] = static_cast<uint8_t>(hi * 16 + lo);
  }
  return out;
}

Result<Key> key_from_hex(std::string_view text) {
  auto bytes = from_hex(text);
  if (!bytes.ok()) return bytes.status();
  if (bytes->size() != kKeyBytes) {
    return Status::Error(ErrorCode::kCorrupt, "a key is 64 hex digits");
  }
  Key key;
  for (size_t i = 0; i < kKeyBytes; ++i) key[i] = (*bytes)[i];
  return key;
}

}  // namespace rwd::net
