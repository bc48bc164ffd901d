#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Steps the large scenes of both lanes on one thread and on N threads
# (World3D/World2D::set_thread_pool) in the same run, every body awake, and
# writes docs/THREADS.md and the Threads section of docs/BENCHMARKS.md
# (scripts/charts_threads.py): each scene's time per step both ways and the
# speed-up, beside the checksum-identity the tests prove (the threads change
# how long a step takes, never its result). The raw rows go to
# docs/charts/threads3d.csv and threads2d.csv. scripts/charts.sh runs it.
#
# Usage: scripts/threads_bench.sh [--no-build] [--threads N]
#   --no-build    use the binaries already in build/bench
#   --threads N   the threaded runs' thread count (default 2, this
#                 machine's cores; 2 to 31)
#
# About 4 minutes on 2 cores. Exit codes: 0 done; 2 bad usage; otherwise
# the status of the failing step.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

build=1
threads=2
usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
while (($#)); do
  case "$1" in
    --no-build) build=0; shift ;;
    --threads)
      threads=${2:-}
      [[ $threads =~ ^[0-9]+$ ]] && ((threads >= 2 && threads <= 31)) ||
        { echo "threads_bench: --threads takes 2 to 31, not '${2:-}'" >&2; exit 2; }
      shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "threads_bench: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
done

step() { echo "==> $*" >&2; }

if ((build)); then
  step "configure + build (preset bench: rewind-scene-sweep, rewind-scene2d-sweep)"
  cmake --preset bench >/dev/null
  cmake --build --preset bench -j2 --target rewind-scene-sweep rewind-scene2d-sweep >&2
fi

out=docs/charts
mkdir -p "$out"
sweep=build/bench/bin/rewind-scene-sweep
sweep2d=build/bench/bin/rewind-scene2d-sweep

step "3D: piles on 1 and $threads threads"
{
  "$sweep" --mode defaults --engine rewind --no-sleep --threads "$threads" \
    --scene pile --size 2000
  for run in "mixed_pile 1000" "convex_pile 1000" "compound_pile 400" "mesh_pile 1000"; do
    read -r scene size <<<"$run"
    "$sweep" --mode defaults --engine rewind --no-sleep --threads "$threads" \
      --scene "$scene" --size "$size" | tail -n +2
  done
} >"$out/threads3d.csv.tmp"
mv "$out/threads3d.csv.tmp" "$out/threads3d.csv"

step "2D: the lane's scenes on 1 and $threads threads"
"$sweep2d" --engine rewind --threads "$threads" >"$out/threads2d.csv.tmp"
mv "$out/threads2d.csv.tmp" "$out/threads2d.csv"

step "docs/THREADS.md and the Threads section of docs/BENCHMARKS.md"
python3 scripts/charts_threads.py --csv3d "$out/threads3d.csv" --csv2d "$out/threads2d.csv" \
  --threads-doc docs/THREADS.md --doc docs/BENCHMARKS.md
cat docs/THREADS.md
