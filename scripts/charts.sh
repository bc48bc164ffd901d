#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Measures Rewind against Bullet on the scene catalogue and on the jointed
# scenes, and Rewind's 2D lane against Box2D 2.4 on the 2D scenes, and
# writes the charts and docs/BENCHMARKS.md from that one run.
#
# Usage: scripts/charts.sh [--quick] [--no-build] [--only 3d|2d|joints|threads]
#                          [--jolt DIR] [--box2d3 DIR]
#   (default)   full sweep: every scene size at default settings on both
#               engines, piles up to 8000 boxes, and at each scene's chart
#               size Rewind's substeps 4-16, relax 0-4, contact_hertz 15-60
#               and Bullet's iterations 5-40, steps per tick 1-4
#               (2D: every scene, and the substeps/iterations sweep of the
#               large pyramid and the small pyramids)
#               (joints: the pendulum, chain, bridge and grid at Rewind's
#               substeps 4/8/16 and Bullet's iterations 10/20/40)
#   --quick     piles up to 2000 boxes, substeps 4/6/8 and iterations 5/10/20
#               (2D: 60 timed ticks a scene instead of 180-600; joints: the
#               default settings only; no threads part unless --only threads)
#   --no-build  use the binaries already in build/bench
#   --only 3d   the 3D part alone (the 2D and joints sections are rebuilt
#               from the stored docs/charts/2d_sweep.csv and joints3d.csv)
#   --only 2d   the 2D part alone: rewind-scene2d-sweep, then
#               scripts/charts2d.py replaces the 2D section of the document
#   --only joints  the 3D joints part alone: rewind-joint-bench, then
#               scripts/charts_joints.py replaces the "3D joints" section
#   --only threads  the threads part alone: scripts/threads_bench.sh, the
#               large scenes of both lanes on 1 and 2 threads (about 4
#               minutes; docs/THREADS.md and the "Threads" section)
#   --jolt DIR  also run the 3D scenes on Jolt Physics, built from the Jolt
#               source tree DIR (optional, never fetched; the environment
#               variable REWIND_JOLT_DIR does the same): the 3D tables and
#               charts gain Jolt beside Bullet
#   --box2d3 DIR  also Box2D v3 in the 2D part, built from the source tree
#               DIR (v3.1; default: $REWIND_BOX2D3_DIR; never
#               fetched): cmake --preset bench -DREWIND_BOX2D3_DIR=DIR
#
# Steps: scripts/setup.sh (only installs what is missing), cmake --preset bench,
# build rewind-scene-sweep and rewind-scene2d-sweep, run them (progress on
# stderr), then scripts/charts.py writes docs/charts/*.csv, *.svg and
# docs/BENCHMARKS.md, and scripts/charts2d.py docs/charts/2d_* and the 2D
# section of docs/BENCHMARKS.md, and rewind-joint-bench with
# scripts/charts_joints.py docs/charts/joints3d_* and the "3D joints"
# section, and scripts/threads_bench.sh docs/THREADS.md and the "Threads"
# section. Exit codes: 0 done; 2 bad usage; otherwise the status
# of the failing step.
set -euo pipefail

caller_dir=$PWD  # a relative --jolt or --box2d3 DIR is the caller's
cd "$(dirname "${BASH_SOURCE[0]}")/.."

mode=full
build=1
only=all
jolt=${REWIND_JOLT_DIR:-}
box2d3=${REWIND_BOX2D3_DIR:-}
usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
while (($#)); do
  case "$1" in
    --quick) mode=quick; shift ;;
    --no-build) build=0; shift ;;
    --only)
      [[ ${2:-} == 3d || ${2:-} == 2d || ${2:-} == joints || ${2:-} == threads ]] ||
        { echo "charts: --only takes 3d, 2d, joints or threads" >&2; usage >&2; exit 2; }
      only=$2; shift 2 ;;
    --jolt)
      [[ -n ${2:-} ]] || { echo "charts: --jolt takes a Jolt Physics source tree" >&2; exit 2; }
      jolt=$2; shift 2 ;;
    --box2d3)
      [[ -n ${2:-} ]] || { echo "charts: --box2d3 takes a directory" >&2; usage >&2; exit 2; }
      box2d3=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "charts: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
