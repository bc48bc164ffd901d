#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Hosts one short tag match, plays it with two bots and verifies its replay.
# Usage: play_match.sh TAG_SERVER TAG_BOTS TAG_REPLAY
set -euo pipefail
server=$1 bots=$2 replay=$3
dir=$(mktemp -d)
trap 'kill "$pid" 2>/dev/null || true; rm -rf "$dir"' EXIT

"$server" --game tag --players 2 --ticks 600 --bind 127.0.0.1 --port 0 \
  --port-file "$dir/port" --replay "$dir/match.rwr" 2>"$dir/server.log" &
pid=$!
for _ in $(seq 200); do [ -s "$dir/port" ] && break; sleep 0.05; done
[ -s "$dir/port" ] || { cat "$dir/server.log"; echo "tag-server did not start"; exit 1; }

"$bots" --game tag --bots 2 --connect "127.0.0.1:$(head -1 "$dir/port")" --summary-json
wait "$pid" || { cat "$dir/server.log"; echo "tag-server failed"; exit 1; }
"$replay" verify "$dir/match.rwr"
# A forged input, edited by the name of one of tag's own input fields: the
# replay still reads, and re-simulation catches it.
"$replay" tamper "$dir/match.rwr" --tick 300 --player 1 --set heading=900,sprint=1 \
  --out "$dir/forged.rwr"
status=0
"$replay" verify "$dir/forged.rwr" >"$dir/forged.txt" || status=$?
[ "$status" -eq 1 ] || { cat "$dir/forged.txt"; echo "the forged replay was not caught"; exit 1; }
echo "the forged replay diverges: $(grep -m1 DIVERGED "$dir/forged.txt")"
