#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# A secure match soaked under a bad network: 64 clients (32 players and 32
# spectators, each holding its own connect token) against one rewind-server,
# every datagram in both directions dropped, duplicated or held back and
# overtaken at the given rates. Passes when the match plays to its end with
# every client finished, no desync report, a replay that verifies, and the
# server's memory flat: its resident size over the last half of the run may
# grow by at most --rss-growth-mb over the first half's peak (after a warm-up
# minute, or the first fifth of a short run).
#
# Usage: scripts/soak.sh [--minutes M] [--asan] [--bin DIR] [--work DIR]
#                        [--players N] [--spectators N] [--tick-rate HZ]
#                        [--loss X] [--duplicate X] [--reorder X]
#                        [--rss-growth-mb MB]
#   --minutes M        length of the match (default 10)
#   --asan             run the server under ASan + UBSan (build/debug, built
#                      with the debug preset when its programs are missing);
#                      a sanitizer report or a leak at exit fails the run.
#                      The bots are the release build's when it has them:
#                      64 clients' simulations under ASan cannot keep a
#                      real-time match on two cores
#   --bin DIR          the programs' directory (default build/release/bin,
#                      or build/debug/bin with --asan)
#   --bots-bin DIR     rewind-bots' directory (default: --bin's, or
#                      build/release/bin with --asan when it is there)
#   --work DIR         where the key, tokens, logs and replay go (default a
#                      new temporary directory, kept)
#   --players N        player slots, 1-32 (default 32)
#   --spectators N     spectator seats (default 32; players + spectators <= 64)
#   --tick-rate HZ     default 30 (64 clients' simulations share the
#                      machine with the server)
#   --loss/--duplicate/--reorder X   fault rates per datagram and direction
#                      (default 0.1 each)
#   --rss-growth-mb MB default 16
#
# Prints progress lines and one JSON summary line last:
#   {"minutes":..,"clients":..,"ticks_final":..,"desyncs":..,
#    "rss_first_half_mb":..,"rss_last_half_mb":..,"rss_growth_mb":..,"pass":true}
# Exit codes: 0 pass; 1 a check failed; 2 bad usage or a program missing.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
minutes=10 asan=0 bin="" bots_bin="" work="" players=32 spectators=32 tick_rate=30
loss=0.1 duplicate=0.1 reorder=0.1 rss_growth_mb=16
usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
need() { [[ -n ${2:-} ]] || { echo "soak: $1 needs a value" >&2; exit 2; }; }
while (($#)); do
  case "$1" in
    --minutes) need "$1" "${2:-}"; minutes=$2; shift 2 ;;
    --asan) asan=1; shift ;;
    --bin) need "$1" "${2:-}"; bin=$2; shift 2 ;;
    --bots-bin) need "$1" "${2:-}"; bots_bin=$2; shift 2 ;;
    --work) need "$1" "${2:-}"; work=$2; shift 2 ;;
    --players) need "$1" "${2:-}"; players=$2; shift 2 ;;
    --spectators) need "$1" "${2:-}"; spectators=$2; shift 2 ;;
    --tick-rate) need "$1" "${2:-}"; tick_rate=$2; shift 2 ;;
    --loss) need "$1" "${2:-}"; loss=$2; shift 2 ;;
    --duplicate) need "$1" "${2:-}"; duplicate=$2; shift 2 ;;
    --reorder) need "$1" "${2:-}"; reorder=$2; shift 2 ;;
    --rss-growth-mb) need "$1" "${2:-}"; rss_growth_mb=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "soak: unknown option '$1' (try --help)" >&2; exit 2 ;;
  esac
done
number() { [[ $2 =~ ^[0-9]+([.][0-9]+)?$ ]] || { echo "soak: $1 must be a number, got '$2'" >&2; exit 2; }; }
number --minutes "$minutes"; number --players "$players"; number --spectators "$spectators"
number --tick-rate "$tick_rate"; number --rss-growth-mb "$rss_growth_mb"
for rate in "$loss" "$duplicate" "$reorder"; do number "a fault rate" "$rate"; done

