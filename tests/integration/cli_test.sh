#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Every program answers --help (exit 0) and refuses unknown or malformed
# flags with a message naming the flag (exit 64).
#   cli_test.sh BIN_DIR
set -uo pipefail
bin=$1
failures=0
check() {  # expected_status expected_text program args...
  local want=$1 text=$2 prog=$3
  shift 3
  local out status
  out=$("$bin/$prog" "$@" 2>&1)
  status=$?
  if [ "$status" != "$want" ] || ! grep -qF -- "$text" <<<"$out"; then
    echo "FAIL: $prog $*: exit $status (want $want), output: $out"
    failures=$((failures + 1))
  fi
}
for prog in rewind-server rewind-bots rewind-replay; do
  check 0 "usage: $prog" "$prog" --help
done
check 64 "unknown flag --frobnicate" rewind-server --frobnicate
check 64 "unknown flag --frobnicate" rewind-bots --frobnicate
check 64 "unknown command '--frobnicate'" rewind-replay --frobnicate
check 64 "unknown flag --frobnicate" rewind-replay verify x.rwr --frobnicate
check 64 "--port: 70000 is outside [0, 65535]" rewind-server --port 70000
check 64 "--players: expected an integer, got 'four'" rewind-server --players four
check 64 "--window: missing value" rewind-server --window
check 64 "--tick-rate: 0 is outside [1, 1000]" rewind-server --tick-rate 0
check 64 "--tick-budget: 0 is outside [0.01, 1]" rewind-server --tick-budget 0
check 64 "--tick-budget: 1.5 is outside [0.01, 1]" rewind-server --tick-budget 1.5
check 1 "unknown game 'chess'" rewind-server --game chess --port 0
check 64 "--metrics-bind: expected HOST:PORT, got 'nowhere'" rewind-server --metrics-bind nowhere
check 64 "--metrics-port-file needs --metrics-bind" rewind-server --metrics-port-file x --port 0
check 1 "metrics: bad address 'nowhere.invalid'" rewind-server --metrics-bind nowhere.invalid:0 --bind 127.0.0.1 --port 0
check 1 "refusing to serve /metrics on 0.0.0.0 without --metrics-keys" rewind-server --metrics-bind 0.0.0.0:0 --bind 127.0.0.1 --port 0
check 1 "the control API needs --control-keys FILE" rewind-server --control --matches 0 --bind 127.0.0.1 --port 0
check 64 "--control-keys /nonexistent/keys: cannot read it" rewind-server --control --control-keys /nonexistent/keys
check 64 "--control-keys and --control-port-file need --control" rewind-server --control-keys x
check 64 "--control-bind: expected HOST:PORT" rewind-server --control --control-bind nowhere
check 64 "are required" rewind-token api-key --name a
check 64 "--http-tls-cert and --http-tls-key go together" rewind-server --http-tls-cert c.pem
check 1 "metrics: TLS certificate /nonexistent/c.pem" rewind-server --bind 127.0.0.1 --port 0 --metrics-bind 127.0.0.1:0 --http-tls-cert /nonexistent/c.pem --http-tls-key /nonexistent/k.pem
check 1 "match id '..' must be a name" rewind-server --match-id .. --bind 127.0.0.1 --port 0
check 1 '"level":"error","msg":"unknown game' rewind-server --game chess --port 0 --log-json
check 64 "--agones-health-period: 0 is outside [0.1, 60]" rewind-server --agones --agones-health-period 0
AGONES_SDK_HTTP_PORT=x check 64 "AGONES_SDK_HTTP_PORT='x' is not a port number" rewind-server --agones
check 64 "--loss: 1.5 is outside [0, 1]" rewind-bots --loss 1.5
check 64 "--connect: expected HOST:PORT" rewind-bots --connect nowhere
check 64 "--script: expected game, random, circle or idle" rewind-bots --script dance
check 64 "--game: no game named 'chess' in this program" rewind-bots --game chess
check 64 "--corrupt-bot and --corrupt-at-tick go together" rewind-bots --corrupt-bot 1
check 64 "usage" rewind-replay
check 2 "" rewind-replay verify /nonexistent/file.rwr
check 0 "keygen" rewind-token --help
check 64 "unknown command 'frobnicate'" rewind-token frobnicate
check 64 "--slot: 99 is outside [0, 63]" rewind-token mint --slot 99
check 64 "are required" rewind-token mint --match m
check 1 "cannot read /nonexistent/key" rewind-token mint --key-file /nonexistent/key --match m --slot 0 --client-id 1
check 64 "--key-file /nonexistent/key: cannot read it" rewind-server --key-file /nonexistent/key --port 0
check 64 "--live-bind: expected HOST:PORT, got 'nowhere'" rewind-server --live-bind nowhere
check 64 "--live-port-file needs --live-bind" rewind-server --live-port-file x --port 0
check 64 "--live-delay-ticks: 40000 is outside [0, 36000]" rewind-server --live-delay-ticks 40000
check 1 "live: the viewer is not built in '/nonexistent/viewer'" rewind-server --bind 127.0.0.1 --port 0 --live-bind 127.0.0.1:0 --live-viewer-dir /nonexistent/viewer
check 1 "live: bad address 'nowhere.invalid'" rewind-server --bind 127.0.0.1 --port 0 --live-bind nowhere.invalid:0
check 0 "usage: rewind-synctest" rewind-synctest --help
check 0 "synctest arena: deterministic: 120 ticks of 3 players" rewind-synctest --game arena --players 3 --ticks 120
check 64 "unknown game 'chess'" rewind-synctest --game chess
check 64 "--check-distance: 0 is outside [1, 64]" rewind-synctest --check-distance 0
# Tokenless only on loopback, unless the operator says otherwise; the
# refusal says how to run secure (also before an Agones GameServer is Ready).
check 1 "refusing to run tokenless on 0.0.0.0" rewind-server --port 0
check 1 "rewind-token keygen --out server.key" rewind-server --bind :: --port 0
check 1 "refusing to run tokenless on 0.0.0.0" rewind-server --agones --port 0
check 2 "TOKENLESS on loopback" rewind-server --bind 127.0.0.1 --port 0 --join-timeout 0.1
check 2 "INSECURE: tokenless on 0.0.0.0" rewind-server --port 0 --join-timeout 0.1 \
  --insecure-tokenless-on-public-address
check 64 "connect token 0: not a hex digit" rewind-bots --token nothex
check 64 "connect token 0: a connect token is" rewind-bots --token 00ff
check 64 "--bots and --spectators are both 0" rewind-bots --bots 0
check 64 "1 connect tokens for 4 clients" rewind-bots --bots 4 --token "$("$bin/rewind-token" mint --key-file <(echo 0000000000000000000000000000000000000000000000000000000000000000) --match m --slot 0 --client-id 1)"
[ "$failures" = 0 ] && echo "PASS: cli" || exit 1
