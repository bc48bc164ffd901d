#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Runs the same det_checksums binary twice (two processes, so two address
# layouts) and requires byte-identical output: a checksum that depends on a
# pointer, uninitialized memory or hash-map order shows up here even before
# the cross-compiler matrix runs.
#
# Usage: compare_runs.sh DET_CHECKSUMS OUT_DIR [TICKS]
# Exit codes: 0 identical, 1 a run failed or the outputs differ, 2 bad usage.
set -euo pipefail

(($# >= 2 && $# <= 3)) || { echo "usage: compare_runs.sh DET_CHECKSUMS OUT_DIR [TICKS]" >&2; exit 2; }
exe=$1 out_dir=$2 ticks=${3:-600}
mkdir -p "$out_dir"

for run in 1 2; do
  rc=0
  "$exe" "$ticks" >"$out_dir/run$run.out" 2>"$out_dir/run$run.err" || rc=$?
  if ((rc != 0)); then
    echo "compare_runs: FAIL: run $run of $exe exited with status $rc" >&2
    tail -n 3 "$out_dir/run$run.out" >&2 || true
    tail -n 10 "$out_dir/run$run.err" >&2 || true
    exit 1
  fi
done

# Match ticks are "<tick> <checksum>"; the edge scene's "edge ..." lines
# before them are compared too, but not counted.
lines=$(grep -c -E '^-?[0-9]+ [0-9a-f]{16}$' "$out_dir/run1.out" || true)
edge=$(grep -c '^edge ' "$out_dir/run1.out" || true)
if ((lines != ticks)) || ((edge == 0)); then
  echo "compare_runs: FAIL: $exe printed $lines match tick lines (expected $ticks) and $edge edge lines" >&2
  exit 1
fi
if ! cmp -s "$out_dir/run1.out" "$out_dir/run2.out"; then
  first=$(cmp "$out_dir/run1.out" "$out_dir/run2.out" | sed -n 's/.* line \([0-9]*\).*/\1/p')
  echo "compare_runs: FAIL: the two runs differ first at line ${first:-?}:" >&2
  echo "  run 1: $(sed -n "${first:-1}p" "$out_dir/run1.out")" >&2
  echo "  run 2: $(sed -n "${first:-1}p" "$out_dir/run2.out")" >&2
  exit 1
fi
echo "compare_runs: PASS: two runs, $ticks ticks, identical; final $(tail -n 1 "$out_dir/run1.out")"
