#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Measures Rewind against Bullet on the scene catalogue and writes the
# charts and docs/BENCHMARKS.md from that one run.
#
# Usage: scripts/charts.sh [--quick] [--no-build]
#   (default)   full sweep: every scene size at default settings on both
#               engines, piles up to 8000 boxes, and at each scene's chart
#               size Rewind's substeps 1-16, relax 0-4, contact_hertz 15-60
#               and Bullet's iterations 5-40, steps per tick 1-4
#   --quick     piles up to 2000 boxes, substeps 2/4/8 and iterations 5/10/20
#   --no-build  use the binaries already in build/bench
#
# Steps: scripts/setup.sh (only installs what is missing), cmake --preset bench,
# build rewind-scene-sweep, run it (progress on stderr), then
# scripts/charts.py writes docs/charts/*.csv, *.dat, *.svg and
# docs/BENCHMARKS.md. Exit codes: 0 done; 2 bad usage; otherwise the status
# of the failing step.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

mode=full
build=1
usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
while (($#)); do
  case "$1" in
    --quick) mode=quick; shift ;;
    --no-build) build=0; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "charts: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
done

step() { echo "==> $*" >&2; }

if ((build)); then
  step "system packages"
  bash scripts/setup.sh >&2
  step "configure + build (preset bench, rewind-scene-sweep)"
  cmake --preset bench >/dev/null
  cmake --build --preset bench -j2 --target rewind-scene-sweep >&2
fi

sweep=build/bench/bin/rewind-scene-sweep
out=docs/charts
mkdir -p "$out"
rm -f "$out"/*.csv "$out"/*.dat "$out"/*.svg
start=$(date +%s)

step "sweep ($mode): every scene, both engines"
"$sweep" --mode "$mode" >"$out/sweep.csv"

pyramid_sizes=(--size 10 --size 20 --size 30)
[[ $mode == full ]] && pyramid_sizes+=(--size 40)
pile_sizes=(--size 250 --size 500 --size 1000 --size 2000)
[[ $mode == full ]] && pile_sizes+=(--size 4000 --size 8000)
step "stacks, pyramids, card houses, log cabins, hull stacks and piles with every body awake (the solver without sleeping)"
"$sweep" --mode defaults --no-sleep --scene pyramid "${pyramid_sizes[@]}" >"$out/awake.csv"
"$sweep" --mode defaults --no-sleep --scene stack | tail -n +2 >>"$out/awake.csv"
"$sweep" --mode defaults --no-sleep --scene card_house | tail -n +2 >>"$out/awake.csv"
"$sweep" --mode defaults --no-sleep --scene log_cabin | tail -n +2 >>"$out/awake.csv"
"$sweep" --mode defaults --no-sleep --scene hull_stack | tail -n +2 >>"$out/awake.csv"
"$sweep" --mode defaults --no-sleep --scene mixed_pile | tail -n +2 >>"$out/awake.csv"
"$sweep" --mode defaults --no-sleep --scene convex_pile | tail -n +2 >>"$out/awake.csv"
"$sweep" --mode defaults --no-sleep --scene mesh_pile | tail -n +2 >>"$out/awake.csv"
"$sweep" --mode defaults --no-sleep --scene field_boxes | tail -n +2 >>"$out/awake.csv"
"$sweep" --mode defaults --no-sleep --scene pile "${pile_sizes[@]}" | tail -n +2 >>"$out/awake.csv"

"$sweep" --list >"$out/catalog.txt"
seconds=$(( $(date +%s) - start ))

step "charts and docs/BENCHMARKS.md"
python3 scripts/charts.py --sweep "$out/sweep.csv" --awake "$out/awake.csv" \
  --catalog "$out/catalog.txt" --out "$out" --doc docs/BENCHMARKS.md --mode "$mode" \
  --seconds "$seconds"
rm -f "$out/catalog.txt" "$out"/*.dat  # gnuplot input, rebuilt from the CSVs
step "done in $(( $(date +%s) - start )) s: docs/BENCHMARKS.md, $out/"
