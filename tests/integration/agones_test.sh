#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# rewind-server --agones against a fake Agones SDK sidecar (fake_agones.py).
#   agones_test.sh MODE BIN_DIR WORK_DIR
# MODE match: the sidecar turns Allocated 2 s after Ready, with annotations
#   for 3 players and a tick budget, and a label for the match id (the flags
#   say 2 players and no budget). The server must send Ready before the
#   allocation and bind only after it, ping /health throughout, host 3 bots
#   to the annotated budget, and send Shutdown exactly once, after the match.
# MODE refused: the allocation asks for 99 players. The server must log a
#   clear error naming the annotation, send Shutdown once, host nothing and
#   exit 1.
# MODE signal: SIGTERM while waiting for an allocation. The server must send
#   Shutdown once and exit 0 without hosting.
# MODE unreachable: no sidecar at AGONES_SDK_HTTP_PORT. The server must say
#   so and exit 1 within its sidecar timeout; a malformed
#   AGONES_SDK_HTTP_PORT is a usage error (64).
set -euo pipefail
mode=$1
bin=$2
work=$3
test_name=agones_$mode
# shellcheck source=script_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_common.sh"
enter_work_dir "$work"
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

tick_rate=${REWIND_TEST_TICK_RATE:-60}
ticks=$((tick_rate * 5))
players=3
allocate_after=2
health_period=0.5

# calls METHOD PATH: how many such calls the sidecar recorded.
calls() {
  python3 -c "
import json, sys
n = sum(1 for line in open('calls.jsonl')
        if (e := json.loads(line)).get('method') == sys.argv[1] and e.get('path') == sys.argv[2])
print(n)" "$1" "$2"
}
# first_t METHOD PATH (or 'event NAME'): the time of the first such record.
first_t() {
  python3 -c "
import json, sys
for line in open('calls.jsonl'):
    e = json.loads(line)
    if (sys.argv[1] == 'event' and e.get('event') == sys.argv[2]) or \
       (e.get('method') == sys.argv[1] and e.get('path') == sys.argv[2]):
        print(e['t']); break
else:
    print('none')" "$1" "$2"
}
last_call() {
  python3 -c "
import json
calls = [e for line in open('calls.jsonl') if 'method' in (e := json.loads(line))]
print(calls[-1]['method'], calls[-1]['path'])"
}
# before A B: time A is earlier than time B (both numbers).
before() { [ "$1" != none ] && [ "$2" != none ] && awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }
not_after() { [ "$1" != none ] && [ "$2" != none ] && awk -v a="$1" -v b="$2" 'BEGIN { exit !(a <= b) }'; }

start_sidecar() {
  python3 "$here/fake_agones.py" --port-file sidecar_port --log calls.jsonl \
    --allocate-after "$allocate_after" "$@" 2>sidecar.log &
  pids+=($!)
  for _ in $(seq 1 100); do [ -s sidecar_port ] && break; sleep 0.1; done
  [ -s sidecar_port ] || fail "the fake sidecar did not start: $(cat sidecar.log)"
  export AGONES_SDK_HTTP_PORT
  AGONES_SDK_HTTP_PORT=$(cat sidecar_port)
}

case "$mode" in
match)
  start_sidecar --annotation "rewind.dev/players=$players" --annotation "rewind.dev/ticks=$ticks" \
    --label rewind.dev/match-id=duel-7
  "$bin/rewind-server" --agones --agones-health-period "$health_period" --game crates \
    --bind 127.0.0.1 --port 0 --port-file port --players 2 --tick-rate "$tick_rate" \
    --join-timeout 60 --summary-json >server.json 2>server.log &
  server_pid=$!
  pids+=("$server_pid")
  for _ in $(seq 1 150); do [ -s port ] && break; sleep 0.1; done
  [ -s port ] || fail "the server did not bind after the allocation: $(cat server.log)"
  bound_t=$(python3 -c "import json; print([json.loads(l) for l in open('calls.jsonl')][-1]['t'])")
  "$bin/rewind-bots" --bots "$players" --connect "127.0.0.1:$(cat port)" \
    --duration $((ticks / tick_rate + 30)) --summary-json >bots.json 2>bots.log \
    || fail "bots failed: $(tail -5 bots.log)"
  wait "$server_pid" || fail "server exit $?: $(tail -5 server.log)"

  ready_t=$(first_t POST /ready)
  allocated_t=$(first_t event allocated)
  shutdown_t=$(first_t POST /shutdown)
  before "$ready_t" "$allocated_t" || fail "Ready ($ready_t) not before the allocation ($allocated_t)"
  # The last call the sidecar saw when the port file appeared.
  not_after "$allocated_t" "$bound_t" || fail "the port was bound before the allocation"
  [ "$(calls POST /ready)" = 1 ] || fail "Ready sent $(calls POST /ready) times"
  [ "$(calls POST /shutdown)" = 1 ] || fail "Shutdown sent $(calls POST /shutdown) times"
  [ "$(last_call)" = "POST /shutdown" ] || fail "calls after Shutdown: last is $(last_call)"
  before "$bound_t" "$shutdown_t" || fail "Shutdown ($shutdown_t) before the match"
  # Pings every 0.5 s over the whole run (2 s waiting, 5 s of ticks):
  # at least half the number the period allows.
  pings=$(calls POST /health)
  min_pings=$(awk -v t="$shutdown_t" -v p="$health_period" 'BEGIN { printf "%d", t / p / 2 }')
  [ "$pings" -ge "$min_pings" ] || fail "$pings health pings in $shutdown_t s (want >= $min_pings)"
  [ "$(calls GET /gameserver)" -ge 2 ] || fail "GET /gameserver not polled"

  [ "$(json server.json players_joined)" = "$players" ] \
    || fail "players from the annotation not used: $(cat server.json)"
  [ "$(json server.json ticks_final)" = "$ticks" ] \
    || fail "tick budget from the annotation not used: $(cat server.json)"
  [ "$(json server.json end_reason)" = "tick budget reached" ] || fail "$(cat server.json)"
  [ "$(json bots.json finished)" = "$players" ] || fail "not every bot finished: $(cat bots.json)"
  [ "$(json bots.json desyncs)" = 0 ] || fail "desync: $(cat bots.json)"
  grep -q "match settings from the allocation: match-id=duel-7 (label), players=$players (annotation), ticks=$ticks (annotation)" \
    server.log || fail "the applied settings are not logged: $(cat server.log)"
  grep -q "hosting 'crates' for $players players" server.log || fail "$(cat server.log)"
  grep -q "agones: Shutdown sent (the match is over)" server.log || fail "$(cat server.log)"
  grep -q "agones: $pings health pings, 0 failed" server.log \
    || fail "health ping count not logged as $pings: $(tail -3 server.log)"
  echo "agones match: Ready at $ready_t s, allocated at $allocated_t s, bound by $bound_t s," \
    "Shutdown at $shutdown_t s, $pings health pings, $ticks ticks for $players players"
  ;;
