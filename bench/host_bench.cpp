// SPDX-License-Identifier: MIT
// The match host's cost per tick and what it sends each player, for 2 to 32
// players: a whole match on a simulated clock (tests/support/headless_match.h)
// with scripted protocol peers, which speak the real codec and connection
// layer but simulate nothing, so the host's work is all that is timed
// (on_tick and on_datagram: simulation, finalization, input intake, the
// broadcast, encoding). Wall time per tick is the manual iteration time.
//
// Counters: host_us_per_tick; bytes_per_player_s (the envelopes sent to one
// client per second) and wire_bytes_per_player_s (with the 28 bytes of
// IPv4 and UDP headers each datagram costs); datagrams_per_player_s.
#include <benchmark/benchmark.h>

#include <cstdio>

#include "headless_match.h"

namespace {

using rwd::Tick;

rwd::game::PlayerInput circling(uint32_t player, Tick tick) {
  // A direction that changes every 15 ticks, different per player: the
  // inputs change as often as a real player's stick does.
  static constexpr int16_t kAxis[8] = {1000, 707, 0, -707, -1000, -707, 0, 707};
  const uint32_t phase = (static_cast<uint32_t>(tick) / 15 + player) % 8;
  return {kAxis[phase], kAxis[(phase + 2) % 8], 0};
}

void BM_HostTick(benchmark::State& state) {
  const auto players = static_cast<uint32_t>(state.range(0));
  double busy = 0.0, ticks = 0.0, bytes = 0.0, datagrams = 0.0, seconds = 0.0;
  for (auto _ : state) {
    rwd::test::HeadlessConfig config;
    config.match.players = players;
    config.match.max_ticks = 600;
    config.match.keyframe_interval = 0;
    config.sdk_clients = 0;
    config.latency_ms = 20.0;
    config.jitter_ms = 5.0;
    config.inputs = circling;
    auto match = rwd::test::HeadlessMatch::create(config);
    if (!match.ok()) {
      state.SkipWithError(match.status().message().c_str());
      return;
    }
    const rwd::test::HeadlessResult r = (*match)->run();
    if (r.timed_out || r.server.ticks_final != 600) {
      state.SkipWithError("the match did not finish");
      return;
    }
    state.SetIterationTime(r.host_busy_seconds / static_cast<double>(r.host_ticks));
    busy += r.host_busy_seconds;
    ticks += static_cast<double>(r.host_ticks);
    bytes += static_cast<double>(r.server.bytes_out);
    datagrams += static_cast<double>(r.datagrams_to_clients);
    seconds += r.simulated_seconds;
  }
  const double per_player_s = static_cast<double>(players) * seconds;
  state.counters["host_us_per_tick"] = busy / ticks * 1e6;
  state.counters["bytes_per_player_s"] = bytes / per_player_s;
  state.counters["wire_bytes_per_player_s"] = (bytes + 28.0 * datagrams) / per_player_s;
  state.counters["datagrams_per_player_s"] = datagrams / per_player_s;
}

BENCHMARK(BM_HostTick)
    ->ArgName("players")
    ->Arg(2)
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Arg(32)
    ->UseManualTime()
    ->Iterations(3)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
