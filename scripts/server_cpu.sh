#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Server CPU per tick of live secure matches on loopback: rewind-server
# hosting MATCHES matches of PLAYERS players, one rewind-bots process per
# match, the server's CPU time (every thread, from /proc/PID/task/*/schedstat,
# nanoseconds) read over a window in the middle of the matches.
#
# Usage: scripts/server_cpu.sh [--players N] [--matches M] [--seconds S] [--bin DIR]
#   --players N   players per match (default 8)
#   --matches M   matches in the one server process (default 1)
#   --seconds S   the measured window (default 15; the matches run S + 10 s)
#   --bin DIR     the programs (default build/release/bin)
# Prints one line: matches, players, ticks in the window, server CPU ms,
# CPU µs per match and tick, context switches per second, and the bytes per
# player per second the server sent. Exit 1 when a match or a bot failed.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

players=8
matches=1
seconds=15
bin=build/release/bin
usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
while (($#)); do
  case "$1" in
    --players) players=${2:?}; shift 2 ;;
    --matches) matches=${2:?}; shift 2 ;;
    --seconds) seconds=${2:?}; shift 2 ;;
    --bin) bin=${2:?}; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "server_cpu: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
done
bin=$(cd "$bin" && pwd)
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
python3 - "$cpu0" "$cpu1" "$cs0" "$cs1" "$t0" "$t1" "$matches" "$players" "$tick_rate" <<'PY'
import json, sys
cpu0, cpu1, cs0, cs1 = (int(x) for x in sys.argv[1:5])
t0, t1 = float(sys.argv[5]), float(sys.argv[6])
matches, players, rate = (int(x) for x in sys.argv[7:10])
window = t1 - t0
ticks = window * rate
summaries = [json.loads(l) for l in open("server.json") if l.strip()]
sent = sum(s["bytes_out"] for s in summaries)
duration = max(s["duration_s"] for s in summaries)
print(f"matches {matches}, players {players}: {ticks:.0f} ticks in {window:.1f} s; "
      f"server CPU {(cpu1 - cpu0) / 1e6:.1f} ms = {(cpu1 - cpu0) / 1e3 / ticks / matches:.0f} us "
      f"per match and tick; {(cs1 - cs0) / window:.0f} context switches/s; "
      f"{sent / duration / (players * matches):.0f} B/s sent per player")
PY
for m in $(seq 1 "$matches"); do
  grep -q '"desyncs":0' "bots-$m.json" || { echo "server_cpu: match $m: $(cat "bots-$m.json")" >&2; status=1; }
done
exit "$status"
