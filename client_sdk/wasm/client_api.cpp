// SPDX-License-Identifier: MIT
// The browser client's entry points: a C interface over ClientProtocol (the
// SDK without sockets or clocks) that client_sdk/web/rewind-client.js calls
// through Emscripten. JavaScript owns the WebSocket and the clock: it hands
// in what the server sent and the time, and takes out what to send.
//
// Clients are numbered handles (several per page are fine). Strings
// returned stay valid until the next call that returns one; the datagram
// and draw buffers until the next call on the same client. Every call on a
// handle that is not open answers 0, -1 or an empty string.
#include <cinttypes>
#include <cstdio>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "rewind/cli/json_text.h"
#include "rewind/client/browser_games.h"
#include "rewind/client/client_protocol.h"
#include "rewind/core/debug_draw.h"
#include "rewind/core/input_spec.h"
#include "rewind/game/simulation.h"

#if defined(__EMSCRIPTEN__)
#include <emscripten/emscripten.h>
#define RC_EXPORT extern "C" EMSCRIPTEN_KEEPALIVE
#else
#define RC_EXPORT extern "C"
#endif

namespace {

using rwd::client::ClientEvent;
using rwd::client::ClientEventType;
using rwd::client::ClientPhase;
using rwd::client::ClientProtocol;

struct Client {
  explicit Client(ClientProtocol p) : protocol(std::move(p)) {}
  ClientProtocol protocol;
  ClientEvent event;  ///< the last one polled
  rwd::DebugDrawBuffers draw;
};

// A throwaway match of one game that rc_warm_up() steps in slices.
struct WarmUp {
  std::unique_ptr<rwd::game::Simulation> sim;
  rwd::game::SimSnapshot snapshot;
  std::vector<rwd::PlayerInput> inputs;
  std::vector<uint8_t> bytes;
  uint64_t draws = 0;
};

struct Clients {
  std::map<int, std::unique_ptr<Client>> open;
  std::map<std::string, WarmUp> warm_ups;  ///< by game
  int next = 1;
  std::string error;
  std::string text;
  rwd::Status games;  ///< what register_browser_games() answered
};

Clients& clients() {
  static Clients c = [] {
    Clients made;
    made.games = rwd::client::register_browser_games();
    return made;
  }();
  return c;
}

/// Whether this module plays `game`; otherwise rc_error says why.
bool plays(const std::string& game) {
  Clients& all = clients();
  if (!all.games.ok()) {
    all.error = "the module's games did not register: " + all.games.message();
    return false;
  }
  if (!rwd::game::make_builtin_game(game)) {
    all.error = "no game named '" + game + "' in this module";
    return false;
  }
  return true;
}

Client* find(int handle) {
  auto& open = clients().open;
  const auto it = open.find(handle);
  return it == open.end() ? nullptr : it->second.get();
}

const char* hand_out(std::string text) {
  clients().text = std::move(text);
  return clients().text.c_str();
}

// The browser's clock is a double of milliseconds (performance.now()).
rwd::net::TimePoint time_of(double now_ms) {
  return rwd::net::TimePoint(std::chrono::duration_cast<rwd::net::TimePoint::duration>(
      std::chrono::duration<double, std::milli>(now_ms < 0 ? 0 : now_ms)));
}

std::string hex64(uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "\"%016" PRIx64 "\"", v);
  return buf;
}

const char* event_name(ClientEventType type) {
  switch (type) {
    case ClientEventType::kJoined:
      return "joined";
    case ClientEventType::kMatchStarted:
      return "matchStarted";
    case ClientEventType::kFinalTick:
      return "finalTick";
    case ClientEventType::kDesync:
      return "desync";
    case ClientEventType::kResynced:
      return "resynced";
    case ClientEventType::kMatchEnded:
      return "matchEnded";
    case ClientEventType::kRejected:
      return "rejected";
    case ClientEventType::kDisconnected:
      return "disconnected";
    case ClientEventType::kResyncRefused:
      return "resyncRefused";
  }
  return "unknown";
}

