// SPDX-License-Identifier: MIT
// The match host's cost per tick and what it sends each player, for 2 to 32
// players: a whole match on a simulated clock (tests/support/headless_match.h)
// with scripted protocol peers, which speak the real codec and connection
// layer but simulate nothing, so the host's work is all that is timed
// (on_tick and on_datagram: simulation, finalization, input intake, the
// broadcast, encoding; with secure:1 the server's gateway opens and seals
// every datagram, as with connect tokens). Wall time per tick is the manual
// iteration time.
//
// Counters: host_us_per_tick (the mean) and host_us_median (robust to the
// preemptions of a shared machine, which stretch a few ticks' wall time);
// bytes_per_player_s (the envelopes sent to one
// client per second) and wire_bytes_per_player_s (with the 28 bytes of
// IPv4 and UDP headers each datagram costs); datagrams_per_player_s.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "headless_match.h"
#include "live_load.h"

namespace {

using rwd::Tick;

rwd::PlayerInput circling(uint32_t player, Tick tick) {
  // A direction that changes every 15 ticks, different per player: the
  // inputs change as often as a real player's stick does.
  static constexpr int16_t kAxis[8] = {1000, 707, 0, -707, -1000, -707, 0, 707};
  const uint32_t phase = (static_cast<uint32_t>(tick) / 15 + player) % 8;
  return rwd::stick_input(kAxis[phase], kAxis[(phase + 2) % 8]);
}

void BM_HostTick(benchmark::State& state) {
  const auto players = static_cast<uint32_t>(state.range(0));
  const bool secure = state.range(1) != 0;
  double busy = 0.0, ticks = 0.0, bytes = 0.0, datagrams = 0.0, seconds = 0.0;
  std::vector<double> per_tick;
  for (auto _ : state) {
    rwd::test::HeadlessConfig config;
    config.match.players = players;
    config.secure = secure;
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
    per_tick.insert(per_tick.end(), r.host_tick_seconds.begin(), r.host_tick_seconds.end());
    ticks += static_cast<double>(r.host_ticks);
    bytes += static_cast<double>(r.server.bytes_out);
    datagrams += static_cast<double>(r.datagrams_to_clients);
    seconds += r.simulated_seconds;
  }
  const double per_player_s = static_cast<double>(players) * seconds;
  state.counters["host_us_per_tick"] = busy / ticks * 1e6;
  if (!per_tick.empty()) {
    std::nth_element(per_tick.begin(), per_tick.begin() + per_tick.size() / 2, per_tick.end());
    state.counters["host_us_median"] = per_tick[per_tick.size() / 2] * 1e6;
  }
  state.counters["bytes_per_player_s"] = bytes / per_player_s;
  state.counters["wire_bytes_per_player_s"] = (bytes + 28.0 * datagrams) / per_player_s;
  state.counters["datagrams_per_player_s"] = datagrams / per_player_s;
}

// The socket-less host work of one secure match of `players`, median per
// tick (microseconds); `wall_paced` ticks it at 60 Hz of wall time (10 s).
double secure_host_us(uint32_t players, bool wall_paced = false) {
  rwd::test::HeadlessConfig config;
  config.match.players = players;
  config.match.max_ticks = 600;
  config.match.keyframe_interval = 0;
  config.secure = true;
  config.sdk_clients = 0;
  config.inputs = circling;
  config.wall_paced = wall_paced;
  auto match = rwd::test::HeadlessMatch::create(config);
  if (!match.ok()) return 0.0;
  rwd::test::HeadlessResult r = (*match)->run();
  if (r.host_tick_seconds.empty()) return 0.0;
  auto& t = r.host_tick_seconds;
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2] * 1e6;
}

// Live secure 8-player matches on one or two server threads
// (bench/live_load.h): the server threads' CPU per match and tick over a
// 10 s window, whether every match kept its tick rate (sustained: every
// tick due ran, at most 1% late or dropped), and the matches one core would
// hold at that cost.
// Beside it, in the same run, the socket-less host work of the same match
// (a secure headless match, median per tick), and the ratio of the two.
void BM_LiveMatches(benchmark::State& state) {
  const auto matches = static_cast<uint32_t>(state.range(0));
  const auto threads = static_cast<uint32_t>(state.range(1));
  constexpr uint32_t kPlayers = 8;
  for (auto _ : state) {
    rwd::bench::LiveLoadConfig config;
    config.matches = matches;
    config.players = kPlayers;
    config.threads = threads;
    auto load = rwd::bench::LiveLoad::start(config);
    if (!load.ok()) {
      state.SkipWithError(load.status().message().c_str());
      return;
    }
    if (!(*load)->wait_running(std::chrono::seconds(60))) {
      state.SkipWithError("the matches did not all start");
      return;
    }
    (void)(*load)->measure(2.0);  // settle: joins answered, first snapshots gone
    const rwd::bench::LiveLoadReport r = (*load)->measure(10.0);
    (*load).reset();  // the matches end before the host work is timed
    const double live_us = r.server_us_per_match_tick();
    const double host_us = secure_host_us(kPlayers);
    state.SetIterationTime(live_us / 1e6);
    state.counters["live_us_per_tick"] = live_us;
    state.counters["host_us_per_tick"] = host_us;
    state.counters["live_over_host"] = host_us > 0 ? live_us / host_us : 0.0;
    state.counters["server_core_share"] = r.server_core_share();
    state.counters["peers_core_share"] = r.peers_cpu_s / r.seconds;
    state.counters["matches_per_core"] = live_us > 0 ? 1e6 / (live_us * config.tick_rate_hz) : 0.0;
    state.counters["sustained"] = r.sustained() ? 1 : 0;
    state.counters["tick_rate"] =
        static_cast<double>(r.ticks) / (r.seconds * static_cast<double>(matches));
    state.counters["ticks_late"] = static_cast<double>(r.late);
    state.counters["ticks_missed"] = static_cast<double>(r.missed);
    state.counters["lateness_p99_ms"] = r.lateness_p99_s * 1e3;
  }
}

// The same socket-less host work as BM_HostTick's secure match, ticked on
// the wall clock at 60 Hz with the thread asleep in between, as a live
// server's is: what the host work itself costs after an idle wait (cold
// caches, a core woken from idle), without sockets. Beside BM_HostTick's
// back-to-back figure it separates the machine's wake-up cost from the
// socket path's in scripts/server_cpu.sh. One iteration of 600 ticks (10 s)
// per player count.
void BM_HostTickPaced(benchmark::State& state) {
  const auto players = static_cast<uint32_t>(state.range(0));
  for (auto _ : state) {
    const double paced_us = secure_host_us(players, true);
    if (paced_us <= 0.0) {
      state.SkipWithError("the match did not run");
      return;
    }
    state.SetIterationTime(paced_us / 1e6);
    state.counters["host_us_median"] = paced_us;
  }
}

BENCHMARK(BM_LiveMatches)
    ->ArgNames({"matches", "threads"})
    ->Args({1, 1})
    ->Args({25, 1})
    ->Args({50, 1})
    ->Args({100, 1})
    ->Args({25, 2})
    ->Args({50, 2})
    ->Args({100, 2})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_HostTickPaced)
    ->ArgName("players")
    ->Arg(2)
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Arg(32)
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_HostTick)
    ->ArgNames({"players", "secure"})
    ->ArgsProduct({{2, 4, 8, 16, 32}, {0, 1}})
    ->UseManualTime()
    ->Iterations(3)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
