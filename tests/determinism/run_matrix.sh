#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Determinism matrix: builds det_checksums.cpp together with every source of
# the core and the engine (core/src/*.cpp, sim/src/**/*.cpp), the game seam
# (sim/game/src/*.cpp) and the fixed-point library with its golden digest (sim/fixed/src/*.cpp,
# tests/unit/fixed/golden_digest.cpp) and the 2D lane (sim/d2/src/*.cpp,
# with its engine scene tests/determinism/lane2d_scene.cpp)
# directly with each compiler -- no CMake, so no project flag can hide a
# difference -- runs every build and diffs its per-tick checksums against the
# g++ -O0 build.
#
#   gcc-O0         g++ -O0 -DREWIND_SCALAR_LANES    (the reference): the
#                  solver's four lanes as plain arrays instead of SSE2 or
#                  eight AVX lanes; every other build runs SIMD lanes (eight
#                  AVX where the machine has AVX, four NEON on aarch64), so
#                  comparing each with it proves neither the instruction set
#                  nor the lane count changes a result
#   gcc-O3-native  g++ -O3 -march=native
#   clang-O3       clang++ -O3
#   aarch64-O3     aarch64-linux-gnu-g++ -O3 -static, run under qemu-aarch64
#   wasm-O0, wasm-O3, wasm-O3-simd128
#                  em++ (Emscripten) -O0, -O3, and -O3 with WebAssembly SIMD
#                  (-msimd128 -msse2: the SSE2 lanes as wasm SIMD); run under
#                  node; only with --wasm (each takes minutes to compile);
#                  with --chromium each also in headless Chromium
#                  (wasm-O0-chromium, ...: the same file in a browser page)
#
# Usage: run_matrix.sh [--source DIR] [--ticks N] [--jobs N] [--wasm] [--chromium DIR]
#                      [--builds NAMES] [--compile-only] BUILD_DIR
#   --source DIR  repository root (default: two levels above this script)
#   --ticks N     ticks to simulate (default 600)
#   --jobs N      parallel compile jobs (default 2, at most 2)
#   --wasm        add the WebAssembly builds
#   --chromium DIR  also run every WebAssembly build in headless Chromium
#                 (DIR holds tests/browser's run_in_chromium.mjs and its
#                 node_modules: the build's tests/browser after browser_npm)
#   --builds NAMES  only these builds (comma-separated), besides the
#                 reference gcc-O0 that every other is compared with
#   --compile-only  compile the builds and stop (scripts/test.sh compiles
#                 the matrix this way while the real-time tests leave the
#                 CPU idle, so the matrix test then finds its objects built)
#   BUILD_DIR     where objects, binaries and outputs go (reused between runs:
#                 objects are rebuilt only when a source or header changed;
#                 runs on one directory take turns, through a lock in it)
#
# Exit codes: 0 every build printed identical checksums; 1 a build differs,
# failed to compile or failed to run; 2 bad usage or a missing toolchain.
set -euo pipefail

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
source_dir=$(cd "$script_dir/../.." && pwd -P)
ticks=600
jobs=2
build_dir=""
wasm=0
chromium_dir=""
only=""
compile_only=0

usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }

while (($#)); do
  case "$1" in
    --source) source_dir=$(cd "${2:?--source needs a directory}" && pwd -P); shift 2 ;;
    --ticks) ticks=${2:?--ticks needs a number}; shift 2 ;;
    --jobs) jobs=${2:?--jobs needs a number}; shift 2 ;;
    --wasm) wasm=1; shift ;;
    --chromium) chromium_dir=$(cd "${2:?--chromium needs a directory}" && pwd -P); shift 2 ;;
    --builds) only=${2:?--builds needs a list of build names}; shift 2 ;;
    --compile-only) compile_only=1; shift ;;
    -h|--help) usage; exit 0 ;;
    -*) echo "run_matrix: unknown option '$1'" >&2; usage >&2; exit 2 ;;
    *) [[ -z $build_dir ]] || { echo "run_matrix: one BUILD_DIR only" >&2; exit 2; }
       build_dir=$1; shift ;;
  esac