const char* phase_name(ClientPhase phase) {
  switch (phase) {
    case ClientPhase::kIdle:
      return "idle";
    case ClientPhase::kJoining:
      return "joining";
    case ClientPhase::kLobby:
      return "lobby";
    case ClientPhase::kRunning:
      return "running";
    case ClientPhase::kEnding:
      return "ending";
    case ClientPhase::kEnded:
      return "ended";
  }
  return "unknown";
}

const char* type_name(rwd::InputFieldType type) {
  switch (type) {
    case rwd::InputFieldType::kI8:
      return "i8";
    case rwd::InputFieldType::kU8:
      return "u8";
    case rwd::InputFieldType::kI16:
      return "i16";
    case rwd::InputFieldType::kU16:
      return "u16";
    case rwd::InputFieldType::kI32:
      return "i32";
    case rwd::InputFieldType::kU32:
      return "u32";
  }
  return "u8";
}

}  // namespace

/// The last error, for a call that answered -1 or 0 where it failed.
RC_EXPORT const char* rc_error() {
  return clients().error.c_str();
}

/// The input a game of this module takes (a built-in one, or one its
/// register_browser_games() added), as JSON: {"name", "size", "fields":
/// [{"name", "type", "offset", "min", "max"}]}; "" for an unknown game.
RC_EXPORT const char* rc_input_spec(const char* game) {
  if (!plays(game)) return hand_out("");
  const std::unique_ptr<rwd::game::Game> made = rwd::game::make_builtin_game(game);
  const rwd::InputSpec& spec = made->input_spec();
  std::string json = "{\"name\":" + rwd::cli::json_string(spec.name) +
                     ",\"size\":" + std::to_string(spec.size) + ",\"fields\":[";
  for (size_t i = 0; i < spec.fields.size(); ++i) {
    const rwd::InputField& f = spec.fields[i];
    json += (i ? "," : "") + std::string("{\"name\":") + rwd::cli::json_string(f.name) +
            ",\"type\":\"" + type_name(f.type) + "\",\"offset\":" + std::to_string(f.offset) +
            ",\"min\":" + std::to_string(f.min) + ",\"max\":" + std::to_string(f.max) + "}";
  }
  return hand_out(json + "]}");
}

/// Opens a client of `game` (the server's). `token` is the connect token
/// from the game's backend (`token_size` bytes; 0 bytes: a tokenless local
/// server). `nonce_low`/`nonce_high`: a random join nonce (crypto). The
/// handle, or -1 (rc_error says why).
RC_EXPORT int rc_create(const char* game, const char* name, const uint8_t* token,
                        uint32_t token_size, int spectator, int snapshot_ticks, uint32_t nonce_low,
                        uint32_t nonce_high) {
  rwd::client::ClientConfig config;
  config.game = game;
  config.name = name;
  config.connect_token.assign(token, token + token_size);
  config.spectator = spectator != 0;
  if (snapshot_ticks > 0) config.snapshot_ticks = snapshot_ticks;
  if (!plays(config.game)) return -1;
  auto protocol =
      ClientProtocol::create(config, (static_cast<uint64_t>(nonce_high) << 32) | nonce_low);
  if (!protocol.ok()) {
    clients().error = protocol.status().message();
    return -1;
  }
  Clients& all = clients();
  const int handle = all.next++;
  all.open.emplace(handle, std::make_unique<Client>(std::move(*protocol)));
  return handle;
}

