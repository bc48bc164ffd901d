#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# A game of one's own in the browser, from the installed package: the build
# is installed under a fresh prefix; examples/tag is built against it twice,
# natively (tag-server, tag-bots, tag-replay) and with Emscripten
# (examples/tag/browser: Rewind's client SDK module with tag registered,
# through share/rewind/wasm's RewindBrowserConfig.cmake); then tag-server
# hosts a secure match on --websocket, one page of headless Chromium plays
# it with tag's own module beside a native tag bot over UDP, both with 40 ms
# of latency and 3% loss: no desync, and the replay verifies.
#
# usage: run_browser_game.sh BUILD_DIR SOURCE_DIR SCRIPT_DIR WORK_DIR
#   SCRIPT_DIR  where browser_players.mjs and its node_modules are
set -euo pipefail
test_name=browser_game
build=$1 source=$2 scripts=$3 work=$4
chromium=${REWIND_CHROMIUM:-/usr/bin/chromium}
[ -x "$chromium" ] || { echo "FAIL [$test_name]: no Chromium at $chromium (Debian package chromium)" >&2; exit 1; }
source "$source/tests/integration/script_common.sh"
enter_work_dir "$work"
lap() { echo "[${SECONDS}s] $*"; }

prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >install.log || fail "cmake --install: $(tail -5 install.log)"
[ -f "$prefix/share/rewind/wasm/lib/cmake/RewindBrowser/RewindBrowserConfig.cmake" ] ||
  fail "the install has no share/rewind/wasm (see the build's wasm/wasm-deps.log)"
lap "installed under the prefix"

cmake -S "$source/examples/tag" -B tag -DCMAKE_PREFIX_PATH="$prefix" >tag.log 2>&1 &&
  cmake --build tag -j2 --target tag-server tag-bots tag-replay >>tag.log 2>&1 ||
  fail "building examples/tag: $(tail -20 tag.log)"
lap "built tag-server, tag-bots and tag-replay against the package"
NODE_PATH=/usr/share/nodejs emcmake cmake -S "$source/examples/tag/browser" -B tag-web \
  -DCMAKE_PREFIX_PATH="$prefix/share/rewind/wasm" -DCMAKE_BUILD_TYPE=Release >tag-web.log 2>&1 &&
  NODE_PATH=/usr/share/nodejs cmake --build tag-web >>tag-web.log 2>&1 ||
  fail "building examples/tag/browser: $(tail -20 tag-web.log)"
for f in rewind_client.js rewind-client.js rewind-client.d.ts package.json; do
  [ -s "tag-web/web/$f" ] || fail "the browser module's folder has no $f"
done
lap "built tag's browser module against share/rewind/wasm"

ticks=600
"$prefix/bin/rewind-token" keygen --out server.key >/dev/null
for slot in 0 1; do
  "$prefix/bin/rewind-token" mint --key-file server.key --match m --slot "$slot" \
    --client-id $((slot + 1)) >"token$slot"
done
tag/tag-server --game tag --bind 127.0.0.1 --port 0 --port-file port --players 2 \
  --ticks "$ticks" --replay match.rwr --join-timeout 60 --key-file server.key --match-id m \
  --websocket 127.0.0.1:0 --websocket-port-file ws.port --summary-json >server.json 2>server.log &
server_pid=$!
pids+=("$server_pid")
for _ in $(seq 1 100); do [ -s port ] && [ -s ws.port ] && break; sleep 0.1; done
[ -s ws.port ] || fail "tag-server did not start: $(cat server.log)"

cat >players.json <<JSON
{ "chromium": "$chromium", "clientDir": "$work/tag-web/web",
  "url": "ws://127.0.0.1:$(cat ws.port)/matches/m", "game": "tag", "tokens": ["$(cat token1)"],
  "faults": { "latencyMs": 40, "jitterMs": 10, "loss": 0.03 }, "timeoutS": 90,
  "out": "$work/pages.json" }
JSON
tag/tag-bots --connect "127.0.0.1:$(cat port)" --bots 1 --token-file token0 --game tag \
  --latency-ms 40 --jitter-ms 10 --loss 0.03 --duration 90 --summary-json >native.json 2>native.log &
native=$!
pids+=("$native")
(cd "$scripts" && node browser_players.mjs "$work/players.json") >pages.log 2>&1 ||
  fail "the browser player: $(tail -8 pages.log)"
cat pages.log
grep -q '"spec":"tag"' pages.json || fail "the page did not play tag's own input: $(cat pages.json)"
wait "$native" || fail "the native bot: $(tail -5 native.log)"
wait "$server_pid" || fail "tag-server exit: $(tail -5 server.log)"
[ "$(json native.json finished)" = 1 ] || fail "native bot: $(cat native.json)"
[ "$(json native.json desyncs)" = 0 ] || fail "the native bot desynced: $(cat native.json)"
[ "$(json server.json players_joined)" = 2 ] || fail "joined: $(cat server.json)"
[ "$(json server.json desync_reports)" = 0 ] || fail "desync reports: $(cat server.json)"
grep -q "joined from 100::" server.log || fail "no player over WebSocket: $(cat server.log)"
tag/tag-replay verify match.rwr >verify.txt || fail "replay: $(cat verify.txt)"
lap "hosted, played and verified"
echo "PASS [$test_name]: tag's own browser module and a native tag bot, $ticks ticks, 0 desyncs, replay verified"