done
if [[ -n $jolt ]]; then
  [[ $jolt == /* ]] || jolt=$caller_dir/$jolt
  [[ -f $jolt/Build/CMakeLists.txt ]] ||
    { echo "charts: $jolt is not a Jolt Physics source tree (no Build/CMakeLists.txt)" >&2; exit 2; }
  jolt=$(cd "$jolt" && pwd)
fi
run3d=1 run2d=1 runjoints=1 runthreads=1
[[ $only == 2d ]] && run3d=0 && runjoints=0 && runthreads=0
[[ $only == 3d ]] && run2d=0 && runjoints=0 && runthreads=0
[[ $only == joints ]] && run3d=0 && run2d=0 && runthreads=0
[[ $only == threads ]] && run3d=0 && run2d=0 && runjoints=0
# --quick keeps to seconds: the threads part (minutes) runs only when asked
# for, and its section is rebuilt from the stored CSVs.
[[ $mode == quick && $only != threads ]] && runthreads=0

step() { echo "==> $*" >&2; }

# Box2D v3 is an optional peer of the 2D part. Without it the cache entry is
# cleared, so that an earlier --box2d3 configure does not linger.
box2d3_args=(-DREWIND_BOX2D3_DIR=)
box2d3_version=
if [[ -n $box2d3 ]]; then
  [[ $box2d3 == /* ]] || box2d3=$caller_dir/$box2d3
  [[ -f $box2d3/include/box2d/box2d.h && -f $box2d3/src/world.c ]] ||
    { echo "charts: --box2d3 '$box2d3' is not a Box2D v3 source tree" >&2; exit 2; }
  box2d3=$(cd "$box2d3" && pwd)
  box2d3_args=(-DREWIND_BOX2D3_DIR="$box2d3")
  # "VERSION 3.1.1" in the project() call of its CMakeLists.txt.
  box2d3_version=$(sed -n 's/^[[:space:]]*VERSION[[:space:]]\{1,\}\([0-9][0-9.]*\)[[:space:]]*$/\1/p' \
    "$box2d3/CMakeLists.txt" | head -n 1)
fi

targets=()
((run3d)) && targets+=(rewind-scene-sweep)
((run2d)) && targets+=(rewind-scene2d-sweep rewind-rays2d)
((runjoints)) && targets+=(rewind-joint-bench)
((runthreads)) && targets+=(rewind-scene-sweep rewind-scene2d-sweep)
if ((build)); then
  step "system packages"
  bash scripts/setup.sh >&2
  step "configure + build (preset bench, ${targets[*]})"
  # Without a peer its cache entry is cleared, so that an earlier --jolt or
  # --box2d3 configure does not linger.
  jolt_cache=(-DREWIND_JOLT_DIR=)
  [[ -n $jolt ]] && jolt_cache=(-DREWIND_JOLT_DIR="$jolt")
  cmake --preset bench "${jolt_cache[@]}" "${box2d3_args[@]}" >/dev/null
  cmake --build --preset bench -j2 --target "${targets[@]}" >&2
fi

out=docs/charts
doc=docs/BENCHMARKS.md
mkdir -p "$out"

if ((run3d)); then
  sweep=build/bench/bin/rewind-scene-sweep
  # The 3D files only: the 2D ones (2d_*) and the joints ones (joints3d*)
  # belong to the parts below.
  find "$out" -maxdepth 1 -type f \( -name '*.csv' -o -name '*.dat' -o -name '*.svg' \) \
    ! -name '2d_*' ! -name 'joints3d*' ! -name 'threads*' -delete
  start=$(date +%s)

  # both: Rewind and Bullet; all: Jolt too (the binary refuses it when
  # built without Jolt).
  engines=(--engine both)
  [[ -n $jolt ]] && engines=(--engine all)
  step "sweep ($mode): every scene, ${engines[1]} engines"
  "$sweep" --mode "$mode" "${engines[@]}" >"$out/sweep.csv"

  pyramid_sizes=(--size 10 --size 20 --size 30)
  [[ $mode == full ]] && pyramid_sizes+=(--size 40)
  pile_sizes=(--size 250 --size 500 --size 1000 --size 2000)
  [[ $mode == full ]] && pile_sizes+=(--size 4000 --size 8000)
  step "stacks, pyramids, card houses, log cabins, hull stacks and piles with every body awake (the solver without sleeping)"
  "$sweep" --mode defaults "${engines[@]}" --no-sleep --scene pyramid "${pyramid_sizes[@]}" >"$out/awake.csv"
  "$sweep" --mode defaults "${engines[@]}" --no-sleep --scene stack | tail -n +2 >>"$out/awake.csv"
  "$sweep" --mode defaults "${engines[@]}" --no-sleep --scene card_house | tail -n +2 >>"$out/awake.csv"
  "$sweep" --mode defaults "${engines[@]}" --no-sleep --scene log_cabin | tail -n +2 >>"$out/awake.csv"
  "$sweep" --mode defaults "${engines[@]}" --no-sleep --scene hull_stack | tail -n +2 >>"$out/awake.csv"
  "$sweep" --mode defaults "${engines[@]}" --no-sleep --scene mixed_pile | tail -n +2 >>"$out/awake.csv"
  "$sweep" --mode defaults "${engines[@]}" --no-sleep --scene convex_pile | tail -n +2 >>"$out/awake.csv"
  "$sweep" --mode defaults "${engines[@]}" --no-sleep --scene mesh_pile | tail -n +2 >>"$out/awake.csv"
  "$sweep" --mode defaults "${engines[@]}" --no-sleep --scene field_boxes | tail -n +2 >>"$out/awake.csv"
  "$sweep" --mode defaults "${engines[@]}" --no-sleep --scene pile "${pile_sizes[@]}" | tail -n +2 >>"$out/awake.csv"

  "$sweep" --list >"$out/catalog.txt"
  seconds=$(( $(date +%s) - start ))

  step "charts and $doc"
  python3 scripts/charts.py --sweep "$out/sweep.csv" --awake "$out/awake.csv" \
    --catalog "$out/catalog.txt" --out "$out" --doc "$doc" --mode "$mode" \
    --seconds "$seconds"
  rm -f "$out/catalog.txt" "$out"/*.dat  # gnuplot input, rebuilt from the CSVs
  step "3D done in $(( $(date +%s) - start )) s"
fi

if ((run2d)); then
  sweep2d=build/bench/bin/rewind-scene2d-sweep
  rm -f "$out"/2d_*
  start=$(date +%s)
  ticks=()
  [[ $mode == quick ]] && ticks=(--ticks 60)
  step "2D sweep ($mode): large pyramid, pyramids, tumbler, joint grid, smash, rain on Rewind and Box2D 2.4${box2d3:+ and Box2D v3}"
  "$sweep2d" --sweep --scene large_pyramid "${ticks[@]}" >"$out/2d_sweep.csv"
  "$sweep2d" --sweep --scene pyramids "${ticks[@]}" | tail -n +2 >>"$out/2d_sweep.csv"
  "$sweep2d" --scene tumbler "${ticks[@]}" | tail -n +2 >>"$out/2d_sweep.csv"
  "$sweep2d" --scene joint_grid "${ticks[@]}" | tail -n +2 >>"$out/2d_sweep.csv"
  "$sweep2d" --scene smash "${ticks[@]}" | tail -n +2 >>"$out/2d_sweep.csv"
  "$sweep2d" --scene rain "${ticks[@]}" | tail -n +2 >>"$out/2d_sweep.csv"
  rays=100000
  [[ $mode == quick ]] && rays=20000
  build/bench/bin/rewind-rays2d "$rays" >"$out/2d_rays.csv"
  printf 'mode=%s\ndate=%s\nseconds=%s\n' "$mode" "$(date -u +%F)" \
    "$(( $(date +%s) - start ))" >"$out/2d_run.txt"
  # Its version names it in the document (the CSV says only "box2d3").
  [[ -n $box2d3_version ]] && printf 'box2d3=v%s\n' "$box2d3_version" >>"$out/2d_run.txt"
fi

if ((runjoints)); then
  rm -f "$out"/joints3d*
  start=$(date +%s)
  quick=()
  [[ $mode == quick ]] && quick=(--quick)
  step "3D joints ($mode): pendulum, chain, bridge, grid, ragdoll pile on Rewind and Bullet"
  build/bench/bin/rewind-joint-bench "${quick[@]}" >"$out/joints3d.csv"
  printf 'mode=%s\ndate=%s\nseconds=%s\n' "$mode" "$(date -u +%F)" \
    "$(( $(date +%s) - start ))" >"$out/joints3d_run.txt"
fi

if ((runthreads)); then
  step "threads: the large scenes of both lanes on 1 and 2 threads"
  bash scripts/threads_bench.sh --no-build >/dev/null
fi

# The 2D section: from this run's CSV, or from the stored one after a 3D-only
# run rewrote the document.
if [[ -f $out/2d_sweep.csv && -f $out/2d_run.txt ]]; then
  step "2D charts and the 2D section of $doc"
  python3 scripts/charts2d.py --csv "$out/2d_sweep.csv" --run "$out/2d_run.txt" --out "$out" \
    --doc "$doc" --rays "$out/2d_rays.csv"
fi
# The 3D joints section: from this run's CSV, or from the stored one after
# another part rewrote the document.
if [[ -f $out/joints3d.csv && -f $out/joints3d_run.txt ]]; then
  step "3D joints charts and the 3D joints section of $doc"
  python3 scripts/charts_joints.py --csv "$out/joints3d.csv" --run "$out/joints3d_run.txt" \
    --out "$out" --doc "$doc"
fi
# The Threads section: from this run's CSVs, or from the stored ones after
# another part rewrote the document.
if [[ -f $out/threads3d.csv && -f $out/threads2d.csv ]]; then
  step "the Threads section of $doc"
  python3 scripts/charts_threads.py --csv3d "$out/threads3d.csv" --csv2d "$out/threads2d.csv" \
    --threads-doc docs/THREADS.md --doc "$doc"
fi
step "done: $doc, $out/"
