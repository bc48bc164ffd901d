#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Several matches in one rewind-server process, with the real programs.
#   matches_test.sh MODE BIN_DIR WORK_DIR
#   launch   --matches 2: two tokenless matches on consecutive ids and their
#            own ports, two bots each; both play to their tick budget with
#            no desync, the summaries name their match, and each match's
#            replay (named by its id) verifies.
#   control  --control --matches 0 and a server key: matches allocated by
#            POST /matches with a caller's bearer key (no key 401; bad,
#            duplicate, over-the-limit, path-like and day-long calls refused
#            with 400, 409 and 503), each played by bots holding tokens for
#            it; a token for one match does not join another; GET /matches
#            lists them, /metrics (its own port) carries them, another
#            caller's DELETE is 403, the owner's ends a lobby; a finished
#            match's id is refused while its replay exists; SIGTERM ends the
#            process after its matches, exit 0.
set -euo pipefail
mode=$1
bin=$2
work=$3
test_name=matches_$mode
# shellcheck source=script_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_common.sh"
enter_work_dir "$work"

tick_rate=${REWIND_TEST_TICK_RATE:-60}
ticks=${REWIND_TEST_TICKS:-480}
bot_seconds=$(( ticks / tick_rate + 30 ))

# http METHOD PORT TARGET [KEY]: prints "CODE BODY"; KEY goes as a bearer.
http() {
  python3 - "$1" "$2" "$3" "${4:-}" <<'PY'
import sys, urllib.request, urllib.error
method, port, target, key = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
headers = {"Authorization": f"Bearer {key}"} if key else {}
request = urllib.request.Request(f"http://127.0.0.1:{port}{target}", method=method,
                                 headers=headers)
try:
    with urllib.request.urlopen(request, timeout=5) as answer:
        print(answer.status, answer.read().decode().strip())
except urllib.error.HTTPError as error:
    print(error.code, error.read().decode().strip())
PY
}

# summary_of MATCH: the server's --summary-json line for MATCH.
summary_of() { grep "\"match\":\"$1\"" server.json || fail "no summary for $1: $(cat server.json)"; }

check_bots() {  # FILE: every bot finished, none desynced
  [ "$(json "$1" finished)" = 2 ] || fail "$1: bots did not finish: $(cat "$1")"
  [ "$(json "$1" desyncs)" = 0 ] || fail "$1: desync: $(cat "$1")"
}

case "$mode" in
launch)
  "$bin/rewind-server" --bind 127.0.0.1 --port 0 --port-file port --matches 2 --players 2 \
    --tick-rate "$tick_rate" --ticks "$ticks" --replay "game-{match}.rwr" --join-timeout 30 \
    --summary-json >server.json 2>server.log &
  server_pid=$!
  pids+=("$server_pid")
  for _ in $(seq 1 100); do [ "$(wc -l <port 2>/dev/null || echo 0)" = 2 ] && break; sleep 0.1; done
  [ "$(wc -l <port)" = 2 ] || fail "the server did not write two ports: $(cat server.log)"
  first=$(sed -n 1p port)
  second=$(sed -n 2p port)
  [ "$first" != "$second" ] || fail "both matches on port $first"
  "$bin/rewind-bots" --bots 2 --connect "127.0.0.1:$first" --duration "$bot_seconds" \
    --summary-json >bots1.json 2>bots1.log &
  bots1=$!
  "$bin/rewind-bots" --bots 2 --connect "127.0.0.1:$second" --duration "$bot_seconds" \
    --summary-json >bots2.json 2>bots2.log &
  bots2=$!
  pids+=("$bots1" "$bots2")
  wait "$bots1" || fail "bots of match-1 failed: $(tail -3 bots1.log)"
  wait "$bots2" || fail "bots of match-2 failed: $(tail -3 bots2.log)"
  wait "$server_pid" || fail "server exited with $?: $(tail -5 server.log)"
  check_bots bots1.json
  check_bots bots2.json
  for id in match-1 match-2; do
    summary_of "$id" | grep -q "\"ticks_final\":$ticks," || fail "$id: $(summary_of "$id")"
    grep -q "\[rewind-server\] $id: match ends: tick budget reached" server.log ||
      fail "$id: no end in the log"
    "$bin/rewind-replay" verify "game-$id.rwr" >"verify-$id.txt" ||
      fail "replay of $id does not verify: $(cat "verify-$id.txt")"
  done
  echo "launch: 2 matches, $ticks final ticks each, both replays verify"
  ;;