/// Steps a throwaway match of `game` (`players` slots, random inputs within
/// its input spec) `ticks` ticks further, the way a client does: a snapshot
/// restored and 8 ticks re-simulated every 8, the state serialized and
/// checksummed. Browsers run WebAssembly first as quickly compiled baseline
/// code and optimize what runs hot later; a match's first seconds on
/// baseline code re-simulate several times slower and stall the page. Called
/// in slices before joining, it leaves the step's code optimized. Returns the
/// ticks stepped so far in this game's warm-up, or -1 (rc_error says why).
RC_EXPORT int rc_warm_up(const char* game, int players, int ticks) {
  if (!plays(game)) return -1;
  if (players < 1 || players > static_cast<int>(rwd::game::kMaxPlayers) || ticks < 0) {
    clients().error =
        "warm up: players in [1, " + std::to_string(rwd::game::kMaxPlayers) + "] and ticks >= 0";
    return -1;
  }
  WarmUp& warm = clients().warm_ups[game];
  if (!warm.sim) {
    auto sim =
        rwd::game::Simulation::create(game, {static_cast<uint32_t>(players), /*seed=*/0x5eed});
    if (!sim.ok()) {
      clients().error = sim.status().message();
      return -1;
    }
    warm.sim = std::move(*sim);
    warm.inputs.resize(static_cast<size_t>(players));
    warm.sim->save(warm.snapshot);
  }
  rwd::game::Simulation& sim = *warm.sim;
  const rwd::InputSpec& spec = sim.game().input_spec();
  for (int t = 0; t < ticks; ++t) {
    if (sim.tick() % 8 == 0 && sim.tick() > 0) {
      // Back to the last snapshot and forward again, as a rollback does.
      const rwd::Tick target = sim.tick();
      sim.restore(warm.snapshot);
      while (sim.tick() < target) {
        if (!sim.step(warm.inputs).ok()) break;
      }
      sim.save(warm.snapshot);
      sim.serialize(warm.bytes);
      (void)sim.checksum();
    }
    for (rwd::PlayerInput& input : warm.inputs) {
      input = rwd::random_input(spec, ++warm.draws * 0x9e3779b97f4a7c15ull);
    }
    if (!sim.step(warm.inputs).ok()) {
      // The rules refused the state: start over from a fresh match.
      warm.sim.reset();
      break;
    }
  }
  return warm.sim ? static_cast<int>(warm.sim->tick()) : 0;
}

/// Closes the client (a Disconnect is queued first when it is connected:
/// send what rc_next_datagram still hands out before the socket closes).
RC_EXPORT void rc_disconnect(int handle, const char* reason, double now_ms) {
  if (Client* c = find(handle)) c->protocol.disconnect(reason, time_of(now_ms));
}

RC_EXPORT void rc_destroy(int handle) {
  clients().open.erase(handle);
}

RC_EXPORT void rc_connect(int handle, double now_ms) {
  if (Client* c = find(handle)) c->protocol.connect(time_of(now_ms));
}

/// One message from the server (`size` bytes at `bytes`), received at now.
RC_EXPORT void rc_receive(int handle, const uint8_t* bytes, uint32_t size, double now_ms) {
  if (Client* c = find(handle)) c->protocol.receive({bytes, size}, time_of(now_ms));
}

/// Steps the ticks due by now; how many (0 for an unknown handle).
RC_EXPORT int rc_update(int handle, double now_ms) {
  Client* c = find(handle);
  return c ? c->protocol.update(time_of(now_ms)) : 0;
}

/// The next datagram for the server: its bytes, with their count in
/// *size; null (and *size 0) when none is left.
RC_EXPORT const uint8_t* rc_next_datagram(int handle, uint32_t* size) {
  *size = 0;
  Client* c = find(handle);
  if (!c) return nullptr;
  const auto datagram = c->protocol.next_datagram();
  if (!datagram) return nullptr;
  *size = static_cast<uint32_t>(datagram->size());
  return datagram->data();
}

/// Holds `size` bytes at `bytes` as our input from the next tick on
/// (trailing bytes of the game's input are zero). 0, or -1 when the game's
/// spec refuses it (rc_error says which field).
RC_EXPORT int rc_set_input(int handle, const uint8_t* bytes, uint32_t size) {
  Client* c = find(handle);
  if (!c) return -1;
  if (size > rwd::kInputCapacity) {
    clients().error = "an input is at most " + std::to_string(rwd::kInputCapacity) + " bytes";
    return -1;
  }
  rwd::PlayerInput input;
  std::copy(bytes, bytes + size, input.bytes.begin());
  const rwd::Status status = c->protocol.set_input(input);
  if (!status.ok()) {
    clients().error = status.message();
    return -1;
  }
  return 0;
}

