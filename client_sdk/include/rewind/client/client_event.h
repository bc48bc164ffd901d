// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>

#include "rewind/core/tick.h"

namespace rwd::client {

enum class ClientEventType : uint8_t {
  kJoined,        ///< the server gave us a slot (player)
  kMatchStarted,  ///< every slot is filled; ticks run
  kFinalTick,     ///< tick became final and our checksum matched the server's
  kDesync,        ///< our checksum for a final tick differs; a report was sent
  kResynced,      ///< state replaced by the server's snapshot at tick
  kMatchEnded,    ///< the server ended the match (reason)
  kRejected,      ///< the server refused our join (reason)
  kDisconnected,  ///< timed out or gave up (reason)
  /// The server's resync snapshot at tick did not load (reason); another
  /// was asked for and the session keeps waiting for it.
  kResyncRefused,
};

struct ClientEvent {
  ClientEventType type = ClientEventType::kJoined;
  Tick tick = kNoTick;
  uint32_t player = 0;
  uint64_t local_checksum = 0;
  uint64_t server_checksum = 0;
  std::string reason;
};

/// Running figures of one client session.
struct ClientStats {
  double rtt_ms = 0.0;  ///< smoothed round-trip time
  uint64_t rollbacks = 0;
  uint64_t resimulated_ticks = 0;
  int32_t ticks_ahead = 0;            ///< our tick minus the server's estimated tick
  double input_lead_ticks = 0.0;      ///< smoothed arrival margin reported by the server
  uint64_t final_ticks_verified = 0;  ///< final ticks whose checksum matched
  /// Final ticks passed over by resyncs instead: a client that fell behind
  /// (or desynced) loads the server's snapshot, checked against the
  /// server's checksum, and does not simulate the ticks before it.
  uint64_t final_ticks_resynced = 0;
  uint64_t desyncs = 0;
  uint64_t resyncs = 0;
  uint64_t resyncs_refused = 0;  ///< snapshots that did not load (kResyncRefused)
  uint64_t packets_sent = 0;
  uint64_t packets_received = 0;
  uint64_t packets_rejected = 0;  ///< undecodable or not from our server
  /// Datagrams not queued because the caller had not drained
  /// ClientProtocol::kMaxQueuedDatagrams of them (never on ClientSession).
  uint64_t datagrams_dropped = 0;
  Tick last_final_tick = kNoTick;
};

}  // namespace rwd::client