if [[ -z $bin ]]; then
  if ((asan)); then
    bin=$root/build/debug/bin
    programs=(rewind-server rewind-bots rewind-token rewind-replay)
    missing=0
    for p in "${programs[@]}"; do [[ -x $bin/$p ]] || missing=1; done
    if ((missing)); then
      echo "soak: building the ASan + UBSan programs (cmake --preset debug)"
      (cd "$root" && cmake --preset debug >/dev/null &&
        cmake --build --preset debug --target "${programs[@]}")
    fi
  else
    bin=$root/build/release/bin
  fi
fi
if [[ -z $bots_bin ]]; then
  bots_bin=$bin
  if ((asan)) && [[ -x $root/build/release/bin/rewind-bots ]]; then bots_bin=$root/build/release/bin; fi
fi
for p in rewind-server rewind-token rewind-replay; do
  [[ -x $bin/$p ]] || { echo "soak: $bin/$p is missing (build it first)" >&2; exit 2; }
done
[[ -x $bots_bin/rewind-bots ]] || { echo "soak: $bots_bin/rewind-bots is missing" >&2; exit 2; }
[[ -n $work ]] || work=$(mktemp -d "${TMPDIR:-/tmp}/rewind-soak.XXXXXX")
mkdir -p "$work"
cd "$work"

# ASan: small quarantine, so freed memory is reused and the resident size
# measures what the server holds; leaks fail the exit.
export ASAN_OPTIONS=${ASAN_OPTIONS:-quarantine_size_mb=16:detect_leaks=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

clients=$((players + spectators))
ticks=$(python3 -c "print(int(round($minutes * 60 * $tick_rate)))")
echo "soak: $clients clients ($players players, $spectators spectators), $minutes min at" \
  "$tick_rate Hz ($ticks ticks), loss $loss duplicate $duplicate reorder $reorder, in $work"

rm -f server.key tokens
"$bin/rewind-token" keygen --out server.key >/dev/null
for slot in $(seq 0 $((clients - 1))); do
  "$bin/rewind-token" mint --key-file server.key --match soak --slot "$slot" \
    --client-id $((slot + 1000)) --expires-in 86400 >>tokens
done

pids=()
cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; }
trap cleanup EXIT
fail() { echo "soak: FAIL: $*" >&2; exit 1; }

"$bin/rewind-server" --bind 127.0.0.1 --port 0 --port-file port --match-id soak \
  --key-file server.key --players "$players" --spectators "$spectators" \
  --tick-rate "$tick_rate" --ticks "$ticks" --join-timeout 120 --replay soak.rwr \
  --desync-dir desyncs --summary-json >server.json 2>server.log &
server_pid=$!
pids+=("$server_pid")
for _ in $(seq 1 300); do [[ -s port ]] && break; sleep 0.1; done
[[ -s port ]] || fail "the server did not start: $(tail -3 server.log)"

duration=$(python3 -c "print(int($minutes * 60 + 180))")
# Two bots processes, so the clients' simulations use both cores: the
# players with the first tokens, the spectators with the rest.
head -n "$players" tokens >tokens.players
tail -n +"$((players + 1))" tokens >tokens.spectators
bots_pids=()
"$bots_bin/rewind-bots" --bots "$players" --spectators 0 \
  --connect "127.0.0.1:$(cat port)" --token-file tokens.players --loss "$loss" \
  --duplicate "$duplicate" --reorder "$reorder" --duration "$duration" --seed 1 \
  --summary-json >bots.json 2>bots.log &
bots_pids+=($!)
if ((spectators > 0)); then
  "$bots_bin/rewind-bots" --bots 0 --spectators "$spectators" \
    --connect "127.0.0.1:$(cat port)" --token-file tokens.spectators --loss "$loss" \
    --duplicate "$duplicate" --reorder "$reorder" --duration "$duration" --seed 2 \
    --summary-json >spectators.json 2>spectators.log &
  bots_pids+=($!)
