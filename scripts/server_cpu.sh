#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Server CPU per tick of live secure matches on loopback: rewind-server
# hosting MATCHES matches of PLAYERS players, one rewind-bots process per
# match, the server's CPU time (every thread, from /proc/PID/task/*/schedstat,
# nanoseconds) read over a window in the middle of the matches.
#
# Then, in the same run, the socket-less host work of the same match: the
# host benchmark's secure headless match of PLAYERS players (simulation,
# finalization, intake, broadcast, encoding, sealing; no sockets, no timers),
# median per tick, and the ratio of the two; and that host work ticked at
# the tick rate of wall time with the thread asleep in between, as a live
# server's is (BM_HostTickPaced, 10 s): the part of the gap that is the
# machine waking an idle thread, not the socket path.
#
# Usage: scripts/server_cpu.sh [--players N] [--matches M] [--seconds S] [--bin DIR]
#                              [--bench-bin DIR]
#   --players N      players per match (default 8)
#   --matches M      matches in the one server process (default 1)
#   --seconds S      the measured window (default 15; the matches run S + 10 s)
#   --bin DIR        the programs (default build/release/bin)
#   --bench-bin DIR  rewind_host_bench (default build/bench/bin; the bench
#                    preset); without it the second figure is skipped
# Prints: matches, players, ticks in the window, server CPU ms, CPU µs per
# match and tick, context switches per second, the bytes per player per
# second the server sent; the ticks that started late or were dropped (the
# summary's ticks_late, ticks_missed); then the host work per tick and
# live / host, and the paced host work and live / paced. Exit 1 when a
# match or a bot failed.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

players=8
matches=1
seconds=15
bin=build/release/bin
bench_bin=build/bench/bin
usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
while (($#)); do
  case "$1" in
    --players) players=${2:?}; shift 2 ;;
    --matches) matches=${2:?}; shift 2 ;;
    --seconds) seconds=${2:?}; shift 2 ;;
    --bin) bin=${2:?}; shift 2 ;;
    --bench-bin) bench_bin=${2:?}; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "server_cpu: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
done
bin=$(cd "$bin" && pwd)
host_bench=""
[ -x "$bench_bin/rewind_host_bench" ] && host_bench=$(cd "$bench_bin" && pwd)/rewind_host_bench
tick_rate=60
ticks=$(( (seconds + 10) * tick_rate ))
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
cd "$work"

"$bin/rewind-token" keygen --out server.key >/dev/null
ids=()
for m in $(seq 1 "$matches"); do
  id=match; [ "$matches" = 1 ] || id=match-$m
  ids+=("$id")
  for slot in $(seq 0 $((players - 1))); do
    "$bin/rewind-token" mint --key-file server.key --match "$id" --slot "$slot" \
      --client-id $((slot + 1)) >>"tokens-$m"
  done
done
"$bin/rewind-server" --bind 127.0.0.1 --port 0 --port-file port --matches "$matches" \
  --players "$players" --ticks "$ticks" --tick-rate "$tick_rate" --key-file server.key \
  --match-id match --threads 1 --summary-json >server.json 2>server.log &
server=$!
for _ in $(seq 1 100); do [ -f port ] && [ "$(wc -l <port)" = "$matches" ] && break; sleep 0.1; done
bots=()
for m in $(seq 1 "$matches"); do
  "$bin/rewind-bots" --bots "$players" --connect "127.0.0.1:$(sed -n "${m}p" port)" \
    --token-file "tokens-$m" --summary-json >"bots-$m.json" 2>"bots-$m.log" &
  bots+=($!)
done

cpu_ns() { cat /proc/"$server"/task/*/schedstat 2>/dev/null | awk '{ s += $1 } END { print s + 0 }'; }
switches() {
  cat /proc/"$server"/task/*/status 2>/dev/null |
    awk '/^(non)?voluntary_ctxt_switches/ { s += $2 } END { print s + 0 }'
}
sleep 4  # joined and ticking
cpu0=$(cpu_ns); cs0=$(switches); t0=$(date +%s.%N)
sleep "$seconds"
cpu1=$(cpu_ns); cs1=$(switches); t1=$(date +%s.%N)

status=0
for b in "${bots[@]}"; do wait "$b" || status=1; done
wait "$server" || status=1
# The socket-less host work of the same match, after the live one so the
# two never share the CPU.
host_us=""
if [ -n "$host_bench" ]; then
  "$host_bench" --benchmark_filter="BM_HostTick/players:$players/secure:1/" \
    --benchmark_format=json >host.json 2>/dev/null || true
  "$host_bench" --benchmark_filter="BM_HostTickPaced/players:$players/" \
    --benchmark_format=json >paced.json 2>/dev/null || true
fi
python3 - "$cpu0" "$cpu1" "$cs0" "$cs1" "$t0" "$t1" "$matches" "$players" "$tick_rate" \
  "$host_bench" <<'PY'
import json, os, sys
cpu0, cpu1, cs0, cs1 = (int(x) for x in sys.argv[1:5])
t0, t1 = float(sys.argv[5]), float(sys.argv[6])
matches, players, rate = (int(x) for x in sys.argv[7:10])
host_bench = sys.argv[10]
window = t1 - t0
ticks = window * rate
summaries = [json.loads(l) for l in open("server.json") if l.strip()]
sent = sum(s["bytes_out"] for s in summaries)
duration = max(s["duration_s"] for s in summaries)
live_us = (cpu1 - cpu0) / 1e3 / ticks / matches
print(f"matches {matches}, players {players}: {ticks:.0f} ticks in {window:.1f} s; "
      f"server CPU {(cpu1 - cpu0) / 1e6:.1f} ms = {live_us:.0f} us per match and tick; "
      f"{(cs1 - cs0) / window:.0f} context switches/s; "
      f"{sent / duration / (players * matches):.0f} B/s sent per player")
late = sum(s.get("ticks_late", 0) for s in summaries)
missed = sum(s.get("ticks_missed", 0) for s in summaries)
worst = max(s.get("tick_lateness_max_s", 0.0) for s in summaries)
print(f"tick pace: {late} ticks started a period or more late, {missed} dropped "
      f"(latest start {worst * 1e3:.1f} ms after its time)")
def median_of(path):
    if not (host_bench and os.path.exists(path)):
        return None
    try:
        runs = json.load(open(path))["benchmarks"]
        return runs[0]["host_us_median"] if runs else None
    except (ValueError, KeyError, IndexError):
        return None
host = median_of("host.json")
paced = median_of("paced.json")
if host:
    print(f"socket-less host work (rewind_host_bench, secure {players}-player match): "
          f"{host:.0f} us per tick (median); live / host = {live_us / host:.1f}")
if host and paced:
    print(f"the same host work ticked at {rate} Hz of wall time, asleep in between "
          f"(BM_HostTickPaced): {paced:.0f} us per tick (median) = {paced / host:.1f}x back to back; "
          f"live / paced = {live_us / paced:.1f}")
elif host_bench:
    print(f"socket-less host work: rewind_host_bench has no secure {players}-player figure "
          "(it runs 2, 4, 8, 16 and 32 players)")
else:
    print("socket-less host work: no rewind_host_bench (build the bench preset, or --bench-bin)")
PY
for m in $(seq 1 "$matches"); do
  grep -q '"desyncs":0' "bots-$m.json" || { echo "server_cpu: match $m: $(cat "bots-$m.json")" >&2; status=1; }
done
exit "$status"
