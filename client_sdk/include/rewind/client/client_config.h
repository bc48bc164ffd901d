// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rewind/core/tick.h"
#include "rewind/net/fault_config.h"

namespace rwd::client {

struct ClientConfig {
  std::string server_address = "127.0.0.1";  ///< IPv4 or IPv6 literal
  uint16_t server_port = 7777;
  std::string game = "crates";  ///< must match the server's game
  std::string name = "client";  ///< shown in server logs, <= 64 bytes
  /// A serialized connect token (rewind-token mint; read_connect_token):
  /// required by a secure server, which names the slot by it; every
  /// datagram is then sealed. A token connects once: to come back (a new
  /// process, a lost connection) get a fresh token from the backend for the
  /// same client id and slot; the server takes it once it has dropped the
  /// old connection (its peer timeout). Empty: the tokenless mode of local
  /// tests (the join first fetches an address cookie from the server).
  std::vector<uint8_t> connect_token;
  /// Join as a spectator: a read-only seat that receives every final tick
  /// and verifies its checksum but sends no inputs (the input provider is
  /// never called). Joins at any time; a running match is caught up from a
  /// snapshot. On a secure server the token's slot names the seat.
  bool spectator = false;
  int32_t snapshot_ticks = 96;     ///< rollback depth; must exceed lead + window + RTT in ticks
  double join_timeout_s = 10.0;    ///< give up joining after this long
  double server_timeout_s = 5.0;   ///< silence after which the server is considered gone
  double target_lead_ticks = 2.0;  ///< how early our inputs should reach the server
  /// Network faults applied to both directions (tests and load tests).
  std::optional<net::FaultConfig> faults;
  /// Test hook: perturb the state right after simulating this tick, every
  /// time it is simulated, so the client desyncs there deterministically.
  Tick debug_corrupt_at_tick = kNoTick;
};

}  // namespace rwd::client
