#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Late join: a match of 3 slots that starts with 2 players (--start-players
# 2); the third player joins the running match into the slot nobody held,
# catches up from a snapshot, plays to the end with no desync, and its
# inputs count from then on; the replay verifies.
#   late_join_test.sh MODE BIN_DIR WORK_DIR
# MODE: token (a secure server; the late player's token names slot 2) or
# tokenless (the first free slot; joins without an address cookie, in the
# lobby and with the slot open, get no answer and take no seat:
# hostile_tokenless.py).
set -euo pipefail
mode=$1
bin=$2
work=$3
test_name="late join $mode"
# shellcheck source=script_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_common.sh"
enter_work_dir "$work"

tick_rate=${REWIND_TEST_TICK_RATE:-60}
ticks=$(( tick_rate * 10 ))
server_args=(--game crates --bind 127.0.0.1 --port 0 --port-file port --players 3
             --start-players 2 --tick-rate "$tick_rate" --ticks "$ticks" --replay match.rwr
             --join-timeout 30 --summary-json)
first_tokens=()
late_tokens=()
if [ "$mode" = token ]; then
  "$bin/rewind-token" keygen --out server.key >/dev/null
  for slot in 0 1 2; do
    "$bin/rewind-token" mint --key-file server.key --match m --slot "$slot" \
      --client-id $((slot + 1)) >"token$slot"
  done
  server_args+=(--key-file server.key --match-id m)
  cat token0 token1 >first.tokens
  first_tokens=(--token-file first.tokens)
  late_tokens=(--token-file token2)
fi
start_server "${server_args[@]}"
connect=(--connect "127.0.0.1:$port" --duration $(( ticks / tick_rate + 30 )) --summary-json)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
probe() {
  [ "$mode" = tokenless ] || return 0
  python3 "$here/hostile_tokenless.py" probe "$port" >"probe-$1.json" \
    || fail "cookieless joins were answered ($1): $(cat "probe-$1.json")"
  echo "probe ($1): $(cat "probe-$1.json")"
}
probe lobby

"$bin/rewind-bots" --bots 2 "${connect[@]}" "${first_tokens[@]}" >first.json 2>first.log &
first=$!
pids+=("$first")
for _ in $(seq 1 100); do grep -q "2 of 3 players joined" server.log && break; sleep 0.1; done
grep -q "2 of 3 players joined; tick 0 in [0-9]* ticks (the other slots are open" server.log ||
  fail "the match did not start with 2 of 3: $(tail -3 server.log)"
sleep 3  # the match is well under way
probe running
"$bin/rewind-bots" --bots 1 "${connect[@]}" "${late_tokens[@]}" >late.json 2>late.log ||
  fail "the late player failed: $(tail -5 late.log)"
wait "$first" || fail "the first players failed: $(tail -5 first.log)"
wait "$server_pid" || fail "server exit: $(tail -5 server.log)"

grep -q "player 2 joined from" server.log || fail "the late player did not take slot 2"
[ "$(json late.json finished)" = 1 ] || fail "late player: $(cat late.json)"
[ "$(json late.json desyncs)" = 0 ] || fail "the late player desynced: $(cat late.json)"
[ "$(json late.json resyncs)" -ge 1 ] || fail "the late player did not start from a snapshot"
verified=$(json late.json final_ticks_verified)
[ "$verified" -gt $(( ticks / 3 )) ] || fail "the late player verified only $verified final ticks"
[ "$(json first.json finished)" = 2 ] || fail "first players: $(cat first.json)"
[ "$(json first.json desyncs)" = 0 ] || fail "a first player desynced"
[ "$(json server.json players_joined)" = 3 ] || fail "joined: $(json server.json players_joined)"
# Slot 2 was substituted only until its player arrived: fewer than the
# whole match's ticks.
substituted=$(json server.json substituted_inputs)
[ "$substituted" -lt "$ticks" ] || fail "slot 2 substituted $substituted times in $ticks ticks"
"$bin/rewind-replay" verify match.rwr >verify.txt || fail "replay: $(cat verify.txt)"
echo "late join [$mode]: slot 2 joined mid-match and verified $verified final ticks ($substituted inputs substituted)"
echo "PASS [late join $mode]"
