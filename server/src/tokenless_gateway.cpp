// SPDX-License-Identifier: MIT
#include "rewind/server/tokenless_gateway.h"

#include <chrono>

namespace rwd::server {
namespace {

int64_t seconds_of(net::TimePoint now) {
  return std::chrono::duration_cast<std::chrono::seconds>(now.time_since_epoch()).count();
}

}  // namespace

TokenlessGateway::TokenlessGateway(SendFn send)
    : gate_(net::generate_key()), send_(std::move(send)) {}

void TokenlessGateway::on_datagram(std::span<const uint8_t> bytes, const Endpoint& from,
                                   net::TimePoint now, const DeliverFn& deliver) {
  const std::optional<net::CookiePacket> kind = net::cookie_packet_kind(bytes);
  if (!kind) {
    deliver(bytes, from, nullptr);  // an envelope: the host checks whose
    return;
  }
  switch (*kind) {
    case net::CookiePacket::kHello:
      if (gate_.on_hello(bytes, peer_address(from), seconds_of(now), reply_).ok()) {
        ++stats_.cookies;
        send_(from, reply_);
        return;
      }
      break;
    case net::CookiePacket::kJoin: {
      Result<std::span<const uint8_t>> envelope =
          gate_.open_join(bytes, peer_address(from), seconds_of(now));
      if (!envelope.ok()) break;
      ++stats_.admitted;
      const Admission proven;
      deliver(*envelope, from, &proven);
      return;
    }
    case net::CookiePacket::kCookie:
      break;  // the server's to send, never to receive
  }
  ++stats_.refused;
}

}  // namespace rwd::server
