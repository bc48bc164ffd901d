// SPDX-License-Identifier: MIT
#pragma once
// The tokenless server's front door (net/address_cookie.h): between the
// socket and the match host when the server has no key. Nothing is sent
// to an address before it has answered a cookie: a Hello gets a Cookie no
// larger than itself, and only a join carrying that address's cookie
// reaches the host as a join (with an Admission); every other datagram
// goes to the host as it came, where only a joined connection's envelopes
// from its own address are taken. So a datagram with a forged source can
// neither take a seat nor make the server stream to a victim.
// No socket and no clock: the shell passes datagrams and the time in.
#include <functional>
#include <span>

#include "rewind/net/address_cookie.h"
#include "rewind/net/clock.h"
#include "rewind/server/secure_gateway.h"

namespace rwd::server {

class TokenlessGateway {
 public:
  using SendFn = std::function<void(const Endpoint&, std::span<const uint8_t>)>;
  /// `who` is set for a join whose cookie checked, null otherwise.
  using DeliverFn =
      std::function<void(std::span<const uint8_t> envelope, const Endpoint&, const Admission* who)>;

  explicit TokenlessGateway(SendFn send);

  /// One datagram from the socket at `now`: a Hello is answered, a Join
  /// with a good cookie delivered admitted, a bad one dropped, anything
  /// else delivered as is.
  void on_datagram(std::span<const uint8_t> bytes, const Endpoint& from, net::TimePoint now,
                   const DeliverFn& deliver);

  struct Stats {
    uint64_t cookies = 0;   ///< hellos answered
    uint64_t admitted = 0;  ///< joins whose cookie checked
    uint64_t refused = 0;   ///< malformed hellos, joins without a good cookie
  };
  const Stats& stats() const { return stats_; }

 private:
  net::AddressCookieGate gate_;
  SendFn send_;
  std::vector<uint8_t> reply_;
  Stats stats_;
};

}  // namespace rwd::server
