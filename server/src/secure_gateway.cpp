// SPDX-License-Identifier: MIT
#include "rewind/server/secure_gateway.h"

#include <algorithm>
#include <cstring>

namespace rwd::server {
namespace {

constexpr const char* kReused = "the token was used before";

}  // namespace

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

SecureGateway::SecureGateway(const net::Key& server_key, std::string_view match_id, Options options,
                             SendFn send)
    : gate_(server_key, net::generate_key(), net::connect_match_tag(match_id)),
      options_(std::move(options)),
      send_(std::move(send)),
      used_(options_.used_token_capacity) {}

SecureGateway::Client* SecureGateway::find(const Endpoint& endpoint) {
  for (Client& c : clients_) {
    if (c.endpoint == endpoint) return &c;
  }
  return nullptr;
}

bool SecureGateway::holds(const Client& client, int64_t now_unix_s) const {
  if (!options_.seated) return now_unix_s - client.last_heard_unix_s < options_.join_grace_s;
  if (options_.seated(client.slot, client.endpoint)) return true;
  // Not seated: either its join is still on its way (a short claim), or
  // the match has dropped it (no claim at all).
  return !client.seated_once && now_unix_s - client.connected_unix_s < options_.join_grace_s;
}

const char* SecureGateway::refusal(uint64_t client_id, uint32_t slot, const net::TokenMac& mac,
                                   int64_t now_unix_s) {
  if (slot >= options_.slots) return "a token for a slot this match does not have";
  if (used_.used(mac, now_unix_s)) return kReused;
  for (const Client& c : clients_) {
    if (!holds(c, now_unix_s)) continue;
    // netcode.io's rule: a client that is connected is not connected again
    // (a restarted client waits until the match drops its old connection).
    if (c.client_id == client_id) return "this client is connected";
    if (c.slot == slot) return "the slot is held by another client";
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
      on_request(bytes, from, now_unix_s);
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
      // Until the match first seats it, a session's claim runs out with its
      // grace; from then on only the match's word counts. (The host only
      // sends while it is delivered to: the sessions stay as they were.)
      if (!client->seated_once && options_.seated) {
        client->seated_once = options_.seated(client->slot, from);
      }
      return;
    }
    case net::SecurePacket::kChallenge:
      break;
  }
  ++stats_.dropped;
}

void SecureGateway::on_request(std::span<const uint8_t> bytes, const Endpoint& from,
                               int64_t now_unix_s) {
  net::RequestedToken token;
  if (!gate_.on_request(bytes, peer_address(from), now_unix_s, buffer_, &token).ok()) {
    ++stats_.refused;
    return;
  }
  // Refused now rather than after a round trip: the challenge would only
  // be answered with a response refused for the same reason.
  if (const char* why = refusal(token.client_id, token.slot, token.mac, now_unix_s)) {
    ++stats_.refused;
    if (why == kReused) ++stats_.reused;
    return;
  }
  ++stats_.challenges;
  send_(from, buffer_);
}

void SecureGateway::on_response(std::span<const uint8_t> bytes, const Endpoint& from,
                                int64_t now_unix_s) {
  Result<net::ConnectedClient> connected = gate_.on_response(bytes, peer_address(from), now_unix_s);
  if (!connected.ok()) {
    ++stats_.refused;
    return;
  }
  // The same handshake again (the client resends its response until the
  // server speaks): the session stands.
  if (Client* same = find(from);
      same != nullptr && same->slot == connected->slot && same->salt == connected->salt) {
    return;
  }
  // Checked again: sessions may have come and gone since the challenge.
  if (const char* why =
          refusal(connected->client_id, connected->slot, connected->token_mac, now_unix_s)) {
    ++stats_.refused;
    if (why == kReused) ++stats_.reused;
    return;
  }
  // Remembered from the moment a key holder connected with it, not when it
  // was first presented: a token's sealed part copied off the wire could
  // otherwise be burnt by whoever saw it first.
  if (used_.record(connected->token_mac, connected->token_expiry_unix_s, now_unix_s) !=
      net::UsedTokens::Outcome::kRecorded) {
    ++stats_.refused;
    return;
  }
  // One session per slot and per address: whatever either held no longer
  // holds (refusal() said so), and only the token's key holder gets here.
  std::erase_if(clients_,
                [&](const Client& c) { return c.slot == connected->slot || c.endpoint == from; });
  Client client;
  client.endpoint = from;
  client.client_id = connected->client_id;
  client.slot = connected->slot;
  client.salt = connected->salt;
  client.connected_unix_s = now_unix_s;
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
