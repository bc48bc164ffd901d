// SPDX-License-Identifier: MIT
// Secure-connection parsers, fed the same bytes: the connect token reader,
// the hex reader, the server's request and response handlers, the client's
// challenge handler, a session's payload opener, and a tokenless server's
// address-cookie handlers (hello, join) with the client's cookie reader.
// None may crash, and none may accept what was not made with the keys
// (these keys are fresh per process and never appear in the input, so
// anything accepted is a broken invariant) -- except the token reader,
// whose input is not sealed, and the hello, which any client may send
// (but whose answer is never larger than it).
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string_view>
#include <vector>

#include "fuzz_entries.h"
#include "rewind/net/address_cookie.h"
#include "rewind/net/connect_token.h"
#include "rewind/net/secure_channel.h"

namespace {

[[noreturn]] void invariant_broken(const char* what) {
  std::fprintf(stderr, "fuzz_secure_packet: invariant broken: %s\n", what);
  std::abort();
}

struct Keys {
  rwd::net::Key server = rwd::net::generate_key();
  rwd::net::Key challenge = rwd::net::generate_key();
  rwd::net::Key cookie = rwd::net::generate_key();
  uint64_t tag = rwd::net::connect_match_tag("fuzz");
  rwd::net::ConnectToken token =
      *rwd::net::make_connect_token(server, "fuzz", 0, 1, 1'900'003'600, 1'900'000'000);
};

const Keys& keys() {
  static const Keys k;
  return k;
}

}  // namespace

int fuzz_secure_packet_one(const uint8_t* data, size_t size) {
  using namespace rwd::net;
  const std::span<const uint8_t> bytes(data, size);
  const Keys& k = keys();
  rwd::Result<ConnectToken> token = read_connect_token(bytes);
  if (token.ok() &&
      write_connect_token(*token) != std::vector<uint8_t>(bytes.begin(), bytes.end())) {
    invariant_broken("token round trip changed the bytes");
  }
  (void)from_hex(std::string_view(reinterpret_cast<const char*>(data), size));
  PeerAddress from;
  from.port = 4000;
  ServerGate gate(k.server, k.challenge, k.tag);
  std::vector<uint8_t> reply;
  if (gate.on_request(bytes, from, 1'900'000'000, reply).ok()) {
    invariant_broken("a request accepted without the server key");
  }
  if (!reply.empty()) invariant_broken("a refused request got a reply");
  if (gate.on_response(bytes, from, 1'900'000'000).ok()) {
    invariant_broken("a response accepted without the challenge key");
  }
  ClientHandshake client(k.token);
  std::vector<uint8_t> response;
  if (client.on_challenge(bytes, response).ok()) {
    invariant_broken("a challenge accepted without the token's key");
  }
  SecureSession session(generate_key(), generate_key(), k.tag);
  std::vector<uint8_t> out;
  if (session.open(bytes, out).ok()) invariant_broken("a payload accepted without the key");
  const AddressCookieGate cookies(k.cookie);
  if (cookies.on_hello(bytes, from, 1'900'000'000, reply).ok()) {
    if (reply.size() > size) invariant_broken("a cookie larger than its hello");
  } else if (!reply.empty()) {
    invariant_broken("a refused hello got a reply");
  }
  if (cookies.open_join(bytes, from, 1'900'000'000).ok()) {
    invariant_broken("a join accepted without the cookie key");
  }
  if (const std::optional<AddressCookie> cookie = read_cookie(bytes);
      cookie && size != kCookieReplyBytes) {
    invariant_broken("a cookie read from a packet of the wrong size");
  }
  return 0;
}
