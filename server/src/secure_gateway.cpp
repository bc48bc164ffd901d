// SPDX-License-Identifier: MIT
#include "rewind/server/secure_gateway.h"

#include <algorithm>

namespace rwd::server {

net::PeerAddress peer_address(const Endpoint& endpoint) {
  net::PeerAddress out;
  const asio::ip::address address = endpoint.address();
  const asio::ip::address_v6 v6 =
      address.is_v4() ? asio::ip::make_address_v6(asio::ip::v4_mapped, address.to_v4())
                      : address.to_v6();
  const asio::ip::address_v6::bytes_type bytes = v6.to_bytes();
  std::copy(bytes.begin(), bytes.end(), out.ip.begin());
  out.port = endpoint.port();
  return out;
}

SecureGateway::SecureGateway(const net::Key& server_key, std::string_view match_id, uint32_t slots,
                             SendFn send)
    : gate_(server_key, net::generate_key(), net::connect_match_tag(match_id)),
      slots_(slots),
      send_(std::move(send)) {}

SecureGateway::Client* SecureGateway::find(const Endpoint& endpoint) {
  for (Client& c : clients_) {
    if (c.endpoint == endpoint) return &c;
  }
  return nullptr;
}

void SecureGateway::on_datagram(std::span<const uint8_t> bytes, const Endpoint& from,
                                int64_t now_unix_s, const DeliverFn& deliver) {
  const std::optional<net::SecurePacket> kind = net::secure_packet_kind(bytes);
  if (!kind) {
    ++stats_.dropped;
    return;
  }
  switch (*kind) {
    case net::SecurePacket::kRequest:
      if (gate_.on_request(bytes, peer_address(from), now_unix_s, buffer_).ok()) {
        ++stats_.challenges;
        send_(from, buffer_);
      } else {
        ++stats_.refused;
      }
      return;
    case net::SecurePacket::kResponse:
      on_response(bytes, from, now_unix_s);
      return;
    case net::SecurePacket::kPayload: {
      Client* client = find(from);
      if (client == nullptr || !client->session.open(bytes, plain_).ok()) {
        ++stats_.dropped;
        return;
      }
      client->last_heard_unix_s = now_unix_s;
      deliver(plain_, from, Admission{client->slot, client->client_id});
      return;
    }
    case net::SecurePacket::kChallenge:
      break;
  }
  ++stats_.dropped;
}

void SecureGateway::on_response(std::span<const uint8_t> bytes, const Endpoint& from,
                                int64_t now_unix_s) {
  Result<net::ConnectedClient> connected = gate_.on_response(bytes, peer_address(from), now_unix_s);
  if (!connected.ok() || connected->slot >= slots_) {
    ++stats_.refused;
    return;
  }
  // The same handshake again (the client resends its response until the
  // server speaks): the session stands.
  if (Client* same = find(from);
      same != nullptr && same->slot == connected->slot && same->salt == connected->salt) {
    return;
  }
  // Another client's token for a slot whose holder is still talking is
  // refused here: it must not cut the holder off.
  for (const Client& c : clients_) {
    if (c.slot == connected->slot && c.client_id != connected->client_id &&
        now_unix_s - c.last_heard_unix_s < kHolderQuietS) {
      ++stats_.refused;
      return;
    }
  }
  // One session per slot and per address: a new handshake (a restarted
  // client, a new address) replaces what either held. Only the holder of
  // the token's keys can get here.
  std::erase_if(clients_,
                [&](const Client& c) { return c.slot == connected->slot || c.endpoint == from; });
  Client client;
  client.endpoint = from;
  client.client_id = connected->client_id;
  client.slot = connected->slot;
  client.salt = connected->salt;
  client.last_heard_unix_s = now_unix_s;
  client.session = std::move(connected->session);
  clients_.push_back(std::move(client));
  ++stats_.connects;
}

void SecureGateway::send(const Endpoint& to, std::span<const uint8_t> envelope) {
  Client* client = find(to);
  if (client == nullptr) return;
  client->session.seal(envelope, buffer_);
  send_(to, buffer_);
}

}  // namespace rwd::server
