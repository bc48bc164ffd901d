#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Hosted demo match on loopback: builds the release preset, mints a server
# key and one connect token per player (rewind-token, as a match backend
# would), starts a secure rewind-server (4-player "crates", 60 Hz, 1200
# ticks = 20 s), plays it with 4 bots over an impaired link (40 ms latency, 15 ms jitter, 5 % loss,
# duplication, reordering), prints both summaries, then re-simulates the
# recorded replay with `rewind-replay verify`.
#
# Usage: scripts/demo.sh [--port N] [--no-build]
#   --port N     UDP port for the server (default 7777, or a random free port
#                when 7777 is taken; an explicit --port must be free)
#   --no-build   use the binaries already in build/release/bin
# Output files: build/demo/{match.rwr, desyncs/, server.log, bots.log,
#               server.json, bots.json, server.key, tokens}
# Exit codes: 0 the match ran and its replay verified; 1 a step failed (build,
# server, bots, missing summary); rewind-replay verify's own status when the
# replay does not verify (1 diverged, 2 corrupt, 3 recorded by another engine
# version, 4 incomplete); 2 on bad usage.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$(pwd)

port=""
build=1
usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
while (($#)); do
  case "$1" in
    --port) (($# >= 2)) || { echo "demo: --port needs a value" >&2; exit 2; }
            port=$2; shift 2 ;;
    --port=*) port=${1#--port=}; shift ;;
    --no-build) build=0; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "demo: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
done
if [[ -n $port ]]; then
  if ! [[ $port =~ ^[0-9]{1,5}$ ]] || ((10#$port < 1 || 10#$port > 65535)); then
    echo "demo: --port needs a number in 1..65535" >&2
    exit 2
  fi
  port=$((10#$port))
fi

bin="$root/build/release/bin"
demo_dir="$root/build/demo"
ticks=1200
tick_rate=60

step() { echo; echo "==> $*"; }
fail() { echo "demo: FAIL: $*" >&2; exit 1; }

# True when some socket on this machine has UDP port $1 bound (any address).
# Reads /proc instead of binding a test socket, so it never races the server.
udp_port_in_use() {
  local hex
  hex=$(printf '%04X' "$1")
  awk -v p=":$hex" 'FNR > 1 && substr($2, length($2) - 4) == p { found = 1 } END { exit !found }' \
    /proc/net/udp /proc/net/udp6 2>/dev/null
}
random_free_udp_port() {
  python3 -c 'import socket
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.bind(("127.0.0.1", 0))
print(s.getsockname()[1])'
}

if ((build)); then
  step "system packages"
  bash scripts/setup.sh
  step "build (preset release: rewind-server rewind-bots rewind-replay rewind-token)"
  cmake --preset release
  cmake --build --preset release -j"$(nproc 2>/dev/null || echo 2)" \
    --target rewind-server rewind-bots rewind-replay rewind-token
fi
for tool in rewind-server rewind-bots rewind-replay rewind-token; do
  [[ -x $bin/$tool ]] || fail "$bin/$tool is missing (build the release preset first)"
done

if [[ -z $port ]]; then
  port=7777
  if udp_port_in_use "$port"; then
    port=$(random_free_udp_port)
    echo "demo: UDP port 7777 is busy; using $port"
  fi
elif udp_port_in_use "$port"; then
  fail "UDP port $port is already in use"
fi

rm -rf "$demo_dir"
mkdir -p "$demo_dir/desyncs"

server_pid=""
bots_pid=""
cleanup() {
  local pid
  for pid in "$bots_pid" "$server_pid"; do
    if [[ -n $pid ]] && kill -0 "$pid" 2>/dev/null; then
      kill "$pid" 2>/dev/null || true
      wait "$pid" 2>/dev/null || true
    fi
  done
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# Waits up to $2 seconds for pid $1 to exit; its status goes to $wait_status.
wait_status=0
wait_for() {
  local pid=$1 limit=$2 waited=0
  while kill -0 "$pid" 2>/dev/null; do
    if ((waited >= limit * 10)); then return 1; fi
    sleep 0.1
    waited=$((waited + 1))
  done
  wait_status=0
  wait "$pid" || wait_status=$?
  return 0
}

# Prints the last line of $1 if it is one JSON object; fails otherwise.
summary_line() {
  local file=$1 who=$2 line
  line=$(tail -n 1 "$file" 2>/dev/null || true)
  [[ -n $line ]] || fail "$who printed no summary line on stdout ($file is empty)"
  printf '%s' "$line" | python3 -c 'import json, sys; v = json.loads(sys.stdin.read()); sys.exit(0 if isinstance(v, dict) else 1)' \
    2>/dev/null || fail "$who's last stdout line is not a JSON object: $line"
  printf '%s\n' "$line"
}

step "backend: a server key and a connect token for each of the 4 players"
rm -f "$demo_dir/server.key" "$demo_dir/tokens"
"$bin/rewind-token" keygen --out "$demo_dir/server.key" >/dev/null
for slot in 0 1 2 3; do
  "$bin/rewind-token" mint --key-file "$demo_dir/server.key" --match demo --slot "$slot" \
    --client-id $((slot + 1)) --expires-in 600 >>"$demo_dir/tokens"
done

step "server: 127.0.0.1:$port, crates, 4 players, $tick_rate Hz, $ticks ticks, secure connections"
"$bin/rewind-server" --game crates --port "$port" --bind 127.0.0.1 --players 4 \
  --tick-rate "$tick_rate" --window 8 --ticks "$ticks" \
  --key-file "$demo_dir/server.key" --match-id demo \
  --replay "$demo_dir/match.rwr" --desync-dir "$demo_dir/desyncs" --summary-json \
  >"$demo_dir/server.json" 2>"$demo_dir/server.log" &
server_pid=$!

# Wait until the server has bound its socket (or died).
for ((i = 0; i < 100; ++i)); do
  udp_port_in_use "$port" && break
  kill -0 "$server_pid" 2>/dev/null || break
  sleep 0.1
done
if ! kill -0 "$server_pid" 2>/dev/null; then
  wait "$server_pid" || true
  tail -n 20 "$demo_dir/server.log" >&2 || true
  fail "rewind-server exited before the match started (log: $demo_dir/server.log)"
fi
udp_port_in_use "$port" || fail "rewind-server did not bind UDP port $port within 10 s"

step "bots: 4 clients, 40 ms latency, 15 ms jitter, 5% loss, 1% duplicates, 2% reordering (~20 s)"
"$bin/rewind-bots" --bots 4 --connect "127.0.0.1:$port" --game crates \
  --token-file "$demo_dir/tokens" --latency-ms 40 --jitter-ms 15 --loss 0.05 --duplicate 0.01 --reorder 0.02 --summary-json \
  >"$demo_dir/bots.json" 2>"$demo_dir/bots.log" &
bots_pid=$!

# The match itself takes ticks / tick_rate seconds; allow generous slack for
# joining, the finalization window and a loaded machine.
limit=$((ticks / tick_rate + 60))
wait_for "$bots_pid" "$limit" || fail "rewind-bots still running after ${limit}s (log: $demo_dir/bots.log)"
bots_status=$wait_status
bots_pid=""
wait_for "$server_pid" 30 || fail "rewind-server still running 30 s after the bots finished (log: $demo_dir/server.log)"
server_status=$wait_status
server_pid=""

if ((server_status != 0)); then
  tail -n 20 "$demo_dir/server.log" >&2 || true
  fail "rewind-server exited with status $server_status (log: $demo_dir/server.log)"
fi
if ((bots_status != 0)); then
  tail -n 20 "$demo_dir/bots.log" >&2 || true
  fail "rewind-bots exited with status $bots_status (log: $demo_dir/bots.log)"
fi

step "summaries"
server_summary=$(summary_line "$demo_dir/server.json" rewind-server)
bots_summary=$(summary_line "$demo_dir/bots.json" rewind-bots)
echo "server: $server_summary"
echo "bots:   $bots_summary"

step "rewind-replay verify build/demo/match.rwr"
[[ -s $demo_dir/match.rwr ]] || fail "the server wrote no replay at $demo_dir/match.rwr"
verify_status=0
"$bin/rewind-replay" verify "$demo_dir/match.rwr" || verify_status=$?
if ((verify_status != 0)); then
  echo "demo: FAIL: the replay did not verify (rewind-replay exit status $verify_status)" >&2
  exit "$verify_status"
fi

# One line a person can read: the figures that say the match went right.
printf '%s\n%s\n' "$server_summary" "$bots_summary" | python3 -c '
import json, sys
server, bots = (json.loads(line) for line in sys.stdin.read().splitlines()[:2])
print("match: %d final ticks, %d players; rollbacks: server %d, clients %d (%d ticks re-simulated); "
      "late inputs %d, substituted %d; desyncs %d; final checksums verified by the clients: %d"
      % (server["ticks_final"], server["players_joined"], server["rollbacks"], bots["rollbacks"],
         server["resimulated_ticks"] + bots["resimulated_ticks"], server["late_inputs"],
         server["substituted_inputs"], bots["desyncs"], bots["final_ticks_verified"]))
'

echo
echo "demo: OK: match played on 127.0.0.1:$port, summaries above, replay verified" \
     "(files in build/demo/)"
