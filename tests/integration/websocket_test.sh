#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Browser transport: a secure match of 4 players, 2 over UDP and 2 over
# WebSocket (rewind-server --websocket; rewind-bots --websocket connects as a
# browser does), every one with latency and loss. Everyone finishes with no
# desync, the replay verifies, and the server's summary splits its bytes by
# transport. Before the match: a foreign token over WebSocket takes no seat,
# and an unknown match or a plain HTTP request gets no connection.
#   websocket_test.sh BIN_DIR WORK_DIR
set -euo pipefail
bin=$1
work=$2
test_name="websocket"
# shellcheck source=script_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_common.sh"
enter_work_dir "$work"

tick_rate=${REWIND_TEST_TICK_RATE:-60}
ticks=$(( tick_rate * 8 ))
"$bin/rewind-token" keygen --out server.key >/dev/null
"$bin/rewind-token" keygen --out other.key >/dev/null
for slot in 0 1 2 3; do
  "$bin/rewind-token" mint --key-file server.key --match m --slot "$slot" \
    --client-id $((slot + 1)) >"token$slot"
done
"$bin/rewind-token" mint --key-file other.key --match m --slot 3 --client-id 9 >foreign.token
cat token0 token1 >udp.tokens
cat token2 token3 >ws.tokens
start_server --game crates --bind 127.0.0.1 --port 0 --port-file port --players 4 \
  --tick-rate "$tick_rate" --ticks "$ticks" --replay match.rwr --join-timeout 30 \
  --key-file server.key --match-id m --websocket 127.0.0.1:0 --websocket-port-file ws.port \
  --summary-json
for _ in $(seq 1 100); do [ -s ws.port ] && break; sleep 0.1; done
ws_port=$(cat ws.port)
log_has server.log "browsers on ws://127.0.0.1:$ws_port/matches/<match id>" ||
  fail "no WebSocket line: $(cat server.log)"
url="ws://127.0.0.1:$ws_port/matches/m"
common=(--game crates --duration $(( ticks / tick_rate + 30 )) --summary-json --latency-ms 30
        --jitter-ms 5 --loss 0.03)

# Refused before the match starts: a token of another key over WebSocket
# takes no seat (the bot gives up at its duration), and an unknown match or
# a plain request gets an HTTP answer, not a connection.
"$bin/rewind-bots" --websocket "$url" --bots 1 --token-file foreign.token --game crates \
  --duration 2 --summary-json >foreign.json 2>foreign.log || true
[ "$(json foreign.json joined)" = 0 ] || fail "a foreign token joined: $(cat foreign.json)"
if "$bin/rewind-bots" --websocket "ws://127.0.0.1:$ws_port/matches/nosuch" --bots 1 \
  --duration 5 >nosuch.json 2>nosuch.log; then
  fail "a bot joined a match that does not exist"
fi
grep -q "handshake" nosuch.log || fail "unknown match: $(cat nosuch.log)"
answer=$(python3 - "$ws_port" <<'EOF'
import socket, sys
s = socket.create_connection(("127.0.0.1", int(sys.argv[1])), timeout=5)
s.sendall(b"GET /matches/m HTTP/1.1\r\nHost: x\r\n\r\n")
print(s.recv(4096).split(b"\r\n")[0].decode())
EOF
)
[[ $answer == "HTTP/1.1 426"* ]] || fail "a plain request got '$answer'"
"$bin/rewind-bots" --connect "127.0.0.1:$port" --bots 2 --token-file udp.tokens "${common[@]}" \
  >udp.json 2>udp.log &
pids+=($!)
udp_bots=$!
"$bin/rewind-bots" --websocket "$url" --bots 2 --token-file ws.tokens "${common[@]}" \
  >ws.json 2>ws.log || fail "the WebSocket bots failed: $(tail -5 ws.log)"
wait "$udp_bots" || fail "the UDP bots failed: $(tail -5 udp.log)"
wait "$server_pid" || fail "server exit: $(tail -5 server.log)"

for side in udp ws; do
  [ "$(json $side.json finished)" = 2 ] || fail "$side bots: $(cat $side.json)"
  [ "$(json $side.json desyncs)" = 0 ] || fail "$side bots desynced: $(cat $side.json)"
done
grep -q "player [23] joined from 100::" server.log || fail "no player came over WebSocket"
[ "$(json server.json players_joined)" = 4 ] || fail "joined: $(json server.json players_joined)"
[ "$(json server.json websocket_connections)" -ge 3 ] ||
  fail "connections: $(json server.json websocket_connections)"
"$bin/rewind-replay" verify match.rwr >verify.txt || fail "replay: $(cat verify.txt)"
udp_out=$(json server.json udp_bytes_out)
ws_out=$(json server.json websocket_bytes_out)
udp_in=$(json server.json udp_bytes_in)
ws_in=$(json server.json websocket_bytes_in)
[ "$ws_out" -gt 0 ] && [ "$udp_out" -gt 0 ] || fail "bytes: udp $udp_out ws $ws_out"
echo "websocket: $ticks ticks, 2 UDP + 2 WebSocket players, 0 desyncs, replay verified;" \
  "bytes out per player: UDP $(( udp_out / 2 )), WebSocket $(( ws_out / 2 ));" \
  "in: UDP $(( udp_in / 2 )), WebSocket $(( ws_in / 2 ))"
echo "PASS [websocket]"
