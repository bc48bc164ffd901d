// SPDX-License-Identifier: MIT
#pragma once
// A client of the Agones SDK sidecar's local REST API (HTTP/1.1 JSON on
// localhost, port AGONES_SDK_HTTP_PORT): the lifecycle calls a game server
// makes (Ready, Health, Shutdown) and reading its GameServer record (state,
// address, ports, labels, annotations). Every call blocks for at most the
// call deadline, so run them off the tick loop. The methods are const and
// share no state: one AgonesSdk may be used from several threads.
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "rewind/core/status.h"
#include "rewind/server/agones_game_server.h"

namespace rwd::server {

/// The sidecar's REST port when AGONES_SDK_HTTP_PORT is not set.
inline constexpr uint16_t kAgonesDefaultHttpPort = 9358;

/// The sidecar's port from the value of AGONES_SDK_HTTP_PORT: null (unset)
/// gives kAgonesDefaultHttpPort; otherwise decimal digits in [1, 65535],
/// anything else kInvalidArgument.
Result<uint16_t> agones_port_from_env(const char* value);

class AgonesSdk {
 public:
  struct Options {
    std::string host = "localhost";  ///< the sidecar shares the pod's network namespace
    uint16_t port = kAgonesDefaultHttpPort;
    std::chrono::milliseconds call_deadline{2000};  ///< per call, connect to answer
  };

  explicit AgonesSdk(Options options) : options_(std::move(options)) {}

  /// POST /ready: the GameServer may now be allocated.
  Status ready() const;
  /// POST /health: one health ping; Agones marks the GameServer Unhealthy
  /// when pings stop for longer than the manifest's health settings allow.
  Status health() const;
  /// POST /shutdown: the match is over; Agones deletes the pod.
  Status shutdown() const;
  /// GET /gameserver.
  Result<AgonesGameServer> game_server() const;

  const Options& options() const { return options_; }

 private:
  /// One call; a status other than 2xx is an error naming it.
  Result<std::string> call(std::string_view method, std::string_view path) const;

  Options options_;
};

}  // namespace rwd::server