fi
pids+=("${bots_pids[@]}")

# The server's resident size every 5 s while it runs (kB), for the trend.
: >rss.txt
while kill -0 "$server_pid" 2>/dev/null; do
  rss=$(awk '/^VmRSS:/ { print $2 }' "/proc/$server_pid/status" 2>/dev/null || true)
  [[ -z $rss ]] || echo "$(date +%s) $rss" >>rss.txt
  sleep 5
done
server_status=0
wait "$server_pid" || server_status=$?
bots_status=0
for p in "${bots_pids[@]}"; do wait "$p" || bots_status=$?; done

problems=()
((server_status == 0)) || problems+=("the server exited with $server_status: $(tail -3 server.log)")
((bots_status == 0)) || problems+=("the bots exited with $bots_status: $(tail -3 bots.log)")
touch spectators.log spectators.json
grep -q "ERROR: \(AddressSanitizer\|LeakSanitizer\)\|runtime error:" server.log bots.log \
  spectators.log && problems+=("a sanitizer report: $(grep -m1 "ERROR: \|runtime error:" \
  server.log bots.log spectators.log)")
field() { python3 -c "import json,sys; print(json.loads(open(sys.argv[1]).read().strip().splitlines()[-1]).get(sys.argv[2], ''))" "$1" "$2" 2>/dev/null || true; }
ticks_final=$(field server.json ticks_final)
count() { local v; v=$(field "$1" "$2"); [[ $v =~ ^[0-9]+$ ]] && echo "$v" || echo 0; }
finished=$(( $(count bots.json finished) + $(count spectators.json finished) ))
desyncs=$(( $(count bots.json desyncs) + $(count spectators.json desyncs) ))
reports=$(field server.json desync_reports)
[[ $ticks_final == "$ticks" ]] || problems+=("$ticks_final of $ticks ticks final")
[[ $finished == "$clients" ]] || problems+=("$finished of $clients clients finished")
[[ $desyncs == 0 && $reports == 0 ]] || problems+=("desyncs: bots $desyncs, server reports $reports")
"$bin/rewind-replay" verify soak.rwr >verify.txt 2>&1 || problems+=("the replay does not verify")

# Memory: the first half's peak after the warm-up against the last half's.
read -r first_mb last_mb < <(python3 - "$minutes" <<'PY'
import sys
samples = [tuple(map(int, line.split())) for line in open("rss.txt") if line.strip()]
if len(samples) < 4:
    print("0 0")
    sys.exit()
start, end = samples[0][0], samples[-1][0]
warm = min(60, (end - start) / 5)
kept = [(t, kb) for t, kb in samples if t - start >= warm]
middle = (kept[0][0] + kept[-1][0]) / 2
first = [kb for t, kb in kept if t <= middle] or [kept[0][1]]
last = [kb for t, kb in kept if t > middle] or [kept[-1][1]]
print(f"{max(first) / 1024:.1f} {max(last) / 1024:.1f}")
PY
)
growth=$(python3 -c "print(round($last_mb - $first_mb, 1))")
python3 -c "import sys; sys.exit(0 if $growth <= $rss_growth_mb else 1)" ||
  problems+=("the server's memory grew by $growth MB (at most $rss_growth_mb)")
[[ $first_mb != 0 ]] || problems+=("too few memory samples")

pass=true
((${#problems[@]} == 0)) || pass=false
for problem in "${problems[@]}"; do echo "soak: FAIL: $problem" >&2; done
echo "{\"minutes\":$minutes,\"clients\":$clients,\"ticks_final\":${ticks_final:-0}," \
  "\"desyncs\":${desyncs:-null},\"rss_first_half_mb\":$first_mb,\"rss_last_half_mb\":$last_mb," \
  "\"rss_growth_mb\":$growth,\"pass\":$pass}" | tr -d ' '
[[ $pass == true ]]