done
[[ -n $build_dir ]] || { echo "run_matrix: BUILD_DIR is required" >&2; usage >&2; exit 2; }
[[ $ticks =~ ^[1-9][0-9]*$ ]] || { echo "run_matrix: --ticks must be a positive integer" >&2; exit 2; }
[[ $jobs =~ ^[1-9][0-9]*$ ]] || { echo "run_matrix: --jobs must be a positive integer" >&2; exit 2; }
((jobs <= 2)) || jobs=2   # the machines this runs on have 2 cores, shared

# --- toolchains: a missing one is a failure, never a skip -------------------
missing=0
need() {  # need COMMAND DEBIAN-PACKAGE
  if ! command -v "$1" >/dev/null 2>&1; then
    echo "run_matrix: FAIL: '$1' not found; install the Debian package '$2'" \
         "(sudo bash scripts/setup.sh installs everything)" >&2
    missing=1
  fi
}
need g++ g++
need clang++ clang
need aarch64-linux-gnu-g++ g++-aarch64-linux-gnu
need qemu-aarch64 qemu-user
need ninja ninja-build
need flock util-linux
if ((wasm)); then
  need em++ emscripten
  need node nodejs
  # Emscripten's JavaScript tools need Debian's node modules (acorn), which
  # a node not from Debian does not look for by itself.
  export NODE_PATH="/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}"
fi
[[ -f /usr/include/xxhash.h ]] || {
  echo "run_matrix: FAIL: /usr/include/xxhash.h not found; install the Debian package 'libxxhash-dev'" >&2
  missing=1
}
((missing == 0)) || exit 2

