#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Spectators: read-only seats that join a running match, catch up from a
# snapshot and verify every final checksum after it to the end.
#   spectator_test.sh MODE BIN_DIR WORK_DIR
# MODE: token (a secure server; the spectators' tokens name seats past the
# player slots) or tokenless.
set -euo pipefail
mode=$1
bin=$2
work=$3
test_name="spectator $mode"
# shellcheck source=script_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_common.sh"
enter_work_dir "$work"

tick_rate=${REWIND_TEST_TICK_RATE:-60}
ticks=$(( tick_rate * 10 ))
server_args=(--game crates --bind 127.0.0.1 --port 0 --port-file port --players 2 --spectators 4
             --tick-rate "$tick_rate" --ticks "$ticks" --replay match.rwr --join-timeout 30
             --summary-json)
player_tokens=()
watcher_tokens=()
if [ "$mode" = token ]; then
  "$bin/rewind-token" keygen --out server.key >/dev/null
  for slot in 0 1 2 3; do
    "$bin/rewind-token" mint --key-file server.key --match m --slot "$slot" \
      --client-id $((slot + 1)) >"token$slot"
  done
  server_args+=(--key-file server.key --match-id m)
  cat token0 token1 >players.tokens
  cat token2 token3 >watchers.tokens
  player_tokens=(--token-file players.tokens)
  watcher_tokens=(--token-file watchers.tokens)
fi
start_server "${server_args[@]}"
connect=(--connect "127.0.0.1:$port" --duration $(( ticks / tick_rate + 30 )) --summary-json)

"$bin/rewind-bots" --bots 2 "${connect[@]}" "${player_tokens[@]}" >players.json 2>players.log &
players=$!
pids+=("$players")
for _ in $(seq 1 100); do grep -q "all 2 players joined" server.log && break; sleep 0.1; done
sleep 3  # the match is well under way
"$bin/rewind-bots" --bots 0 --spectators 2 "${connect[@]}" "${watcher_tokens[@]}" \
  >watchers.json 2>watchers.log || fail "the spectators failed: $(tail -5 watchers.log)"
wait "$players" || fail "the players failed: $(tail -5 players.log)"
wait "$server_pid" || fail "server exit: $(tail -5 server.log)"

[ "$(grep -c "spectator [0-9] joined" server.log)" = 2 ] || fail "two spectators should have joined"
[ "$(json watchers.json finished)" = 2 ] || fail "spectators: $(cat watchers.json)"
[ "$(json watchers.json desyncs)" = 0 ] || fail "a spectator desynced: $(cat watchers.json)"
[ "$(json watchers.json resyncs)" -ge 2 ] || fail "the spectators did not start from snapshots"
verified=$(json watchers.json final_ticks_verified)
[ "$verified" -gt $(( ticks / 2 )) ] || fail "the spectators verified only $verified final ticks"
[ "$(json players.json finished)" = 2 ] || fail "players: $(cat players.json)"
[ "$(json players.json desyncs)" = 0 ] || fail "a player desynced"
[ "$(json server.json players_joined)" = 2 ] || fail "spectators counted as players"
"$bin/rewind-replay" verify match.rwr >verify.txt || fail "replay: $(cat verify.txt)"
echo "spectators [$mode]: 2 joined mid-match and verified $verified final ticks between them"
echo "PASS [spectator $mode]"
