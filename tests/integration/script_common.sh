# SPDX-License-Identifier: MIT
# Sourced by the integration scripts: a fresh work directory to run in,
# failing with the test's name, and one field of a --summary-json line.
#   test_name=...; source script_common.sh; enter_work_dir "$work"
# shellcheck shell=bash

enter_work_dir() {
  rm -rf "$1"
  mkdir -p "$1"
  cd "$1"
}

fail() { echo "FAIL [$test_name]: $*" >&2; exit 1; }

# json FILE FIELD: FIELD of the JSON object on FILE's last line.
json() {
  python3 -c "import json,sys; print(json.loads(open(sys.argv[1]).read().strip().splitlines()[-1])[sys.argv[2]])" "$1" "$2"
}

# Background processes the script starts (start_server, or pids+=(...)),
# killed when it exits.
pids=()
kill_started() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; }
trap kill_started EXIT

# log_has FILE PATTERN: whether FILE gets a line matching PATTERN (grep -E)
# within 15 s. The server writes its port files before its start-up lines,
# so a script that saw the port must still wait for the line.
log_has() {
  for _ in $(seq 1 150); do grep -qE -- "$2" "$1" 2>/dev/null && return 0; sleep 0.1; done
  return 1
}

# start_server ARGS...: rewind-server from $bin with ARGS (which include
# --port-file port) in the background, stdout to server.json and stderr to
# server.log; waits for the port it bound. Sets server_pid and port.
start_server() {
  "$bin/rewind-server" "$@" >server.json 2>server.log &
  server_pid=$!
  pids+=("$server_pid")
  for _ in $(seq 1 100); do [ -s port ] && break; sleep 0.1; done
  [ -s port ] || fail "server did not start: $(cat server.log)"
  port=$(cat port)
}
