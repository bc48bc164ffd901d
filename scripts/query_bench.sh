#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Measures Rewind's scene queries and stepping in a 10,000-box static level
# against Bullet's in the same process (bench/query_bench.cpp), writes the
# Google Benchmark JSON to docs/charts/query_bench.json and prints the
# Rewind/Bullet time ratio of each family (and Jolt's time and the
# Rewind/Jolt ratio when build/bench was configured with REWIND_JOLT_DIR).
#
# Usage: scripts/query_bench.sh [--no-build] [--min-time SECONDS]
#   --no-build        use the binary already in build/bench
#   --min-time S      --benchmark_min_time for the query benchmarks (default
#                     0.5; the step benchmarks always time 240 ticks)
#
# Steps: cmake --preset bench, build rewind_query_bench, run it (the engines'
# agreement check goes to stderr; the run stops if they disagree), then the
# ratio table. About a minute to build from scratch on 2 cores and 15 s to
# run. Exit codes: 0 done; 2 bad usage; otherwise the status of the failing
# step.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

build=1
min_time=0.5
usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
while (($#)); do
  case "$1" in
    --no-build) build=0; shift ;;
    --min-time)
      min_time=${2:-}
      [[ -n $min_time ]] || { echo "query_bench: --min-time needs a value" >&2; exit 2; }
      shift 2 ;;
    --min-time=*) min_time=${1#--min-time=}; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "query_bench: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
done

step() { echo "==> $*" >&2; }

if ((build)); then
  step "configure + build (preset bench, rewind_query_bench)"
  cmake --preset bench >/dev/null
  cmake --build --preset bench -j2 --target rewind_query_bench >&2
fi

bin=build/bench/bin/rewind_query_bench
out=docs/charts/query_bench.json
mkdir -p "$(dirname "$out")"
step "run (queries: --benchmark_min_time=$min_time)"
# Written to a temporary file first so a failed run leaves the last good JSON.
"$bin" --benchmark_format=json --benchmark_min_time="$min_time" >"$out.tmp"
mv "$out.tmp" "$out"

step "Rewind/Bullet time per family (< 1: Rewind faster), from $out"
python3 - "$out" <<'EOF'
import json
import sys

SCALE = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}  # to milliseconds
runs = {}
order = []
for b in json.load(open(sys.argv[1]))["benchmarks"]:
    if b.get("run_type") == "aggregate":
        continue
    parts = [p for p in b["name"].split("/") if ":" not in p]  # drop "iterations:240"
    engine = parts[-1]
    family = "/".join(parts[:-1])
    if family not in runs:
        runs[family] = {}
        order.append(family)
    runs[family][engine] = b

def per_op(b, key):
    # A step benchmark's iteration is one tick (ms/step); a query
    # benchmark's is 1,000 queries, so its milliseconds per iteration are
    # microseconds per query.
    ms = b[key] * SCALE[b["time_unit"]]
    return (ms, "us/query") if "items_per_second" in b else (ms, "ms/step")

# Jolt's columns only when the binary was built with it (REWIND_JOLT_DIR).
jolt = any("Jolt" in e for e in runs.values())
print(f"{'family':<18}{'Rewind':>10}{'Bullet':>10}  {'unit':<9}{'ratio':>7}{'cpu ratio':>11}"
      f"{'agree %':>9}" + (f"{'Jolt':>10}{'R/Jolt':>8}{'agree %':>9}" if jolt else ""))
for family in order:
    r, b = runs[family].get("Rewind"), runs[family].get("Bullet")
    if r is None or b is None:
        continue
    (rt, unit), (bt_, _) = per_op(r, "real_time"), per_op(b, "real_time")
    rc, bc = per_op(r, "cpu_time")[0], per_op(b, "cpu_time")[0]
    agree = r.get("agree_pct")
    agree_text = f"{agree:>9.1f}" if agree is not None else f"{'-':>9}"
    jolt_text = ""
    j = runs[family].get("Jolt")
    if jolt and j is not None and "error_occurred" not in j:
        jt = per_op(j, "real_time")[0]
        jolt_text = f"{jt:>10.3f}{rt / jt:>8.2f}"
        ja = j.get("agree_pct")
        jolt_text += f"{ja:>9.1f}" if ja is not None else f"{'-':>9}"
    elif jolt:
        jolt_text = f"{'-':>10}{'-':>8}{'-':>9}"
    print(f"{family:<18}{rt:>10.3f}{bt_:>10.3f}  {unit:<9}{rt / bt_:>7.2f}{rc / bc:>11.2f}"
          f"{agree_text}" + jolt_text)
EOF
