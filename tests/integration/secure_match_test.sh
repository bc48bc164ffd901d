#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A secure match on loopback with the real programs, attacked.
#   secure_match_test.sh BIN_DIR WORK_DIR
# A backend key and tokens come from rewind-token; the server takes only
# those. Before the players arrive, hostile_secure.py probes the lobby:
# clear-text joins, a foreign token, a stolen sealed token, forged
# responses get nothing (but the one challenge, smaller than its request).
# Then 4 bots play through a relay that replays every datagram (from their
# addresses and another), alters some and raises the sequence of others by a
# million; while they play, copies of their tokens (keys included) get no
# challenge (a token connects once). The match ends with every bot finished
# and no desync, the server counts what it dropped, and the replay verifies.
# A tokenless client and a client with a token for another server never join.
set -euo pipefail
bin=$1
work=$2
test_name=secure
# shellcheck source=script_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_common.sh"
enter_work_dir "$work"
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)



tick_rate=${REWIND_TEST_TICK_RATE:-60}
ticks=${REWIND_TEST_TICKS:-480}
players=4
"$bin/rewind-token" keygen --out server.key >/dev/null
"$bin/rewind-token" keygen --out other.key >/dev/null
for slot in $(seq 0 $((players - 1))); do
  "$bin/rewind-token" mint --key-file server.key --match duel-7 --slot "$slot" \
    --client-id $((slot + 100)) >>tokens
done
"$bin/rewind-token" mint --key-file other.key --match duel-7 --slot 0 --client-id 1 >foreign
"$bin/rewind-token" inspect --token-file foreign | grep -q "^slot 0$" || fail "inspect"

start_server --game crates --bind 127.0.0.1 --port 0 --port-file port --players "$players" \
  --tick-rate "$tick_rate" --ticks "$ticks" --replay match.rwr --join-timeout 30 \
  --key-file server.key --match-id duel-7 --summary-json
log_has server.log "secure connections" || fail "the server does not say it is secure"

python3 "$here/hostile_secure.py" probe "$port" tokens foreign >probe.json || fail "probe: $(cat probe.json)"
echo "probe: $(cat probe.json)"

# Neither a tokenless client nor one with another server's token joins.
if "$bin/rewind-bots" --bots 1 --connect "127.0.0.1:$port" --duration 2 >/dev/null 2>tokenless.log; then
  fail "a tokenless bot joined a secure server"
fi
if "$bin/rewind-bots" --bots 1 --connect "127.0.0.1:$port" --token-file foreign --duration 2 \
     >/dev/null 2>foreign.log; then
  fail "a bot with another server's token joined"
fi

python3 "$here/hostile_secure.py" proxy relay_port "$port" $(( ticks / tick_rate + 20 )) >relay.json &
pids+=($!)
relay_pid=$!
for _ in $(seq 1 50); do [ -s relay_port ] && break; sleep 0.1; done
[ -s relay_port ] || fail "relay did not start"
"$bin/rewind-bots" --bots "$players" --connect "127.0.0.1:$(cat relay_port)" --token-file tokens \
  --duration $(( ticks / tick_rate + 30 )) --summary-json >bots.json 2>bots.log &
bots_pid=$!
pids+=("$bots_pid")
for _ in $(seq 1 100); do grep -q "players joined" server.log && break; sleep 0.1; done
python3 "$here/hostile_secure.py" copied "$port" tokens >copied.json \
  || fail "copied tokens were answered: $(cat copied.json)"
echo "copied: $(cat copied.json)"
wait "$bots_pid" || fail "bots failed: $(tail -5 bots.log)"
wait "$server_pid" || fail "server exit $?: $(tail -5 server.log)"
kill "$relay_pid" 2>/dev/null || true

[ "$(json bots.json finished)" = "$players" ] || fail "not every bot finished: $(cat bots.json)"
[ "$(json bots.json desyncs)" = 0 ] || fail "desync: $(cat bots.json)"
[ "$(json server.json ticks_final)" = "$ticks" ] || fail "ticks: $(cat server.json)"
[ "$(json server.json players_joined)" = "$players" ] || fail "players: $(cat server.json)"
dropped=$(json server.json secure_dropped)
[ "$dropped" -gt 100 ] || fail "the server dropped only $dropped attacking datagrams"
"$bin/rewind-replay" verify match.rwr >verify.txt || fail "replay: $(cat verify.txt)"
echo "secure match: $(json server.json secure_sessions) sessions, $(json server.json secure_challenges)" \
  "challenges, $(json server.json secure_refused) handshakes refused, $dropped datagrams dropped"
echo "PASS [secure]"
