#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Configures wasm/ with Emscripten, after building the browser client's
# libraries (libsodium, protobuf-lite) from Debian's sources
# (scripts/wasm_deps.sh, quick when they are built). When those cannot be
# built (no archive reachable) the viewer alone is configured, and the log
# says why the client is missing.
#
# usage: wasm/configure.sh SOURCE_DIR BUILD_DIR DEPS_DIR
# Run under NODE_PATH=/usr/share/nodejs (Emscripten's tools need it).
set -euo pipefail
source_dir=$1 build_dir=$2 deps_dir=$3
mkdir -p "$build_dir"
deps=""
if bash "$source_dir/scripts/wasm_deps.sh" "$deps_dir" >"$build_dir/wasm-deps.log" 2>&1; then
  deps=$deps_dir
else
  echo "wasm: the browser client's libraries did not build (see $build_dir/wasm-deps.log):" \
    "configuring the viewer alone" >&2
fi
emcmake cmake -G Ninja -S "$source_dir/wasm" -B "$build_dir" -DREWIND_SOURCE_DIR="$source_dir" \
  -DCMAKE_BUILD_TYPE=Release -DREWIND_WASM_DEPS="$deps"
