// SPDX-License-Identifier: MIT
#include "rewind/net/secure_channel.h"

#include <cstring>
#include <string_view>

#include "sodium_util.h"

namespace rwd::net {
namespace {

using detail::Reader;
using detail::Writer;

constexpr size_t kTag = 16;
constexpr size_t kXNonce = crypto_aead_xchacha20poly1305_ietf_NPUBBYTES;
constexpr size_t kNonce = crypto_aead_chacha20poly1305_ietf_NPUBBYTES;
static_assert(kTag == crypto_aead_chacha20poly1305_ietf_ABYTES);
static_assert(kTag == crypto_aead_xchacha20poly1305_ietf_ABYTES);
static_assert(kTokenMacBytes == kTag);  // the MAC is the sealed part's AEAD tag
constexpr size_t kRequestHeader = 1 + 1 + 8 + 8 + 4;
static_assert(kRequestHeader + kTokenNonceBytes + kSealedTokenBytes <= kRequestBytes);
constexpr size_t kChallengePlain = kChallengeTokenBytes - kXNonce - kTag;
static_assert(kChallengeBytes < kRequestBytes && kResponseBytes < kRequestBytes);

Status corrupt(const char* what) {
  return Status::Error(ErrorCode::kCorrupt, what);
}
Status refused(const char* what) {
  return Status::Error(ErrorCode::kInvalidArgument, what);
}

void address_bytes(const PeerAddress& a, uint8_t* out) {
  Writer w{out};
  w.u8(6);
  w.raw(a.ip.data(), a.ip.size());
  w.le(a.port, 2);
}

// A session key: keyed BLAKE2b of the salt and the direction, under the
// token's key for that direction.
Key session_key(const Key& token_key, std::span<const uint8_t, kSaltBytes> salt,
                std::string_view direction) {
  crypto_generichash_state state;
  crypto_generichash_init(&state, token_key.data(), token_key.size(), kKeyBytes);
  crypto_generichash_update(&state, salt.data(), salt.size());
  crypto_generichash_update(&state, reinterpret_cast<const uint8_t*>(direction.data()),
                            direction.size());
  Key out;
  crypto_generichash_final(&state, out.data(), out.size());
  return out;
}

// The Response's proof: keyed BLAKE2b (16 bytes) of the challenge token
// under the client-to-server key.
void response_tag(const Key& c2s, const uint8_t* challenge_token, uint8_t* out) {
  crypto_generichash(out, kTag, challenge_token, kChallengeTokenBytes, c2s.data(), c2s.size());
}

void packet_nonce(uint64_t sequence, uint8_t* out) {
  std::memset(out, 0, kNonce);
  detail::put_le(out + kNonce - 8, sequence, 8);
}

void payload_ad(uint64_t match_tag, uint8_t* out) {
  Writer w{out};
  w.u8(static_cast<uint8_t>(SecurePacket::kPayload));
  w.le(match_tag, 8);
}

}  // namespace

std::optional<SecurePacket> secure_packet_kind(std::span<const uint8_t> datagram) {
  if (datagram.empty()) return std::nullopt;
  switch (datagram[0]) {
    case 0xC1:
    case 0xC2:
    case 0xC3:
    case 0xC4:
      return static_cast<SecurePacket>(datagram[0]);
    default:
      return std::nullopt;
  }
}

// --- replay window ---------------------------------------------------------

bool ReplayWindow::fresh(uint64_t sequence) const {
  if (!any_ || sequence > newest_) return true;
  if (newest_ - sequence >= kWindow) return false;
  const uint64_t bit = sequence % kWindow;
  return (seen_[bit / 64] >> (bit % 64) & 1u) == 0;
}

void ReplayWindow::accept(uint64_t sequence) {
  if (!any_ || sequence > newest_) {
    // Clear the slots the window slides past (all of them after a jump).
    const uint64_t gap = any_ ? sequence - newest_ : kWindow;
    if (gap >= kWindow) {
      seen_.fill(0);
    } else {
      for (uint64_t s = newest_ + 1; s <= sequence; ++s) {
        const uint64_t bit = s % kWindow;
        seen_[bit / 64] &= ~(uint64_t{1} << (bit % 64));
      }
    }
    newest_ = sequence;
    any_ = true;
  }
  const uint64_t bit = sequence % kWindow;
  seen_[bit / 64] |= uint64_t{1} << (bit % 64);
}

// --- session ---------------------------------------------------------------

SecureSession::SecureSession(const Key& send_key, const Key& receive_key, uint64_t match_tag)
    : send_key_(send_key), receive_key_(receive_key), match_tag_(match_tag) {}

void SecureSession::seal(std::span<const uint8_t> payload, std::vector<uint8_t>& out) {
  const uint64_t sequence = next_sequence_++;
  out.resize(kPayloadOverhead + payload.size());
  Writer w{out.data()};
  w.u8(static_cast<uint8_t>(SecurePacket::kPayload));
  w.le(sequence, 8);
  uint8_t nonce[kNonce];
  packet_nonce(sequence, nonce);
  uint8_t ad[9];
  payload_ad(match_tag_, ad);
  unsigned long long size = 0;
  crypto_aead_chacha20poly1305_ietf_encrypt(w.at, &size, payload.data(), payload.size(), ad,
                                            sizeof ad, nullptr, nonce, send_key_.data());
}

Status SecureSession::open(std::span<const uint8_t> packet, std::vector<uint8_t>& out) {
  if (packet.size() < kPayloadOverhead ||
      packet[0] != static_cast<uint8_t>(SecurePacket::kPayload)) {
    return corrupt("not a payload packet");
  }
  Reader r{packet.data() + 1};
  const uint64_t sequence = r.le(8);
  if (!window_.fresh(sequence)) return refused("a payload packet seen before, or too old");
  uint8_t nonce[kNonce];
  packet_nonce(sequence, nonce);
  uint8_t ad[9];
  payload_ad(match_tag_, ad);
  // Opened into the session's scratch buffer, then swapped with `out`:
  // a refused packet leaves `out` as it was, and the two buffers keep their
  // capacity, so a session allocates nothing per datagram once warm.
  scratch_.resize(packet.size() - kPayloadOverhead);
  unsigned long long size = 0;
  if (crypto_aead_chacha20poly1305_ietf_decrypt(scratch_.data(), &size, nullptr, r.at,
                                                packet.size() - 9, ad, sizeof ad, nonce,
                                                receive_key_.data()) != 0) {
    return corrupt("a payload packet that does not authenticate");
  }
  out.swap(scratch_);
  window_.accept(sequence);
  return Status::Ok();
}

// --- server ----------------------------------------------------------------

ServerGate::ServerGate(const Key& server_key, const Key& challenge_key, uint64_t match_tag)
    : server_key_(server_key), challenge_key_(challenge_key), match_tag_(match_tag) {
  detail::ensure_sodium();
}

Status ServerGate::on_request(std::span<const uint8_t> packet, const PeerAddress& from,
                              int64_t now_unix_s, std::vector<uint8_t>& reply,
                              RequestedToken* requested) {
  reply.clear();
  if (packet.size() != kRequestBytes || packet[0] != static_cast<uint8_t>(SecurePacket::kRequest)) {
    return corrupt("a request is exactly 1000 bytes");
  }
  Reader r{packet.data() + 1};
  if (r.u8() != kConnectTokenVersion) return corrupt("unknown connect token version");
  const uint64_t match_tag = r.le(8);
  const auto expiry = static_cast<int64_t>(r.le(8));
  const auto slot = static_cast<uint32_t>(r.le(4));
  if (match_tag != match_tag_) return refused("a token for another match");
  const std::span<const uint8_t, kTokenNonceBytes> nonce(r.at, kTokenNonceBytes);
  const std::span<const uint8_t, kSealedTokenBytes> sealed(r.at + kTokenNonceBytes,
                                                           kSealedTokenBytes);
  Result<PrivateToken> token =
      open_private_token(server_key_, match_tag, expiry, slot, nonce, sealed, now_unix_s);
  if (!token.ok()) return token.status();
  // The sealed part's tag names the token: it authenticated, so only the
  // backend's key could have made it, and no two tokens share it.
  TokenMac mac;
  std::memcpy(mac.data(), sealed.data() + kSealedTokenBytes - kTokenMacBytes, kTokenMacBytes);
  if (requested != nullptr) {
    *requested = RequestedToken{token->client_id, token->slot, expiry, mac};
  }

  // The challenge token: what the server needs to finish the handshake,
  // sealed under its own key and bound to the address it is sent to.
  uint8_t salt[kSaltBytes];
  randombytes_buf(salt, sizeof salt);
  uint8_t plain[kChallengePlain];
  Writer w{plain};
  w.le(token->client_id, 8);
  w.le(token->slot, 4);
  w.raw(token->client_to_server_key.data(), kKeyBytes);
  w.raw(token->server_to_client_key.data(), kKeyBytes);
  w.le(static_cast<uint64_t>(expiry), 8);
  w.le(static_cast<uint64_t>(now_unix_s + kChallengeLifetimeS), 8);
  address_bytes(from, w.at);
  w.at += kAddressBytes;
  w.raw(salt, sizeof salt);
  w.raw(mac.data(), mac.size());
  uint8_t challenge_token[kChallengeTokenBytes];
  randombytes_buf(challenge_token, kXNonce);
  unsigned long long size = 0;
  crypto_aead_xchacha20poly1305_ietf_encrypt(challenge_token + kXNonce, &size, plain, sizeof plain,
                                             nullptr, 0, nullptr, challenge_token,
                                             challenge_key_.data());
  sodium_memzero(plain, sizeof plain);

  // The Challenge: salt and challenge token, for the key holder only.
  uint8_t inner[kSaltBytes + kChallengeTokenBytes];
  std::memcpy(inner, salt, kSaltBytes);
  std::memcpy(inner + kSaltBytes, challenge_token, kChallengeTokenBytes);
  reply.resize(kChallengeBytes);
  reply[0] = static_cast<uint8_t>(SecurePacket::kChallenge);
  randombytes_buf(reply.data() + 1, kXNonce);
  crypto_aead_xchacha20poly1305_ietf_encrypt(reply.data() + 1 + kXNonce, &size, inner, sizeof inner,
                                             reply.data(), 1, nullptr, reply.data() + 1,
                                             token->server_to_client_key.data());
  return Status::Ok();
}

Result<ConnectedClient> ServerGate::on_response(std::span<const uint8_t> packet,
                                                const PeerAddress& from, int64_t now_unix_s) {
  if (packet.size() != kResponseBytes ||
      packet[0] != static_cast<uint8_t>(SecurePacket::kResponse)) {
    return corrupt("not a response packet");
  }
  const uint8_t* challenge_token = packet.data() + 1;
  uint8_t plain[kChallengePlain];
  unsigned long long size = 0;
  if (crypto_aead_xchacha20poly1305_ietf_decrypt(plain, &size, nullptr, challenge_token + kXNonce,
                                                 kChallengeTokenBytes - kXNonce, nullptr, 0,
                                                 challenge_token, challenge_key_.data()) != 0) {
    return refused("a challenge token this server did not issue");
  }
  ConnectedClient client;
  Key c2s;
  Key s2c;
  Reader r{plain};
  client.client_id = r.le(8);
  client.slot = static_cast<uint32_t>(r.le(4));
  r.raw(c2s.data(), kKeyBytes);
  r.raw(s2c.data(), kKeyBytes);
  client.token_expiry_unix_s = static_cast<int64_t>(r.le(8));
  const auto challenge_expiry = static_cast<int64_t>(r.le(8));
  uint8_t address[kAddressBytes];
  r.raw(address, kAddressBytes);
  r.raw(client.salt.data(), kSaltBytes);
  r.raw(client.token_mac.data(), kTokenMacBytes);
  sodium_memzero(plain, sizeof plain);
  uint8_t expected_address[kAddressBytes];
  address_bytes(from, expected_address);
  if (sodium_memcmp(address, expected_address, kAddressBytes) != 0) {
    return refused("a response from another address than the one challenged");
  }
  if (now_unix_s >= challenge_expiry || now_unix_s >= client.token_expiry_unix_s) {
    return refused("the challenge has expired");
  }
  uint8_t tag[kTag];
  response_tag(c2s, challenge_token, tag);
  if (crypto_verify_16(tag, challenge_token + kChallengeTokenBytes) != 0) {
    return refused("a response without the token's key");
  }
  const std::span<const uint8_t, kSaltBytes> salt(client.salt);
  client.session =
      SecureSession(session_key(s2c, salt, "s2c"), session_key(c2s, salt, "c2s"), match_tag_);
  return client;
}

// --- client ----------------------------------------------------------------

ClientHandshake::ClientHandshake(const ConnectToken& token) : token_(token) {
  detail::ensure_sodium();
  request_.assign(kRequestBytes, 0);
  Writer w{request_.data()};
  w.u8(static_cast<uint8_t>(SecurePacket::kRequest));
  w.u8(kConnectTokenVersion);
  w.le(token.match_tag, 8);
  w.le(static_cast<uint64_t>(token.expiry_unix_s), 8);
  w.le(token.slot, 4);
  w.raw(token.nonce.data(), token.nonce.size());
  w.raw(token.sealed.data(), token.sealed.size());
}

Status ClientHandshake::on_challenge(std::span<const uint8_t> packet,
                                     std::vector<uint8_t>& response) {
  if (packet.size() != kChallengeBytes ||
      packet[0] != static_cast<uint8_t>(SecurePacket::kChallenge)) {
    return corrupt("not a challenge packet");
  }
  uint8_t inner[kSaltBytes + kChallengeTokenBytes];
  unsigned long long size = 0;
  if (crypto_aead_xchacha20poly1305_ietf_decrypt(
          inner, &size, nullptr, packet.data() + 1 + kXNonce, packet.size() - 1 - kXNonce,
          packet.data(), 1, packet.data() + 1, token_.server_to_client_key.data()) != 0) {
    return corrupt("a challenge not sealed with this token's key");
  }
  if (session_) {
    // A later answer to a resent request: keep the first, so the server
    // sees one salt per handshake and an older response replayed at it
    // can never switch the session away from the one in use.
    response = response_;
    return Status::Ok();
  }
  response.resize(kResponseBytes);
  response[0] = static_cast<uint8_t>(SecurePacket::kResponse);
  std::memcpy(response.data() + 1, inner + kSaltBytes, kChallengeTokenBytes);
  response_tag(token_.client_to_server_key, response.data() + 1,
               response.data() + 1 + kChallengeTokenBytes);
  const std::span<const uint8_t, kSaltBytes> salt(inner, kSaltBytes);
  session_.emplace(session_key(token_.client_to_server_key, salt, "c2s"),
                   session_key(token_.server_to_client_key, salt, "s2c"), token_.match_tag);
  response_ = response;
  return Status::Ok();
}

}  // namespace rwd::net
