#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Builds Rewind and runs every test (unit, integration, determinism matrix,
# long, container) but the ones labelled `extended`: the five-minute
# real-time long match, left out so the run stays inside 30 minutes on 2
# cores (--label extended runs it).
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
# ctest --preset P --output-on-failure -j2.
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
if [[ $wasm == ON ]]; then bash scripts/setup.sh --wasm; else bash scripts/setup.sh; fi

jobs=$(nproc 2>/dev/null || echo 2)
step "configure + build (preset $preset, -j$jobs)"
cmake --preset "$preset" -DREWIND_TEST_WASM=$wasm
cmake --build --preset "$preset" -j"$jobs"

ctest_args=(--preset "$preset" --output-on-failure -j2 --no-tests=error)
if [[ -z $label ]]; then ctest_args+=(-LE extended); else ctest_args+=(-L "$label"); fi
step "ctest ${ctest_args[*]}"
status=0
ctest "${ctest_args[@]}" || status=$?
exit "$status"