refused)
  start_sidecar --annotation rewind.dev/players=99 --annotation rewind.dev/ticks=600
  status=0
  timeout 30 "$bin/rewind-server" --agones --agones-health-period "$health_period" \
    --bind 127.0.0.1 --port 0 --port-file port --summary-json >server.json 2>server.log \
    || status=$?
  [ "$status" = 1 ] || fail "exit $status (want 1): $(cat server.log)"
  grep -q "agones: allocation refused, no match hosted: rewind.dev/players: '99' is outside \[1, 32\]" \
    server.log || fail "no clear error: $(cat server.log)"
  [ ! -e port ] || fail "a port was bound for a refused allocation"
  ! grep -q "hosting " server.log || fail "a match was hosted: $(cat server.log)"
  [ ! -s server.json ] || fail "a summary was printed: $(cat server.json)"
  [ "$(calls POST /ready)" = 1 ] || fail "Ready sent $(calls POST /ready) times"
  [ "$(calls POST /shutdown)" = 1 ] || fail "Shutdown sent $(calls POST /shutdown) times"
  [ "$(last_call)" = "POST /shutdown" ] || fail "calls after Shutdown: last is $(last_call)"
  grep -q "agones: Shutdown sent (allocation refused)" server.log || fail "$(cat server.log)"
  echo "agones refused: $(grep -o 'rewind.dev/players: .*' server.log)"
  ;;
signal)
  allocate_after=100000
  start_sidecar
  "$bin/rewind-server" --agones --agones-health-period "$health_period" --bind 127.0.0.1 \
    --port 0 --port-file port >server.json 2>server.log &
  server_pid=$!
  pids+=("$server_pid")
  for _ in $(seq 1 100); do [ "$(calls POST /ready)" = 1 ] && break; sleep 0.1; done
  [ "$(calls POST /ready)" = 1 ] || fail "no Ready: $(cat server.log)"
  sleep 1
  kill -TERM "$server_pid"
  status=0
  wait "$server_pid" || status=$?
  [ "$status" = 0 ] || fail "exit $status after SIGTERM (want 0): $(cat server.log)"
  [ "$(calls POST /shutdown)" = 1 ] || fail "Shutdown sent $(calls POST /shutdown) times"
  [ "$(last_call)" = "POST /shutdown" ] || fail "calls after Shutdown: last is $(last_call)"
  grep -q "agones: Shutdown sent (stopped by SIGTERM)" server.log || fail "$(cat server.log)"
  [ ! -e port ] || fail "a port was bound without an allocation"
  echo "agones signal: $(grep 'Shutdown sent' server.log)"
  ;;
unreachable)
  # A port nothing listens on: bound and closed again at once.
  export AGONES_SDK_HTTP_PORT
  AGONES_SDK_HTTP_PORT=$(python3 -c "import socket; s = socket.socket(); s.bind(('127.0.0.1', 0)); print(s.getsockname()[1])")
  status=0
  started=$(date +%s%N)
  timeout 30 "$bin/rewind-server" --agones --agones-sidecar-timeout 1 --bind 127.0.0.1 --port 0 \
    --port-file port >server.json 2>server.log || status=$?
  elapsed_ms=$((($(date +%s%N) - started) / 1000000))
  [ "$status" = 1 ] || fail "exit $status (want 1): $(cat server.log)"
  grep -q "agones: the SDK sidecar at localhost:$AGONES_SDK_HTTP_PORT did not answer within 1 s" \
    server.log || fail "no clear error: $(cat server.log)"
  [ "$elapsed_ms" -lt 10000 ] || fail "took $elapsed_ms ms to give up"
  [ ! -e port ] || fail "a port was bound without a sidecar"
  status=0
  AGONES_SDK_HTTP_PORT=70000 "$bin/rewind-server" --agones --port 0 >/dev/null 2>bad_env.log \
    || status=$?
  [ "$status" = 64 ] || fail "AGONES_SDK_HTTP_PORT=70000: exit $status (want 64)"
  grep -q "AGONES_SDK_HTTP_PORT='70000' is not a port number" bad_env.log \
    || fail "$(cat bad_env.log)"
  echo "agones unreachable: gave up after $elapsed_ms ms: $(tail -1 server.log)"
  ;;
*)
  fail "unknown mode '$mode'"
  ;;
esac
echo "PASS [$test_name]"
