// SPDX-License-Identifier: MIT
#pragma once
// One match hosted as an Agones GameServer (rewind-server --agones):
//   1. GET /gameserver until the SDK sidecar answers (it may start after
//      the server), within sidecar_timeout_s;
//   2. health pings start on their own thread and run until the end,
//      withheld while the match's ticks slip persistently (LoadMonitor),
//      so that Agones marks the GameServer Unhealthy;
//   3. POST /ready, then GET /gameserver every poll_period_s until the
//      state is "Allocated", within allocation_timeout_s;
//   4. the allocation's `rewind.dev/...` annotations and labels override the
//      flags' match settings (agones_match_settings.h);
//   5. the match is hosted;
//   6. POST /shutdown, once, whether the match ended, was refused, timed out
//      or was stopped by SIGINT/SIGTERM.
// Every step is logged with an "agones: " prefix.
#include <functional>

#include "rewind/server/agones_sdk.h"
#include "rewind/server/server.h"

namespace rwd::server {

struct AgonesLifecycleOptions {
  double sidecar_timeout_s = 30;       ///< for the sidecar's first answer, > 0
  double allocation_timeout_s = 3600;  ///< from Ready to Allocated, > 0
  double health_period_s = 2;          ///< between health pings, > 0
  double poll_period_s = 1;            ///< between GET /gameserver while Ready, > 0
};

/// Binds the socket, hosts the match with `config` and returns the process
/// exit status (rewind-server's main: 0 played, 1 could not start, ...).
using HostMatchFn = std::function<int(const ServerConfig& config)>;

/// Runs the steps above. Returns `host_match`'s status when a match was
/// hosted; 0 when stopped by a signal before an allocation; 1 when the
/// sidecar never answered, Ready failed, no allocation came in time, the
/// GameServer left the Ready state some other way, or the allocation's
/// settings were refused (then no match is hosted).
int run_agones_match(const ServerConfig& base, const AgonesSdk& sdk,
                     const AgonesLifecycleOptions& options, const HostMatchFn& host_match);

}  // namespace rwd::server