control)
  "$bin/rewind-token" keygen --out server.key >/dev/null
  backend=$("$bin/rewind-token" api-key --name backend --keys control.keys)
  other=$("$bin/rewind-token" api-key --name other --keys control.keys)
  "$bin/rewind-server" --bind 127.0.0.1 --port 0 --matches 0 --max-matches 2 --control \
    --control-bind 127.0.0.1:0 --control-port-file cport --control-keys control.keys \
    --metrics-bind 127.0.0.1:0 --metrics-port-file mport --key-file server.key \
    --tick-rate "$tick_rate" --replay "{match}.rwr" --summary-json >server.json 2>server.log &
  server_pid=$!
  pids+=("$server_pid")
  for _ in $(seq 1 100); do [ -s cport ] && [ -s mport ] && break; sleep 0.1; done
  [ -s cport ] || fail "no control endpoint: $(cat server.log)"
  cport=$(cat cport)
  mport=$(cat mport)
  code=$(http GET "$cport" /matches); [ "${code%% *}" = 401 ] || fail "no key: $code"
  code=$(http POST "$cport" "/matches?id=x" "$backend-wrong"); [ "${code%% *}" = 401 ] ||
    fail "wrong key: $code"
  [ "$(http GET "$cport" /matches "$backend")" = "200 []" ] ||
    fail "GET /matches: $(http GET "$cport" /matches "$backend")"
  answer=$(http POST "$cport" "/matches?id=north&players=2&ticks=$ticks&join_timeout=30" "$backend")
  [ "${answer%% *}" = 201 ] || fail "POST north: $answer"
  north=$(python3 -c "import json,sys; print(json.loads(sys.argv[1])['port'])" "${answer#* }")
  answer=$(http POST "$cport" "/matches?id=south&players=2&ticks=$ticks&join_timeout=30" "$backend")
  [ "${answer%% *}" = 201 ] || fail "POST south: $answer"
  south=$(python3 -c "import json,sys; print(json.loads(sys.argv[1])['port'])" "${answer#* }")
  code=$(http POST "$cport" "/matches?id=bad&players=99" "$backend")
  [ "${code%% *}" = 400 ] || fail "bad: $code"
  code=$(http POST "$cport" "/matches?id=.." "$backend"); [ "${code%% *}" = 400 ] || fail "..: $code"
  code=$(http POST "$cport" "/matches?id=slow&join_timeout=86400" "$backend")
  [ "${code%% *}" = 400 ] || fail "a day-long lobby: $code"
  code=$(http POST "$cport" "/matches?id=north" "$backend"); [ "${code%% *}" = 409 ] ||
    fail "duplicate: $code"
  code=$(http POST "$cport" "/matches?id=third" "$backend"); [ "${code%% *}" = 503 ] ||
    fail "limit: $code"
  code=$(http PUT "$cport" "/matches" "$backend"); [ "${code%% *}" = 405 ] || fail "PUT: $code"
  code=$(http DELETE "$cport" "/matches/north" "$other"); [ "${code%% *}" = 403 ] ||
    fail "another caller's DELETE: $code"
  code=$(http GET "$mport" "/matches" "$backend"); [ "${code%% *}" = 404 ] ||
    fail "control on the metrics port: $code"
  for id in north south; do
    for slot in 0 1; do
      "$bin/rewind-token" mint --key-file server.key --match "$id" --slot "$slot" \
        --client-id $((slot + 10)) >>"tokens-$id"
    done
  done
  # A token for north does not open south.
  if "$bin/rewind-bots" --bots 1 --connect "127.0.0.1:$south" --token-file tokens-north \
       --duration 2 >/dev/null 2>crossed.log; then
    fail "a token for north joined south"
  fi
  for id in north south; do
    port_var=$id
    "$bin/rewind-bots" --bots 2 --connect "127.0.0.1:${!port_var}" --token-file "tokens-$id" \
      --duration "$bot_seconds" --summary-json >"bots-$id.json" 2>"bots-$id.log" &
    pids+=($!)
    eval "bots_$id=$!"
  done
  # While they play: both listed, the metrics carry both.
  sleep 2
  listed=$(http GET "$cport" /matches "$backend")
  for id in north south; do
    echo "$listed" | grep -q "\"id\":\"$id\"" || fail "GET /matches lacks $id: $listed"
  done
  scraped=$(http GET "$mport" /metrics)
  echo "$scraped" | grep -q 'rewind_ticks_final_total{match="south"}' ||
    fail "no metrics for south: $(echo "$scraped" | head -3)"
  wait "$bots_north" || fail "north's bots failed: $(tail -3 bots-north.log)"
  wait "$bots_south" || fail "south's bots failed: $(tail -3 bots-south.log)"
  check_bots bots-north.json
  check_bots bots-south.json
  # A third match now fits; its lobby is ended through the API.
  answer=$(http POST "$cport" "/matches?id=late&players=2" "$backend")
  [ "${answer%% *}" = 201 ] || fail "POST late: $answer"
  code=$(http DELETE "$cport" "/matches/late" "$backend"); [ "${code%% *}" = 202 ] ||
    fail "DELETE: $code"
  code=$(http DELETE "$cport" "/matches/nobody" "$backend"); [ "${code%% *}" = 404 ] ||
    fail "DELETE: $code"
  for _ in $(seq 1 50); do
    http GET "$cport" /matches/late "$backend" | grep -q '"phase":"ended"' && break
    sleep 0.1
  done
  # North's replay is its record: the id stays taken, the file untouched.
  size=$(stat -c %s north.rwr)
  code=$(http POST "$cport" "/matches?id=north" "$backend"); [ "${code%% *}" = 409 ] ||
    fail "reusing north's id: $code"
  [ "$(stat -c %s north.rwr)" = "$size" ] || fail "north.rwr changed"
  kill -TERM "$server_pid"
  wait "$server_pid" || fail "server exited with $? after SIGTERM: $(tail -5 server.log)"
  for id in north south; do
    summary_of "$id" | grep -q "\"ticks_final\":$ticks," || fail "$id: $(summary_of "$id")"
    "$bin/rewind-replay" verify "$id.rwr" >"verify-$id.txt" ||
      fail "replay of $id does not verify: $(cat "verify-$id.txt")"
  done
  summary_of late | grep -q '"end_reason":"stopped by the control API (backend)"' ||
    fail "late: $(summary_of late)"
  echo "control: north and south allocated and played ($ticks ticks each), late stopped; replays verify"
  ;;
*)
  fail "unknown mode $mode"
  ;;
esac
