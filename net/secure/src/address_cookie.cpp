// SPDX-License-Identifier: MIT
#include "rewind/net/address_cookie.h"

#include <cstring>

#include "sodium_util.h"

namespace rwd::net {
namespace {

using detail::Writer;

}  // namespace

AddressCookie AddressCookieGate::cookie(const PeerAddress& address, int64_t window) const {
  detail::ensure_sodium();
  uint8_t message[16 + 2 + 8];
  Writer w{message};
  w.raw(address.ip.data(), address.ip.size());
  w.le(address.port, 2);
  w.le(static_cast<uint64_t>(window), 8);
  AddressCookie out;
  crypto_generichash(out.data(), out.size(), message, sizeof message, key_.data(), key_.size());
  return out;
}

Status AddressCookieGate::on_hello(std::span<const uint8_t> packet, const PeerAddress& from,
                                   int64_t now_s, std::vector<uint8_t>& reply) const {
  reply.clear();
  if (packet.size() != kHelloBytes || packet[0] != static_cast<uint8_t>(CookiePacket::kHello) ||
      packet[1] != kAddressCookieVersion) {
    return Status::Error(ErrorCode::kCorrupt, "a hello is exactly 64 bytes of this version");
  }
  const AddressCookie made = cookie(from, now_s / kCookieWindowS);
  reply.resize(kCookieReplyBytes);
  reply[0] = static_cast<uint8_t>(CookiePacket::kCookie);
  std::memcpy(reply.data() + 1, made.data(), made.size());
  return Status::Ok();
}

Result<std::span<const uint8_t>> AddressCookieGate::open_join(std::span<const uint8_t> packet,
                                                              const PeerAddress& from,
                                                              int64_t now_s) const {
  if (packet.size() <= kJoinOverhead || packet[0] != static_cast<uint8_t>(CookiePacket::kJoin)) {
    return Status::Error(ErrorCode::kCorrupt, "not a join packet");
  }
  const int64_t window = now_s / kCookieWindowS;
  for (const int64_t w : {window, window - 1}) {
    const AddressCookie expected = cookie(from, w);
    if (sodium_memcmp(expected.data(), packet.data() + 1, kCookieBytes) == 0) {
      return packet.subspan(kJoinOverhead);
    }
  }
  return Status::Error(ErrorCode::kInvalidArgument,
                       "a cookie not made for this address, or too old");
}

std::vector<uint8_t> make_hello() {
  std::vector<uint8_t> hello(kHelloBytes, 0);
  hello[0] = static_cast<uint8_t>(CookiePacket::kHello);
  hello[1] = kAddressCookieVersion;
  return hello;
}

std::optional<AddressCookie> read_cookie(std::span<const uint8_t> packet) {
  if (packet.size() != kCookieReplyBytes ||
      packet[0] != static_cast<uint8_t>(CookiePacket::kCookie)) {
    return std::nullopt;
  }
  AddressCookie out;
  std::memcpy(out.data(), packet.data() + 1, out.size());
  return out;
}

void frame_join(const AddressCookie& cookie, std::span<const uint8_t> envelope,
                std::vector<uint8_t>& out) {
  out.resize(kJoinOverhead + envelope.size());
  out[0] = static_cast<uint8_t>(CookiePacket::kJoin);
  std::memcpy(out.data() + 1, cookie.data(), cookie.size());
  if (!envelope.empty()) std::memcpy(out.data() + kJoinOverhead, envelope.data(), envelope.size());
}

std::optional<CookiePacket> cookie_packet_kind(std::span<const uint8_t> datagram) {
  if (datagram.empty()) return std::nullopt;
  switch (datagram[0]) {
    case 0xB1:
    case 0xB2:
    case 0xB3:
      return static_cast<CookiePacket>(datagram[0]);
    default:
      return std::nullopt;
  }
}

}  // namespace rwd::net
