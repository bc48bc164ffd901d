// SPDX-License-Identifier: MIT
#include "rewind/server/agones_lifecycle.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>

#include "rewind/server/agones_health_pinger.h"
#include "rewind/server/agones_match_settings.h"
#include "rewind/server/server_log.h"

namespace rwd::server {
namespace {

using Clock = std::chrono::steady_clock;

// Set by SIGINT/SIGTERM while no Server is running (the Server's own signal
// set takes over while a match is hosted).
volatile std::sig_atomic_t g_signal = 0;

extern "C" void note_signal(int signal) {
  g_signal = signal;
}

void catch_stop_signals() {
  struct sigaction action {};
  action.sa_handler = note_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// Sleeps until `until`, in short steps so a signal is noticed at once.
// False when a signal arrived.
bool sleep_until(Clock::time_point until) {
  while (g_signal == 0) {
    const auto now = Clock::now();
    if (now >= until) return true;
    std::this_thread::sleep_for(
        std::min<Clock::duration>(until - now, std::chrono::milliseconds(50)));
  }
  return false;
}

// "30 s", "0.5 s": a duration as the flags take it.
std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", s);
  return text;
}

std::string signal_name() {
  return g_signal == SIGINT ? "SIGINT" : "SIGTERM";
}

std::string where(const AgonesSdk& sdk) {
  return sdk.options().host + ":" + std::to_string(sdk.options().port);
}

std::string describe_ports(const AgonesGameServer& gs) {
  std::string out;
  for (const AgonesGameServer::Port& port : gs.ports) {
    out += (out.empty() ? "" : ", ") + gs.address + ":" + std::to_string(port.port) +
           (port.name.empty() ? "" : " (" + port.name + ")");
  }
  return out.empty() ? "no ports listed" : out;
}

// Exactly one Shutdown per process, logged either way.
void send_shutdown(const AgonesSdk& sdk, const std::string& why) {
  const Status status = sdk.shutdown();
  if (status.ok()) {
    write_log(LogLevel::kInfo, "agones: Shutdown sent (" + why + ")");
  } else {
    write_log(LogLevel::kError, "agones: Shutdown failed (" + why + "): " + status.message());
  }
}

// Step 1: the sidecar may start after the server, so its first answer is
// retried until the deadline.
Result<AgonesGameServer> wait_for_sidecar(const AgonesSdk& sdk, double timeout_s) {
  const auto deadline = Clock::now() + seconds(timeout_s);
  Status last;
  while (true) {
    auto gs = sdk.game_server();
    if (gs.ok()) return gs;
    last = gs.status();
    if (Clock::now() >= deadline) break;
    if (!sleep_until(std::min(deadline, Clock::now() + std::chrono::milliseconds(500)))) {
      return Status::Error(ErrorCode::kIo, "stopped by " + signal_name());
    }
  }
  return Status::Error(ErrorCode::kIo, "the SDK sidecar at " + where(sdk) +
                                           " did not answer within " + seconds_text(timeout_s) +
                                           ": " + last.message());
}

// Step 3: polls until Allocated. An error that is not a signal means the
// server gives up (timeout, a state it cannot leave, a sidecar gone silent).
Result<AgonesGameServer> wait_for_allocation(const AgonesSdk& sdk,
                                             const AgonesLifecycleOptions& options) {
  const auto start = Clock::now();
  const auto deadline = start + seconds(options.allocation_timeout_s);
  auto last_answer = start;
  std::string last_state = "Ready";
  while (true) {
    if (!sleep_until(std::min(deadline, Clock::now() + seconds(options.poll_period_s)))) {
      return Status::Error(ErrorCode::kNotFound, "stopped by " + signal_name());
    }
    auto gs = sdk.game_server();
    const auto now = Clock::now();
    if (gs.ok()) {
      last_answer = now;
      if (gs->state == "Allocated") return gs;
      if (gs->state != last_state) {
        write_log(LogLevel::kInfo, "agones: GameServer state " + gs->state);
        last_state = gs->state;
      }
      if (gs->state == "Shutdown" || gs->state == "Unhealthy" || gs->state == "Error") {
        return Status::Error(ErrorCode::kInvalidArgument,
                             "the GameServer became " + gs->state + " before an allocation");
      }
    } else {
      write_log(LogLevel::kWarning, "agones: GET /gameserver failed: " + gs.status().message());
      if (now - last_answer > seconds(options.sidecar_timeout_s)) {
        return Status::Error(ErrorCode::kIo,
                             "the SDK sidecar stopped answering: " + gs.status().message());
      }
    }
    if (now >= deadline) {
      return Status::Error(ErrorCode::kInvalidArgument,
                           "no allocation within " + seconds_text(options.allocation_timeout_s) +
                               " (--agones-allocation-timeout)");
    }
  }
}

}  // namespace

int run_agones_match(const ServerConfig& base, const AgonesSdk& sdk,
                     const AgonesLifecycleOptions& options, const HostMatchFn& host_match) {
  catch_stop_signals();
  write_log(LogLevel::kInfo, "agones: contacting the SDK sidecar at " + where(sdk));
  auto first = wait_for_sidecar(sdk, options.sidecar_timeout_s);
  if (!first.ok()) {
    // Nothing to shut down: there is no sidecar to tell.
    write_log(g_signal != 0 ? LogLevel::kInfo : LogLevel::kError,
              "agones: " + first.status().message());
    return g_signal != 0 ? 0 : 1;
  }
  write_log(LogLevel::kInfo, "agones: GameServer '" + first->name + "' is " +
                                 (first->state.empty() ? "in no state yet" : first->state));

  // From here to the exit: pings on their own thread, never the tick loop's,
  // withheld while the match's ticks slip persistently (the load monitor
  // outlives the Server that feeds it: the pinger reads it to the end).
  const std::shared_ptr<LoadMonitor> load =
      base.load ? base.load : std::make_shared<LoadMonitor>(base.tick_budget, Clock::now());
  AgonesHealthPinger pinger(
      sdk, std::chrono::duration_cast<std::chrono::milliseconds>(seconds(options.health_period_s)),
      [load] { return load->unhealthy_reason(Clock::now()); });
  auto finish = [&](int exit_status, const std::string& why) {
    // The pings end before Shutdown is sent: stopped after it, a ping
    // already on its way (or one whose period came up between the two)
    // reached the sidecar after Shutdown, a health report for a
    // GameServer that is going away.
    pinger.stop();
    send_shutdown(sdk, why);
    write_log(LogLevel::kInfo, "agones: " + std::to_string(pinger.sent()) + " health pings, " +
                                   std::to_string(pinger.failed()) + " failed, " +
                                   std::to_string(pinger.withheld()) + " withheld");
    return exit_status;
  };

  // Ready comes before the match settings are known: Agones allocates only
  // Ready GameServers, and the settings (the player count above all) arrive
  // with the allocation. So the UDP socket is bound after the allocation,
  // when the Server can be created with them; the port is fixed by the
  // Fleet manifest, so players may be told it before it is bound: clients
  // resend their join until the server answers.
  if (Status ready = sdk.ready(); !ready.ok()) {
    write_log(LogLevel::kError, "agones: Ready failed: " + ready.message());
    return finish(1, "Ready failed");
  }
  write_log(LogLevel::kInfo, "agones: Ready sent; waiting up to " +
                                 seconds_text(options.allocation_timeout_s) + " for an allocation");
  auto allocated = wait_for_allocation(sdk, options);
  if (!allocated.ok()) {
    if (g_signal != 0) {
      write_log(LogLevel::kInfo,
                "agones: " + allocated.status().message() + " before an allocation");
      return finish(0, "stopped by " + signal_name());
    }
    write_log(LogLevel::kError, "agones: " + allocated.status().message());
    return finish(1, "no match");
  }

  ServerConfig config = base;
  config.load = load;
  auto applied = apply_agones_match_settings(*allocated, &config.match);
  if (!applied.ok()) {
    write_log(LogLevel::kError,
              "agones: allocation refused, no match hosted: " + applied.status().message());
    return finish(1, "allocation refused");
  }
  write_log(LogLevel::kInfo, "agones: allocated as '" + allocated->name + "', players connect to " +
                                 describe_ports(*allocated) +
                                 "; match settings from the allocation: " +
                                 (applied->empty() ? "none (the flags' settings)" : *applied));
  if (g_signal != 0) return finish(0, "stopped by " + signal_name());

  const int exit_status = host_match(config);
  // The Server's signal set is gone: a signal from here on must not kill
  // the process before Shutdown is sent.
  catch_stop_signals();
  return finish(exit_status, "the match is over");
}

}  // namespace rwd::server
