#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Usage: package_test.sh BUILD_DIR SOURCE_DIR
# Installs the build under a fresh prefix and uses it the way a game
# developer would; prints what it checked and how long each part took.
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
fail() { echo "FAIL: $*" >&2; exit 1; }
lap() { echo "[$((SECONDS))s] $*"; }

cmake --install "$build" --prefix "$prefix" >"$work/install.log" || {
  cat "$work/install.log"; fail "cmake --install"; }
lap "installed under the prefix"
for f in include/rewind/core/status.h include/rewind/sim/world3d.h include/rewind/game/game.h \
         include/rewind/server/server_main.h include/rewind/client/client_session.h \
         include/rewind/version.h lib/librewind_core.a lib/librewind_server_core.a \
         lib/cmake/Rewind/RewindConfig.cmake lib/cmake/Rewind/RewindTargets.cmake \
         lib/pkgconfig/rewind.pc lib/pkgconfig/rewind-engine.pc \
         bin/rewind-server bin/rewind-bots bin/rewind-replay bin/rewind-token bin/rewind-synctest; do
  [ -e "$prefix/$f" ] || fail "the install has no $f"
done
if grep -rq -- "$source\|$build" "$prefix/lib/cmake" "$prefix/lib/pkgconfig"; then
  grep -rn -- "$source\|$build" "$prefix/lib/cmake" "$prefix/lib/pkgconfig" | head -5
  fail "the installed package names the source or build tree"
fi

# Every public header compiles on its own with nothing but the prefix's
# include directory (and the system's, for the dependencies). The protobuf
# messages (rewind/v1/*.pb.h) are protoc's output, not written by hand.
find "$prefix/include" -name '*.h' ! -name '*.pb.h' | LC_ALL=C sort >"$work/headers"
headers=$(wc -l <"$work/headers")
(( headers > 100 )) || fail "only $headers headers installed"
# shellcheck disable=SC2016
xargs -P "$(nproc)" -I{} sh -c 'printf "#include \"%s\"\n" "$1" |
  c++ -std=c++20 -fsyntax-only -Wall -Wextra -Werror -I"$2/include" -x c++ - 2>&1 ||
  echo "FAILED: $1"' _ {} "$prefix" <"$work/headers" >"$work/headers.log"
if grep -q '^FAILED' "$work/headers.log"; then
  head -40 "$work/headers.log"; fail "a public header does not compile on its own"
fi
lap "$headers public headers compile on their own"

# The example with CMake, exactly as its README says.
example=$work/tag
cp -r "$source/examples/tag" "$example"
cmake -S "$example" -B "$example/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  >"$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "configuring the example"; }
cmake --build "$example/build" -j"$(nproc)" >"$work/build.log" 2>&1 ||
  { tail -40 "$work/build.log"; fail "building the example"; }
lap "examples/tag built against the installed package"
ctest --test-dir "$example/build" --output-on-failure || fail "the example's tests"
lap "the example's tests passed"

# The engine alone through pkg-config, for builds without CMake.
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
# shellcheck disable=SC2046
c++ -O1 $(pkg-config --cflags rewind-engine) -o "$work/tag_test_pc" "$example/tag_game.cpp" \
  "$example/tag_test.cpp" $(pkg-config --libs rewind-engine) || fail "building with pkg-config"
"$work/tag_test_pc" || fail "the pkg-config build's tag_test"
pkg-config --exists --print-errors rewind || fail "pkg-config rewind"
lap "built and ran tag_test with pkg-config"

# The Debian package.
(cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/deb" >"$work/cpack.log" 2>&1) ||
  { cat "$work/cpack.log"; fail "cpack -G DEB"; }
deb=$(ls "$work"/deb/*.deb 2>/dev/null | head -1)
[ -n "$deb" ] || fail "cpack made no .deb"
dpkg-deb -c "$deb" >"$work/deb.list"
for f in ./usr/include/rewind/core/status.h ./usr/lib/cmake/Rewind/RewindConfig.cmake \
         ./usr/bin/rewind-server; do
  grep -q " $f\$" "$work/deb.list" || fail "the .deb has no $f"
done
lap "$(basename "$deb"): $(dpkg-deb -f "$deb" Package) $(dpkg-deb -f "$deb" Version), $(wc -l <"$work/deb.list") entries"
echo "package test: PASS"
