#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Builds Rewind and runs every test (unit, integration, determinism matrix,
# long, container, the browser viewer in headless Chromium) but the ones
# labelled `extended`: the five-minute real-time long match and the two-minute
# soak, left out so the run stays inside 30 minutes on 2 cores (--label
# extended runs them).
#
# Usage: scripts/test.sh [--debug] [--label LABEL]
#   --debug        use the ASan + UBSan preset (build/debug) instead of release
#   --label LABEL  run only the tests with this ctest label (e.g. determinism)
#                  --label wasm is the WebAssembly determinism check, which
#                  the full run leaves out (it compiles the engine with
#                  Emscripten, several minutes): it installs emscripten and
#                  node, and configures with -DREWIND_TEST_WASM=ON
#
# Steps: scripts/setup.sh (installs system packages only when some are
# missing), cmake --preset P, cmake --build --preset P, then
# ctest --preset P --output-on-failure -j2. A full run also starts compiling
# the determinism matrix in the background at idle priority when ctest
# starts: the real-time integration tests run alone and leave most of the
# CPU idle, and the matrix test, which ctest runs last, then finds its
# objects built (its log: build/P/matrix-prebuild.log); beside it, the
# WebAssembly build of the browser viewer and client SDK (wasm/), which the
# browser tests, also run last, find done (log: build/P/wasm-prebuild.log).
# Exit codes: ctest's status; the failing step's status if setup, configure or
# build fails; 2 on bad usage.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

preset=release
label=""
usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
while (($#)); do
  case "$1" in
    --debug) preset=debug; shift ;;
    --label) label=${2:-}; [[ -n $label ]] || { echo "test: --label needs a value" >&2; exit 2; }; shift 2 ;;
    --label=*) label=${1#--label=}; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "test: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
done

step() { echo; echo "==> $*"; }

wasm=OFF
[[ $label != wasm ]] || wasm=ON
step "system packages"
if [[ $wasm == ON ]]; then bash scripts/setup.sh --wasm --viewer; else bash scripts/setup.sh --viewer; fi

jobs=$(nproc 2>/dev/null || echo 2)
step "configure + build (preset $preset, -j$jobs)"
# The viewer's WebAssembly build is a test fixture (viewer_build) and is
# compiled in the background while the real-time tests leave the CPU idle.
cmake --preset "$preset" -DREWIND_TEST_WASM=$wasm -DREWIND_BUILD_VIEWER=ON
cmake --build --preset "$preset" -j"$jobs"

ctest_args=(--preset "$preset" --output-on-failure -j2 --no-tests=error)
if [[ -z $label ]]; then ctest_args+=(-LE extended); else ctest_args+=(-L "$label"); fi
prebuilds=()
if [[ -z $label ]]; then
  # Idle priority: the compile takes only what the tests leave. setsid makes
  # it a process group, so ninja and its compilers go with it on exit.
  idle=()
  if chrt --idle 0 true 2>/dev/null; then idle=(chrt --idle 0); fi
  # The browser viewer's and client's WebAssembly build too, with the
  # commands and the lock of its external project (cmake/RewindBrowser.cmake):
  # the browser tests, which ctest runs last, then find it built.
  wasm_dir="build/$preset/wasm"
  setsid "${idle[@]}" nice -n 19 bash tests/determinism/run_matrix.sh --compile-only --source . \
    "build/$preset/tests/determinism/matrix" >"build/$preset/matrix-prebuild.log" 2>&1 &
  prebuilds=($!)
  # Beside it, not after it: the matrix takes most of the run, and the
  # browser tests would otherwise compile the viewer themselves, alone.
  setsid "${idle[@]}" nice -n 19 bash -c '
    flock "$1.lock" env NODE_PATH=/usr/share/nodejs bash wasm/configure.sh "$PWD" "$1" "$2" &&
      flock "$1.lock" env NODE_PATH=/usr/share/nodejs cmake --build "$1"' prebuild \
    "$wasm_dir" "build/$preset/wasm-deps" >"build/$preset/wasm-prebuild.log" 2>&1 &
  prebuilds+=($!)
  trap 'for pid in "${prebuilds[@]}"; do kill -- -"$pid" 2>/dev/null || true; done' EXIT
fi
step "ctest ${ctest_args[*]}"
status=0
ctest "${ctest_args[@]}" || status=$?
exit "$status"
