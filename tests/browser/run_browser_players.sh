#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Browser players and native bots in one hosted match: a secure match of 4
# players on rewind-server --websocket; 2 native bots over UDP and 2 pages of
# headless Chromium over WebSocket (the client SDK, built with Emscripten),
# every one with 40 ms of latency (+- 10) and 3% loss each way. Everyone
# finishes with no desync, the replay verifies, and the figures of each
# transport are reported: payload bytes per player each way (the server's
# count), and the server's CPU: all of it per player, and its WebSocket
# thread's per browser (what a browser costs beyond a UDP player).
#
# usage: run_browser_players.sh BIN_DIR CLIENT_DIR SCRIPT_DIR WORK_DIR
#   BIN_DIR     rewind-server, rewind-bots, rewind-token, rewind-replay
#   CLIENT_DIR  the built client SDK (the build's client_web)
#   SCRIPT_DIR  where browser_players.mjs and its node_modules are
set -euo pipefail
test_name=browser_players
bin=$1 client=$2 scripts=$3 work=$4
chromium=${REWIND_CHROMIUM:-/usr/bin/chromium}
[ -x "$chromium" ] || { echo "FAIL [$test_name]: no Chromium at $chromium (Debian package chromium)" >&2; exit 1; }
[ -s "$client/rewind_client.js" ] ||
  { echo "FAIL [$test_name]: no client SDK in $client (see the build's wasm/wasm-deps.log)" >&2; exit 1; }
source "$(dirname "${BASH_SOURCE[0]}")/../integration/script_common.sh"
enter_work_dir "$work"

ticks=720  # 12 s at 60 Hz
players=4
"$bin/rewind-token" keygen --out server.key >/dev/null
for slot in 0 1 2 3; do
  "$bin/rewind-token" mint --key-file server.key --match m --slot "$slot" \
    --client-id $((slot + 1)) >"token$slot"
done
cat token0 token1 >native.tokens
start_server --game crates --bind 127.0.0.1 --port 0 --port-file port --players "$players" \
  --ticks "$ticks" --replay match.rwr --join-timeout 60 --key-file server.key --match-id m \
  --websocket 127.0.0.1:0 --websocket-port-file ws.port --summary-json
for _ in $(seq 1 100); do [ -s ws.port ] && break; sleep 0.1; done
ws_port=$(cat ws.port)

# The server's CPU, sampled until it exits (clock ticks, utime + stime):
# the process's, and its WebSocket thread's (named rewind-ws).
(
  while [ -d "/proc/$server_pid" ]; do
    total=$(awk '{print $14 + $15}' "/proc/$server_pid/stat" 2>/dev/null) || break
    ws=0
    for task in /proc/"$server_pid"/task/*; do
      if [ "$(cat "$task/comm" 2>/dev/null)" = rewind-ws ]; then
        ws=$(awk '{print $14 + $15}' "$task/stat" 2>/dev/null || echo 0)
      fi
    done
    echo "$total $ws" >cpu.tmp && mv cpu.tmp cpu
    sleep 0.2
  done
) &
pids+=($!)

cat >players.json <<EOF
{ "chromium": "$chromium", "clientDir": "$client", "url": "ws://127.0.0.1:$ws_port/matches/m",
  "game": "crates", "tokens": ["$(cat token2)", "$(cat token3)"],
  "faults": { "latencyMs": 40, "jitterMs": 10, "loss": 0.03 }, "timeoutS": 90,
  "out": "$work/pages.json" }
EOF
"$bin/rewind-bots" --connect "127.0.0.1:$port" --bots 2 --token-file native.tokens \
  --game crates --latency-ms 40 --jitter-ms 10 --loss 0.03 --duration 90 --summary-json \
  >native.json 2>native.log &
native=$!
pids+=("$native")
(cd "$scripts" && node browser_players.mjs "$work/players.json") >pages.log 2>&1 ||
  fail "the browser players: $(tail -8 pages.log)"
cat pages.log
wait "$native" || fail "the native bots: $(tail -5 native.log)"
wait "$server_pid" || fail "server exit: $(tail -5 server.log)"

[ "$(json native.json finished)" = 2 ] || fail "native bots: $(cat native.json)"
[ "$(json native.json desyncs)" = 0 ] || fail "a native bot desynced: $(cat native.json)"
[ "$(json server.json players_joined)" = "$players" ] || fail "joined: $(cat server.json)"
[ "$(json server.json desync_reports)" = 0 ] || fail "desync reports: $(cat server.json)"
grep -c "joined from 100::" server.log | grep -qx 2 || fail "not 2 players over WebSocket"
"$bin/rewind-replay" verify match.rwr >verify.txt || fail "replay: $(cat verify.txt)"

seconds=$(json server.json duration_s)
read -r cpu_total cpu_ws <cpu
hz=$(getconf CLK_TCK)
python3 - "$seconds" "$cpu_total" "$cpu_ws" "$hz" server.json <<'EOF' | tee figures.txt
import json, sys
seconds, total, ws, hz = float(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
s = json.loads(open(sys.argv[5]).read().strip().splitlines()[-1])
per = lambda b: b / 2 / seconds / 1000  # 2 players on each transport; kB/s
print(f"bandwidth per player (payload, kB/s): UDP out {per(s['udp_bytes_out']):.2f} "
      f"in {per(s['udp_bytes_in']):.2f}; WebSocket out {per(s['websocket_bytes_out']):.2f} "
      f"in {per(s['websocket_bytes_in']):.2f}")
print(f"server CPU: {100 * total / hz / seconds / 4:.2f}% of a core per player (all 4), "
      f"WebSocket thread {100 * ws / hz / seconds / 2:.2f}% of a core per browser "
      f"({total / hz:.2f} s and {ws / hz:.2f} s over {seconds:.1f} s)")
EOF
echo "PASS [$test_name]: 2 browsers and 2 native bots, $ticks ticks, 0 desyncs, replay verified"
