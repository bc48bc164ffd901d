// SPDX-License-Identifier: MIT
#pragma once
// The GameServer record as the Agones SDK sidecar answers GET /gameserver:
// the parts rewind-server reads (state, address, ports, and the labels and
// annotations that carry an allocation's match settings) and a strict
// reader for its JSON, on nlohmann-json. nlohmann-json stays out of this
// header: only server/src/agones_game_server.cpp includes it.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/status.h"

namespace rwd::server {

/// What the server reads of its GameServer record (GET /gameserver).
struct AgonesGameServer {
  std::string name;     ///< object_meta.name
  std::string state;    ///< status.state: "Scheduled", "RequestReady", "Ready", "Allocated", ...
  std::string address;  ///< status.address: where players connect (empty before scheduling)
  struct Port {
    std::string name;  ///< e.g. "default"
    int64_t port = 0;  ///< the public (host) port players connect to, [0, 65535]

    friend bool operator==(const Port&, const Port&) = default;
  };
  std::vector<Port> ports;                         ///< status.ports
  std::map<std::string, std::string> labels;       ///< object_meta.labels
  std::map<std::string, std::string> annotations;  ///< object_meta.annotations

  friend bool operator==(const AgonesGameServer&, const AgonesGameServer&) = default;
};

/// Larger GameServer documents are refused before parsing.
inline constexpr size_t kAgonesGameServerMaxBytes = 1 << 20;
/// Arrays and objects nested deeper than this are refused (the document
/// itself is depth 1), so a hostile one costs a bounded stack and heap.
inline constexpr int kAgonesGameServerMaxDepth = 32;

/// Reads a GameServer from the JSON GET /gameserver answers. The whole
/// document must be RFC 8259 JSON, however much of it the server uses: no
/// comments, trailing commas, leading zeros, invalid UTF-8, lone surrogates,
/// numbers beyond a double's range, data after the value, or duplicate keys
/// in any object (two readers could otherwise disagree on a setting). Its
/// size and depth are bounded as above. Fields the server does not use are
/// skipped; the ones it uses must have their documented types (absent or
/// null reads as empty). Errors are kCorrupt, naming the problem in
/// printable ASCII (the message may reach a log line).
Result<AgonesGameServer> parse_agones_game_server(std::string_view json);

}  // namespace rwd::server
