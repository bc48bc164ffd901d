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