/// The oldest pending event as JSON ({"type", "tick", "player",
/// "localChecksum", "serverChecksum", "reason"}), or "" when none is left.
RC_EXPORT const char* rc_poll_event(int handle) {
  Client* c = find(handle);
  if (!c || !c->protocol.poll_event(c->event)) return hand_out("");
  const ClientEvent& e = c->event;
  return hand_out(
      std::string("{\"type\":\"") + event_name(e.type) + "\",\"tick\":" + std::to_string(e.tick) +
      ",\"player\":" + std::to_string(e.player) + ",\"localChecksum\":" + hex64(e.local_checksum) +
      ",\"serverChecksum\":" + hex64(e.server_checksum) +
      ",\"reason\":" + rwd::cli::json_string(e.reason) + "}");
}

/// Where the client is, as JSON: phase, player, the local tick and its
/// checksum, and the running figures (ClientStats).
RC_EXPORT const char* rc_status(int handle) {
  Client* c = find(handle);
  if (!c) return hand_out("");
  const rwd::client::ClientStats s = c->protocol.stats();
  const rwd::game::Simulation* sim = c->protocol.simulation();
  std::string json = std::string("{\"phase\":\"") + phase_name(c->protocol.phase()) +
                     "\",\"player\":" + std::to_string(c->protocol.player()) +
                     ",\"tick\":" + std::to_string(sim ? sim->tick() : rwd::kNoTick) +
                     ",\"checksum\":" + hex64(sim ? sim->checksum() : 0);
  char figures[640];
  std::snprintf(figures, sizeof figures,
                ",\"rttMs\":%.3f,\"rollbacks\":%" PRIu64 ",\"resimulatedTicks\":%" PRIu64
                ",\"ticksAhead\":%d,\"inputLeadTicks\":%.3f,\"finalTicksVerified\":%" PRIu64
                ",\"finalTicksResynced\":%" PRIu64 ",\"desyncs\":%" PRIu64 ",\"resyncs\":%" PRIu64
                ",\"resyncsRefused\":%" PRIu64 ",\"packetsSent\":%" PRIu64
                ",\"packetsReceived\":%" PRIu64 ",\"packetsRejected\":%" PRIu64
                ",\"datagramsDropped\":%" PRIu64 ",\"lastFinalTick\":%d}",
                s.rtt_ms, s.rollbacks, s.resimulated_ticks, s.ticks_ahead, s.input_lead_ticks,
                s.final_ticks_verified, s.final_ticks_resynced, s.desyncs, s.resyncs,
                s.resyncs_refused, s.packets_sent, s.packets_received, s.packets_rejected,
                s.datagrams_dropped, s.last_final_tick);
  return hand_out(json + figures);
}

/// Draws the predicted present into the client's buffers (the viewer's
/// format: lines and triangles as 16-byte vertices x, y, z float32 and
/// colour 0xRRGGBBAA; points 20 bytes, the same and a size). `flags`: bit 0
/// outlines, bit 1 solid shapes, bit 7 static shapes. Returns the vertex
/// counts through the out parameters and the buffers' addresses.
RC_EXPORT int rc_draw(int handle, uint32_t flags, const void** lines, uint32_t* line_vertices,
                      const void** triangles, uint32_t* triangle_vertices) {
  *lines = *triangles = nullptr;
  *line_vertices = *triangle_vertices = 0;
  Client* c = find(handle);
  if (!c || !c->protocol.simulation()) return -1;
  c->draw.clear();
  rwd::DebugDrawOptions options;
  options.shapes = (flags & 1u) != 0;
  options.solid_shapes = (flags & 2u) != 0;
  options.static_shapes = (flags & 128u) != 0;
  c->protocol.simulation()->lane().debug_draw(options, c->draw);
  *lines = c->draw.lines.data();
  *line_vertices = static_cast<uint32_t>(c->draw.lines.size());
  *triangles = c->draw.triangles.data();
  *triangle_vertices = static_cast<uint32_t>(c->draw.triangles.size());
  return 0;
}