# --- sources ------------------------------------------------------------------
cd "$source_dir"
mapfile -t sim_sources < <(find core/src sim/src -name '*.cpp' -type f 2>/dev/null | LC_ALL=C sort)
mapfile -t game_sources < <(find sim/game/src -maxdepth 1 -name '*.cpp' -type f 2>/dev/null | LC_ALL=C sort)
if ((${#sim_sources[@]} == 0 || ${#game_sources[@]} == 0)); then
  echo "run_matrix: FAIL: no engine or game sources under $source_dir/sim/src and" \
       "$source_dir/sim/game/src" >&2
  exit 1
fi
mapfile -t fixed_sources < <(find sim/fixed/src -maxdepth 1 -name '*.cpp' -type f 2>/dev/null | LC_ALL=C sort)
fixed_sources+=(tests/unit/fixed/golden_digest.cpp)
mapfile -t sim2d_sources < <(find sim/d2/src -maxdepth 1 -name '*.cpp' -type f 2>/dev/null | LC_ALL=C sort)
det_source="$script_dir/det_checksums.cpp"
lane2d_source="$script_dir/lane2d_scene.cpp"
joints3d_source="$script_dir/joints3d_scene.cpp"
sources=("$det_source" "$lane2d_source" "$joints3d_source" "${sim_sources[@]/#/$source_dir/}" "${game_sources[@]/#/$source_dir/}"
  "${fixed_sources[@]/#/$source_dir/}" "${sim2d_sources[@]/#/$source_dir/}")

mkdir -p "$build_dir"
build_dir=$(cd "$build_dir" && pwd -P)
# One run at a time per directory: two ninjas on one build directory would
# corrupt its logs, and a run must not compare another run's outputs.
exec 9>"$build_dir/.run_matrix.lock"
flock 9

# The cross compiler does not search /usr/include (it holds the host's
# headers), so xxhash.h -- used header-only -- is offered through a directory
# that holds nothing else. Every build uses it, so all see the same header.
mkdir -p "$build_dir/include"
ln -sf /usr/include/xxhash.h "$build_dir/include/xxhash.h"

# The checkout may sit under any path: directories go into the compile
# command shell-quoted (%q), and into ninja's file with its own escapes.
printf -v src_q '%q' "$source_dir"
printf -v build_q '%q' "$build_dir"
common_flags="-std=c++20 -ffp-contract=off -fno-fast-math -I$src_q/core/include"
common_flags+=" -I$src_q/sim/include"
common_flags+=" -I$src_q/sim/src -I$src_q/sim/game/include -I$src_q/sim/game/src"
common_flags+=" -I$src_q/sim/fixed/include -I$src_q/tests/unit/fixed"
common_flags+=" -I$src_q/sim/d2/include -I$src_q/sim/d2/src"
common_flags+=" -isystem $build_q/include"
# A path in a ninja build line: '$', ' ' and ':' escaped with '$'.
ninja_path() {
  local p=${1//\$/\$\$}
  p=${p// /\$ }
  printf '%s' "${p//:/\$:}"
}
# -fexcess-precision=standard keeps float math in float where x87 exists. GCC
# accepts it for C++ only from GCC 13 on; GCC 12 (Debian 12) refuses it, and
# there x86-64 (SSE) and aarch64 have no excess precision to begin with
# (FLT_EVAL_METHOD == 0), so the flag is passed only where it is accepted.
gcc_flag_if_supported() {  # gcc_flag_if_supported COMPILER FLAG
  if echo 'int main() { return 0; }' | "$1" "$2" -x c++ -fsyntax-only - >/dev/null 2>&1; then
    printf '%s' "$2"
  fi
}
# -fno-tree-slp-vectorize: the same guard the CMake build puts on every GCC
# target (rewind_determinism in the top-level CMakeLists.txt): GCC 12's SLP
# vectorizer forms vfmsubadd on FMA targets despite -ffp-contract=off.
gcc_flags="-fno-tree-slp-vectorize $(gcc_flag_if_supported g++ -fexcess-precision=standard)"
cross_flags="-fno-tree-slp-vectorize $(gcc_flag_if_supported aarch64-linux-gnu-g++ -fexcess-precision=standard)"
gcc_flags=${gcc_flags% }
cross_flags=${cross_flags% }

# name | compiler | flags | link flags | runner
builds=(
  "gcc-O0|g++|-O0 -DREWIND_SCALAR_LANES${gcc_flags:+ $gcc_flags}||"
  "gcc-O3-native|g++|-O3 -march=native${gcc_flags:+ $gcc_flags}||"
  "clang-O3|clang++|-O3||"
  "aarch64-O3|aarch64-linux-gnu-g++|-O3${cross_flags:+ $cross_flags}|-static|qemu-aarch64"
)
# WebAssembly: one JavaScript file for node with the module inside it (a
# separate .wasm would be fetched, which node does not do for a path);
# memory grows as the worlds do.
# Three builds: unoptimized, optimized, and optimized with WebAssembly's
# 128-bit SIMD, where -msse2 makes the solver's SSE2 lanes compile to wasm
# SIMD instructions (Emscripten's SSE headers): a third instruction set
# for the lanes, which must not change a result either.
# Built for the web and node alike, so --chromium runs the same file in a
# browser.
wasm_link="-sALLOW_MEMORY_GROWTH=1 -sTOTAL_STACK=8MB -sENVIRONMENT=web,node -sSINGLE_FILE=1"
((wasm)) && builds+=("wasm-O0|em++|-O0|$wasm_link|node"
                     "wasm-O3|em++|-O3|$wasm_link|node"
                     "wasm-O3-simd128|em++|-O3 -msimd128 -msse2|$wasm_link|node")
if [[ -n $only ]]; then
  kept=()
  for entry in "${builds[@]}"; do
    name=${entry%%|*}
    if [[ $name == gcc-O0 || ",$only," == *",$name,"* ]]; then kept+=("$entry"); fi
  done
  for name in ${only//,/ }; do
    printf '%s\n' "${kept[@]}" | grep -q "^$name|" || {
      echo "run_matrix: unknown build '$name' in --builds (wasm-* builds need --wasm)" >&2; exit 2; }
  done
  builds=("${kept[@]}")
fi
# --chromium: each WebAssembly build runs a second time, in headless
# Chromium (an entry that compiles nothing and runs that build's file).
if [[ -n $chromium_dir ]]; then
  for entry in "${builds[@]}"; do
    IFS='|' read -r name cxx flags ldflags _runner <<<"$entry"
    if [[ $name == wasm-* ]]; then builds+=("$name-chromium|$cxx|$flags|$ldflags|chromium|$name"); fi
  done
fi

# --- compile: one generated ninja file; it reuses objects whose inputs are
# unchanged (depfiles track headers) and runs at most $jobs compilers --------
ninja_file="$build_dir/build.ninja"
{
  echo "# Generated by tests/determinism/run_matrix.sh; do not edit."
  echo "ninja_required_version = 1.10"
  echo "common = ${common_flags//\$/\$\$}"
  for entry in "${builds[@]}"; do
    IFS='|' read -r name cxx flags ldflags _runner of <<<"$entry"
    [[ -z $of ]] || continue  # runs another build's program
    echo
    echo "rule cxx_$name"
    echo "  command = $cxx \$common $flags -MD -MF \$out.d -c \$in -o \$out"
    echo "  depfile = \$out.d"
    echo "  deps = gcc"
    echo "  description = $name: \$in"
    echo "rule link_$name"
    echo "  command = $cxx $flags \$in -o \$out $ldflags"
    echo "  description = $name: link \$out"
    objects=()
    for src in "${sources[@]}"; do
      rel=${src#"$source_dir"/}
      [[ $src == "$det_source" ]] && rel=det_checksums.cpp
      [[ $src == "$lane2d_source" ]] && rel=lane2d_scene.cpp
      [[ $src == "$joints3d_source" ]] && rel=joints3d_scene.cpp
      obj="$name/obj/${rel//\//__}.o"
      objects+=("$obj")
      echo "build $obj: cxx_$name $(ninja_path "$src")"
    done
    echo "build $name/det_checksums: link_$name ${objects[*]}"
  done
} >"$ninja_file.tmp"
# Only replace the file when it changed, so ninja's own bookkeeping stays valid.
if ! cmp -s "$ninja_file.tmp" "$ninja_file" 2>/dev/null; then
  mv "$ninja_file.tmp" "$ninja_file"
else
  rm -f "$ninja_file.tmp"
fi

echo "run_matrix: ${#sources[@]} sources x ${#builds[@]} builds, $ticks ticks, $jobs compile jobs"
echo "run_matrix: build directory $build_dir"
t_start=$SECONDS
if ! ninja -C "$build_dir" -j "$jobs"; then
  echo "run_matrix: FAIL: a build of the matrix did not compile (see above)" >&2
  exit 1
fi
t_compiled=$SECONDS
if ((compile_only)); then
  echo "run_matrix: compiled in $((t_compiled - t_start))s (--compile-only: nothing run)"
  exit 0
fi

# --- run: every build, at most 2 at a time -----------------------------------
run_one() {  # run_one NAME RUNNER [BUILD whose program it runs]
  local name=$1 runner=$2 program="$build_dir/${3:-$1}/det_checksums"
  local out="$build_dir/$1.out" err="$build_dir/$1.err" start=$SECONDS rc=0
  if [[ $runner == chromium ]]; then
    node "$chromium_dir/run_in_chromium.mjs" "$program" "$ticks" >"$out" 2>"$err" || rc=$?
  elif [[ -n $runner ]]; then
    "$runner" "$program" "$ticks" >"$out" 2>"$err" || rc=$?
  else
    "$program" "$ticks" >"$out" 2>"$err" || rc=$?
  fi
  echo "$rc $((SECONDS - start))" >"$build_dir/$name.status"
}
running=0
for entry in "${builds[@]}"; do
  IFS='|' read -r name _cxx _flags _ldflags runner of <<<"$entry"
  rm -f "$build_dir/$name.out" "$build_dir/$name.err" "$build_dir/$name.status"
  run_one "$name" "$runner" "$of" &
  running=$((running + 1))
  if ((running >= 2)); then
    wait -n || true
    running=$((running - 1))
  fi
done
wait || true
t_ran=$SECONDS

# --- compare -------------------------------------------------------------------
reference=gcc-O0
ref_out="$build_dir/$reference.out"
failed=0
rows=()
for entry in "${builds[@]}"; do
  IFS='|' read -r name cxx flags ldflags runner _of <<<"$entry"
  out="$build_dir/$name.out"
  read -r rc secs <"$build_dir/$name.status" || { rc=255; secs=0; }
  lines=$(grep -c -E '^-?[0-9]+ [0-9a-f]{16}$' "$out" || true)
  last=$(tail -n 1 "$out" 2>/dev/null || true)
  final_sum=${last#* }
  [[ $last =~ ^-?[0-9]+\ [0-9a-f]{16}$ ]] || final_sum="-"
  verdict=ok
  if [[ $rc != 0 ]]; then
    verdict="EXIT $rc"
    failed=1
    echo "run_matrix: $name exited with status $rc; last lines of its output and stderr:"
    tail -n 3 "$out" || true
    tail -n 10 "$build_dir/$name.err" || true
  elif [[ $lines != "$ticks" ]]; then
    verdict="$lines/$ticks ticks"
    failed=1
    echo "run_matrix: $name printed $lines checksum lines, expected $ticks"
  fi
  if [[ $name != "$reference" ]] && ! cmp -s "$ref_out" "$out"; then
    [[ $verdict == ok ]] && verdict=DIFFERS
    failed=1
    # First differing line: its tick and both checksums.
    awk -v ref="$reference" -v cur="$name" '
      FILENAME == ARGV[1] { a[FNR] = $0; na = FNR; next }
      { b[FNR] = $0; nb = FNR }
      END {
        na += 0; nb += 0
        n = (na > nb) ? na : nb
        for (i = 1; i <= n; ++i) {
          if (a[i] != b[i]) {
            split(a[i], x, " "); split(b[i], y, " ")
            tick = (x[1] != "") ? x[1] : y[1]
            printf "run_matrix: FIRST DIFFERENCE at tick %s (line %d)\n", tick, i
            printf "  %-14s %s\n", ref ":", (i <= na) ? a[i] : "<no line>"
            printf "  %-14s %s\n", cur ":", (i <= nb) ? b[i] : "<no line>"
            exit
          }
        }
      }' "$ref_out" "$out"
  fi
  rows+=("$(printf '%-14s %-22s %-36s %6s  %-16s  %5ss  %s' "$name" "$cxx" \
    "$flags${ldflags:+ $ldflags}" "$lines" "$final_sum" "$secs" "$verdict")")
done

echo
printf '%-14s %-22s %-36s %6s  %-16s  %6s  %s\n' build compiler flags ticks "final checksum" run result
printf '%s\n' "${rows[@]}"
echo
echo "run_matrix: compile $((t_compiled - t_start))s, run $((t_ran - t_compiled))s" \
     "(common flags: -std=c++20 -ffp-contract=off -fno-fast-math; GCC also -fno-tree-slp-vectorize)"
if ((failed)); then
  echo "run_matrix: FAIL: the builds do not agree with $reference (outputs in $build_dir/*.out)"
  exit 1
fi
echo "run_matrix: PASS: all ${#builds[@]} builds printed identical checksums for $ticks ticks"
