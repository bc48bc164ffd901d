#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A player's process dies mid-match and a new one takes the slot back.
#   rejoin_test.sh MODE BIN_DIR WORK_DIR
# MODE:
#   token      a secure server: the dead player's token, presented again
#              (a copy, keys included), is refused; the backend mints a
#              fresh token for the same client id and slot, and the
#              restarted client rejoins its own slot with it from a new
#              port once the server has dropped the dead connection;
#   tokenless  the dead player times out, and the next joiner takes the
#              free slot.
# Either way the newcomer catches up from a snapshot and plays to the end
# with every final checksum verified, the other players never notice, and
# the replay verifies.
set -euo pipefail
mode=$1
bin=$2
work=$3
test_name="rejoin $mode"
# shellcheck source=script_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_common.sh"
enter_work_dir "$work"


tick_rate=${REWIND_TEST_TICK_RATE:-60}
ticks=$(( tick_rate * 12 ))
server_args=(--game crates --bind 127.0.0.1 --port 0 --port-file port --players 2
             --tick-rate "$tick_rate" --ticks "$ticks" --replay match.rwr --join-timeout 30
             --peer-timeout 1 --summary-json)
if [ "$mode" = token ]; then
  "$bin/rewind-token" keygen --out server.key >/dev/null
  "$bin/rewind-token" mint --key-file server.key --match m --slot 0 --client-id 1 >token0
  "$bin/rewind-token" mint --key-file server.key --match m --slot 1 --client-id 2 >token1
  server_args+=(--key-file server.key --match-id m)
fi
start_server "${server_args[@]}"
connect=(--connect "127.0.0.1:$port" --duration $(( ticks / tick_rate + 30 )) --summary-json)
token_for() { [ "$mode" = token ] && echo "--token-file token$1" || true; }

# shellcheck disable=SC2046
"$bin/rewind-bots" --bots 1 "${connect[@]}" $(token_for 0) --seed 1 >stayer.json 2>stayer.log &
stayer=$!
pids+=("$stayer")
sleep 0.3
# shellcheck disable=SC2046
"$bin/rewind-bots" --bots 1 "${connect[@]}" $(token_for 1) --seed 2 >doomed.json 2>doomed.log &
doomed=$!
pids+=("$doomed")
# Let the match run a few seconds, then kill the second player's process.
for _ in $(seq 1 100); do grep -q "all 2 players joined" server.log && break; sleep 0.1; done
sleep 3
kill -9 "$doomed"
wait "$doomed" 2>/dev/null || true
if [ "$mode" = token ]; then
  # A token connects once: the dead player's token (or a copy of it) gets
  # no challenge, so that bot never joins.
  status=0
  "$bin/rewind-bots" --bots 1 --connect "127.0.0.1:$port" --duration 2 --summary-json \
    --token-file token1 >copied.json 2>copied.log || status=$?
  [ "$status" = 2 ] && [ "$(json copied.json joined)" = 0 ] \
    || fail "a used token joined again (exit $status): $(cat copied.json)"
  # What the backend does for a client that comes back: a fresh token for
  # the same client id and slot.
  "$bin/rewind-token" mint --key-file server.key --match m --slot 1 --client-id 2 >token1
else
  sleep 2  # past --peer-timeout: the slot is free
fi
# shellcheck disable=SC2046
"$bin/rewind-bots" --bots 1 "${connect[@]}" $(token_for 1) --seed 3 >newcomer.json 2>newcomer.log \
  || fail "the newcomer failed: $(tail -5 newcomer.log)"
wait "$stayer" || fail "the other player failed: $(tail -5 stayer.log)"
wait "$server_pid" || fail "server exit: $(tail -5 server.log)"

grep -q "player 1 rejoined" server.log || fail "the server did not log a rejoin: $(tail -20 server.log)"
if [ "$mode" = token ]; then
  [ "$(json server.json secure_sessions)" = 3 ] || fail "sessions: $(cat server.json)"
  [ "$(json server.json secure_refused)" -ge 1 ] || fail "the used token was not refused: $(cat server.json)"
fi
for who in stayer newcomer; do
  [ "$(json $who.json finished)" = 1 ] || fail "$who did not finish: $(cat $who.json)"
  [ "$(json $who.json desyncs)" = 0 ] || fail "$who desynced: $(cat $who.json)"
done
[ "$(json newcomer.json resyncs)" -ge 1 ] || fail "the newcomer did not start from a snapshot"
verified=$(json newcomer.json final_ticks_verified)
[ "$verified" -gt $(( ticks / 4 )) ] || fail "the newcomer verified only $verified final ticks"
[ "$(json server.json ticks_final)" = "$ticks" ] || fail "ticks: $(cat server.json)"
"$bin/rewind-replay" verify match.rwr >verify.txt || fail "replay: $(cat verify.txt)"
echo "rejoin [$mode]: newcomer caught up from a snapshot and verified $verified final ticks"
echo "PASS [rejoin $mode]"
