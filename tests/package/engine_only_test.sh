#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Usage: engine_only_test.sh SOURCE_DIR
# The engine configures and its core builds with the network and server
# components off while CMake is forbidden to find protobuf, Boost, OpenSSL
# or nlohmann-json; no network target exists in that build.
set -euo pipefail
source=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

no_deps=(-DCMAKE_DISABLE_FIND_PACKAGE_Protobuf=ON -DCMAKE_DISABLE_FIND_PACKAGE_Boost=ON
         -DCMAKE_DISABLE_FIND_PACKAGE_OpenSSL=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON
         -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON)
cmake -G Ninja -S "$source" -B "$work/engine" -DREWIND_WITH_NETWORK=OFF -DREWIND_WITH_SERVER=OFF \
  -DREWIND_BUILD_TESTS=OFF "${no_deps[@]}" >"$work/configure.log" 2>&1 ||
  { cat "$work/configure.log"; fail "the engine alone does not configure"; }
ninja -C "$work/engine" -t targets all >"$work/targets"
for t in rewind_core rewind_sim rewind_sim2d rewind_game rewind_view rewind-synctest; do
  grep -q "^$t:" "$work/targets" || fail "the engine-only build has no $t"
done
for t in rewind_proto rewind_transport rewind_secure rewind_client rewind_server_core rewind-server; do
  ! grep -q "^$t:" "$work/targets" || fail "the engine-only build has $t"
done
cmake --build "$work/engine" --target rewind_core >"$work/build.log" 2>&1 ||
  { cat "$work/build.log"; fail "rewind_core does not build alone"; }
echo "the engine alone configures without protobuf, libsodium, Asio, Boost or OpenSSL; rewind_core builds"

# Options that cannot go together are refused with a reason.
if cmake -S "$source" -B "$work/bad" -DREWIND_WITH_NETWORK=OFF -DREWIND_WITH_SERVER=OFF \
     >"$work/bad.log" 2>&1; then
  fail "tests without the network layers were accepted"
fi
grep -q "REWIND_BUILD_TESTS needs" "$work/bad.log" || { cat "$work/bad.log"; fail "no reason given"; }
if cmake -S "$source" -B "$work/bad2" -DREWIND_WITH_NETWORK=OFF -DREWIND_BUILD_TESTS=OFF \
     >"$work/bad2.log" 2>&1; then
  fail "the server without the network layers was accepted"
fi
grep -q "REWIND_WITH_SERVER needs REWIND_WITH_NETWORK" "$work/bad2.log" ||
  { cat "$work/bad2.log"; fail "no reason given"; }
echo "engine-only test: PASS"
