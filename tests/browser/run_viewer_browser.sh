#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# The viewer in headless Chromium on matches the server really hosted:
#   1. a 3D match (crates) where bot 1 corrupts its state after tick 100:
#      the server stores the client's desync report; the viewer must play
#      the replay with native checksums and open at the report with the
#      bodies the server's own report names highlighted;
#   2. a 2D match (arena) and a 3D vehicle match (joust): played back with
#      native checksums at every tick they are scrubbed to;
#   3. a crates match on a server with a live endpoint, watched while it
#      runs (during the cases above) by a page from its start and one that
#      joins midway, to its end.
# Screenshots of each go to SHOTS_DIR (the README shows copies).
#
# usage: run_viewer_browser.sh BIN_DIR VIEWER_DIR SCRIPT_DIR WORK_DIR SHOTS_DIR
#   BIN_DIR     rewind-server, rewind-bots, rewind-replay
#   VIEWER_DIR  the built viewer (the build's viewer_web)
#   SCRIPT_DIR  where viewer_browser.mjs and its node_modules are
set -euo pipefail
test_name=viewer_browser
bin=$1 viewer=$2 scripts=$3 work=$4 shots=$5
chromium=${REWIND_CHROMIUM:-/usr/bin/chromium}
[ -x "$chromium" ] || { echo "FAIL [$test_name]: no Chromium at $chromium (Debian package chromium)" >&2; exit 1; }
source "$(dirname "${BASH_SOURCE[0]}")/../integration/script_common.sh"
enter_work_dir "$work"

# play GAME PLAYERS TICKS [bots flags...]: hosts one match, writes GAME.rwr.
# The bots exit 1 when one of them desynced, as the first match means to.
play() {
  local game=$1 players=$2 ticks=$3
  shift 3
  rm -f port
  "$bin/rewind-server" --game "$game" --bind 127.0.0.1 --port 0 --port-file port \
    --players "$players" --ticks "$ticks" --replay "$game.rwr" --desync-dir "desyncs_$game" \
    >"server_$game.log" 2>&1 &
  local server=$!
  pids+=("$server")
  for _ in $(seq 1 100); do [ -s port ] && break; sleep 0.1; done
  [ -s port ] || fail "server did not start: $(cat "server_$game.log")"
  local rc=0
  "$bin/rewind-bots" --bots "$players" --connect "localhost:$(cat port)" --game "$game" "$@" \
    >"bots_$game.log" 2>&1 || rc=$?
  if [ "$rc" != 0 ] && ! { [ "$rc" = 1 ] && grep -q "DESYNC" "bots_$game.log"; }; then
    fail "bots of $game exited $rc: $(tail -3 "bots_$game.log")"
  fi
  wait "$server" || fail "server of $game: $(tail -3 "server_$game.log")"
}

mkdir -p desyncs_crates desyncs_arena desyncs_joust
play crates 2 360 --corrupt-bot 1 --corrupt-at-tick 100
play arena 2 300
play joust 2 300
report=$(ls desyncs_crates/desync_p1_t*_r*.bin 2>/dev/null | head -1)
[ -n "$report" ] || fail "the server stored no desync report: $(tail -3 server_crates.log)"
# The bodies the server's report names ("  body N field: expected ...").
bodies=$(sed -n 's/^  body \([0-9]*\) .*/\1/p' "${report%.bin}.txt" | sort -n | uniq | paste -sd, -)
[ -n "$bodies" ] || fail "the server's report names no body: $(cat "${report%.bin}.txt")"

# The live match: long enough to watch while the replays above are checked.
live_ticks=1500
rm -f live_port live_udp_port
"$bin/rewind-server" --game crates --bind 127.0.0.1 --port 0 --port-file live_udp_port \
  --players 2 --ticks "$live_ticks" --live-bind 127.0.0.1:0 --live-port-file live_port \
  --live-viewer-dir "$viewer" --live-keyframe-ticks 120 --join-timeout 120 \
  >server_live.log 2>&1 &
live_server=$!
pids+=("$live_server")
for _ in $(seq 1 100); do [ -s live_port ] && [ -s live_udp_port ] && break; sleep 0.1; done
[ -s live_port ] || fail "the live server did not start: $(cat server_live.log)"
"$bin/rewind-bots" --bots 2 --connect "localhost:$(cat live_udp_port)" --game crates \
  >bots_live.log 2>&1 &
live_bots=$!
pids+=("$live_bots")

# Written by python: the paths (the checkout's) may hold any character.
python3 - "$bin/rewind-replay" "$viewer" "$chromium" "$shots" "$PWD" "$report" "$bodies" \
  "$(cat live_port)" "$live_ticks" >config.json <<'PY'
import json, sys
tool, viewer, chromium, shots, here, report, bodies, live_port, live_ticks = sys.argv[1:]
print(json.dumps({
    "tool": tool, "viewerDir": viewer, "chromium": chromium, "shots": shots,
    "cases": [
        {"name": "viewer-desync", "file": here + "/crates.rwr", "desync": here + "/" + report,
         "expectBodies": [int(b) for b in bodies.split(",")], "expectGame": "crates"},
        {"name": "viewer-2d", "file": here + "/arena.rwr", "expectGame": "arena"},
        {"name": "viewer-3d", "file": here + "/joust.rwr", "expectGame": "joust"},
    ],
    "live": {"name": "viewer-live", "url": "http://127.0.0.1:" + live_port, "match": "match",
             "names": ["bot-0", "bot-1"], "ticks": int(live_ticks)},
}))
PY
node "$scripts/viewer_browser.mjs" config.json || fail "see above"
wait "$live_bots" || fail "the live match's bots: $(tail -3 bots_live.log)"
wait "$live_server" || fail "the live server: $(tail -3 server_live.log)"
echo "PASS [$test_name]"
