#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Builds the browser viewer and client SDK if they are not built yet
# (targets rewind_viewer and rewind_browser_client, one WebAssembly build,
# one at a time under LOCK: two browser tests may start together, and
# scripts/test.sh may be compiling it in the background), then runs the
# command. The browser tests start with it instead of depending on a fixture
# test: ctest starts a fixture's setup before everything else, which would
# compile the viewer in the foreground beside the unit tests.
#
# usage: with_viewer.sh LOCK BUILD_DIR COMMAND [ARGS...]
set -euo pipefail
lock=$1 build=$2
shift 2
flock "$lock" cmake --build "$build" --target rewind_viewer rewind_browser_client >"$lock.log" 2>&1 ||
  { echo "FAIL: building the viewer and client: $(tail -20 "$lock.log")" >&2; exit 1; }
exec "$@"
