#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# End-to-end matches on loopback with the real programs.
#   match_test.sh MODE BIN_DIR WORK_DIR
# MODE:
#   faults   4 bots with latency, jitter, 5% loss, duplication, reordering:
#            rollbacks happen, no desync, the replay verifies (exit 0), a
#            replay with one input changed fails verification at that tick
#            (exit 1), copies cut on a frame boundary or inside a frame are
#            incomplete with their prefix verified (exit 4), and a flipped
#            bit inside a frame is corruption (exit 2).
#   desync   one bot corrupts its state at tick 120: it is detected at that
#            tick, reported (the server stores the report) and resynced.
#   garbage  random datagrams are fired at the server during a match: the
#            players see nothing of it, the server counts them.
#   latency  150 ms each way (a 300 ms round trip, longer than the 133 ms
#            window): clients run far enough ahead that almost no input
#            has to be substituted, and nobody desyncs.
#   signal   the server (no tick budget) gets SIGINT mid-match: it ends the
#            match cleanly, the bots finish, the replay verifies and ends
#            with its end record.
#   arena    the 2D lane's game ("arena", fixed point) with 4 bots under
#            latency, jitter and 2% loss: rollbacks happen, no desync, the
#            replay verifies.
#   arena_desync  one arena bot corrupts its state at tick 120: detected
#            there, the report names the 2D field (center.x), resynced.
#   joust    the 3D vehicle game ("joust": raycast cars, jointed riders, a
#            wrecking ball on a chain) with 4 bots under latency, jitter
#            and 2% loss, at 30 Hz (REWIND_TEST_JOUST_TICK_RATE): rollbacks
#            happen, no desync, the replay verifies.
#   joust_desync  one joust bot corrupts its state at tick 120: detected
#            there, the report names position.x, resynced; the replay
#            verifies.
#   kill     the server gets SIGKILL mid-match: the replay it leaves has no
#            end record; verify checks its whole prefix and exits 4.
#   long     16 bots, 17,400 ticks at 60 Hz (about 5 minutes), 5 ms latency
#            and 2% loss; one bot corrupts its state late (1,500 ticks
#            before the end): it is detected there, reported and resynced;
#            no bot fails, few inputs are substituted, nothing on the resync
#            path fails, and the replay verifies to its last tick.
#            REWIND_TEST_LONG_TICKS, _TICK_RATE and _LATENCY_MS change the
#            match (the window follows the rate: 200 ms). On two cores,
#            16 bots in one process keep up at 60 Hz with room to spare;
#            at 120 Hz they keep up only on an otherwise idle machine.
set -euo pipefail
mode=$1
bin=$2
work=$3
test_name="$mode"
# shellcheck source=script_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_common.sh"
enter_work_dir "$work"


server_pid=""
cleanup() { [ -n "$server_pid" ] && kill "$server_pid" 2>/dev/null || true; }
trap cleanup EXIT

# Sanitizer builds run several times slower than the real-time budget of a
# 60 Hz match; they play the same match at a pace they can keep.
tick_rate=${REWIND_TEST_TICK_RATE:-60}
ticks=${REWIND_TEST_TICKS:-480}
players=4
window=8
keyframes=60
if [ "$mode" = long ]; then
  # 16 bots are 16 simulations in one process plus the server's: a raised
  # tick rate plays many ticks in little time, and the window grows with
  # it so it still spans the same ~200 ms of round trip and scheduling.
  tick_rate=${REWIND_TEST_LONG_TICK_RATE:-60}
  ticks=${REWIND_TEST_LONG_TICKS:-17400}
  players=16
  window=$(( tick_rate / 5 > 8 ? tick_rate / 5 : 8 ))
  keyframes=600
  corrupt_at=$(( ticks - 1500 ))
fi
game=crates
case "$mode" in
  arena|arena_desync) game=arena ;;
  joust|joust_desync)
    game=joust
    # A joust tick (cars, four jointed riders solved as trees, 4 substeps)
    # costs about 1.3 ms; four bots' simulations and their rollbacks in one
    # process need more than a core at 60 Hz. Half the pace, the same ticks.
    tick_rate=${REWIND_TEST_JOUST_TICK_RATE:-30} ;;
esac
budget=$ticks
[ "$mode" = signal ] || [ "$mode" = kill ] && budget=0
started=$(date +%s)
"$bin/rewind-server" --game "$game" --bind 127.0.0.1 --port 0 --port-file port --players "$players" \
  --tick-rate "$tick_rate" --window "$window" --ticks "$budget" --replay match.rwr \
  --keyframe-interval "$keyframes" --desync-dir desyncs --join-timeout 30 --summary-json \
  >server.json 2>server.log &
server_pid=$!
for _ in $(seq 1 100); do [ -s port ] && break; sleep 0.1; done
[ -s port ] || fail "server did not start: $(cat server.log)"
port=$(cat port)

bots_args=(--bots "$players" --connect "localhost:$port" --game "$game" --summary-json)
if [ "$mode" = long ]; then
  bots_args+=(--duration $(( ticks / tick_rate + 120 )))
else
  bots_args+=(--duration 60)
fi
case "$mode" in
  faults)  bots_args+=(--latency-ms 30 --jitter-ms 10 --loss 0.05 --duplicate 0.02 --reorder 0.02) ;;
  desync|arena_desync|joust_desync)  bots_args+=(--latency-ms 10 --corrupt-bot 2 --corrupt-at-tick 120) ;;
  arena|joust)   bots_args+=(--latency-ms 20 --jitter-ms 5 --loss 0.02) ;;
  garbage) bots_args+=(--latency-ms 10) ;;
  signal|kill) bots_args+=(--latency-ms 10) ;;
  latency) bots_args+=(--latency-ms 150 --jitter-ms 10 --loss 0.02) ;;
  long)    bots_args+=(--latency-ms ${REWIND_TEST_LONG_LATENCY_MS:-5} --jitter-ms 1 --loss 0.02 --corrupt-bot 5 --corrupt-at-tick "$corrupt_at") ;;
  *) fail "unknown mode" ;;
esac

if [ "$mode" = garbage ]; then
  # Fire random datagrams (random sizes, random bytes, plus mangled copies of
  # a valid-looking header) at the server for the first seconds of the match.
  python3 - "$port" "${REWIND_TEST_FLOOD_GAP_S:-0.0005}" <<'PY' &
import os, random, socket, sys, time
port = int(sys.argv[1])
gap = float(sys.argv[2])
rng = random.Random(42)
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
end = time.time() + 6
sent = 0
while time.time() < end and sent < 20000:
    size = rng.choice([0, 1, 5, 40, 300, 1199, 1200, 1201, 1500, 9000])
    payload = bytes(rng.getrandbits(8) for _ in range(size))
    if rng.random() < 0.3:
        # protocol_version 1, a random connection id, a random sequence, then junk
        payload = b"\x08\x01\x11" + os.urandom(8) + b"\x18" + bytes([rng.randrange(1, 127)]) + payload[:50]
    try:
        s.sendto(payload, ("127.0.0.1", port))
    except OSError:
        pass
    sent += 1
    time.sleep(gap)
print(sent)
PY
  flood_pid=$!
fi

if [ "$mode" = signal ] || [ "$mode" = kill ]; then
  # Interrupt (or kill) the server once the match has been running a while.
  sig=INT
  [ "$mode" = kill ] && sig=KILL
  # Counted from the start of play, not of the server: slow joins on a
  # loaded machine must not move the signal into the lobby.
  ( for _ in $(seq 1 600); do grep -q "players joined" server.log && break; sleep 0.1; done
    sleep $(( ticks / tick_rate / 2 + 1 )); kill -"$sig" "$server_pid" ) &
fi
set +e
"$bin/rewind-bots" "${bots_args[@]}" >bots.json 2>bots.log
bots_status=$?
wait "$server_pid"
server_status=$?
set -e
server_pid=""
[ "$mode" = kill ] || [ "$server_status" = 0 ] || fail "rewind-server exited $server_status: $(tail -5 server.log)"

# Runs rewind-replay; its exit status goes to $status, its output to $2.
replay() {  # command file.txt args...
  local cmd=$1 out=$2
  shift 2
  set +e
  "$bin/rewind-replay" "$cmd" "$@" >"$out" 2>&1
  status=$?
  set -e
}

if [ "$mode" = kill ]; then
  # A killed server finishes nothing: no end record, no summary; what it
  # flushed before the kill is a prefix that verifies.
  [ "$server_status" = 137 ] || fail "rewind-server was not killed: exit $server_status"
  replay verify verify.txt match.rwr
  [ "$status" = 4 ] || fail "killed server's replay: exit $status, expected 4: $(cat verify.txt)"
  grep -q "^INCOMPLETE: no end record" verify.txt || fail "not reported incomplete: $(cat verify.txt)"
  verified=$(sed -n 's/^prefix verified: \([0-9]*\) ticks.*/\1/p' verify.txt)
  [ "${verified:-0}" -gt 30 ] || fail "too few ticks verified before the kill: $(cat verify.txt)"
  replay inspect inspect.txt match.rwr
  [ "$status" = 4 ] || fail "inspect of the killed server's replay: exit $status: $(cat inspect.txt)"
  replay verify verify.json match.rwr --json
  grep -q '"outcome": "incomplete"' verify.json || fail "JSON outcome: $(cat verify.json)"
  grep -q '"complete": false' verify.json || fail "JSON completeness: $(cat verify.json)"
  echo "PASS [$mode] ($verified ticks verified before the kill)"
  exit 0
fi
# Every bot's final ticks agree with the server's: checked by its own
# simulation, or passed over by a resync (the server's snapshot, checked
# against its checksum) when the machine was too loaded for the bot to
# keep up; and a fair share were simulated and checked by the bots.
check_final_ticks() {
  local verified resynced
  verified=$(json bots.json final_ticks_verified)
  resynced=$(json bots.json final_ticks_resynced)
  [ $(( verified + resynced )) -ge $(( players * (ticks - 20) )) ] ||
    fail "final ticks not accounted for: $verified verified, $resynced resynced of $(( players * ticks ))"
  [ "$verified" -ge $(( players * ticks / 4 )) ] ||
    fail "too few verified final ticks: $verified ($resynced passed over by resyncs)"
}

[ "$mode" = garbage ] && wait "$flood_pid"

echo "server: $(cat server.json)"
echo "bots:   $(cat bots.json)"
if [ "$mode" = signal ]; then
  [ "$bots_status" = 0 ] || fail "rewind-bots exited $bots_status"
  grep -q '"end_reason":"stopped by signal SIGINT"' server.json || fail "server did not end on SIGINT"
  final=$(json server.json ticks_final)
  [ "$final" -gt 30 ] || fail "too few final ticks before the signal: $final"
  [ "$(json bots.json finished)" = 4 ] || fail "not every bot saw the end: $(tail -5 bots.log)"
  "$bin/rewind-replay" verify match.rwr >verify.txt 2>&1 || fail "replay did not verify: $(cat verify.txt)"
  grep -q "verified $final ticks" verify.txt || fail "unexpected verify output: $(cat verify.txt)"
  "$bin/rewind-replay" inspect match.rwr | grep -q 'reason "stopped by signal SIGINT"' || fail "replay has no end record"
  echo "PASS [$mode]"
  exit 0
fi
[ "$(json server.json ticks_final)" = "$ticks" ] || fail "server finalized $(json server.json ticks_final) of $ticks ticks"
[ "$(json bots.json finished)" = "$players" ] || fail "not every bot finished the match: $(tail -5 bots.log)"

case "$mode" in
  faults)
    [ "$bots_status" = 0 ] || fail "rewind-bots exited $bots_status"
    [ "$(json bots.json desyncs)" = 0 ] || fail "desyncs under faults"
    rollbacks=$(( $(json server.json rollbacks) + $(json bots.json rollbacks) ))
    [ "$rollbacks" -gt 0 ] || fail "no rollbacks happened: the test did not exercise them"
    check_final_ticks
    "$bin/rewind-replay" verify match.rwr >verify.txt 2>&1 || fail "replay did not verify: $(cat verify.txt)"
    grep -q "verified $ticks ticks" verify.txt || fail "unexpected verify output: $(cat verify.txt)"
    replay inspect inspect.txt match.rwr
    [ "$status" = 0 ] || fail "inspect: exit $status, expected 0: $(cat inspect.txt)"
    grep -q "; this build runs the same" inspect.txt || fail "inspect: engine not this build's: $(cat inspect.txt)"
    grep -q "^file: complete" inspect.txt || fail "inspect: not complete: $(cat inspect.txt)"
    "$bin/rewind-replay" tamper match.rwr --tick 200 --player 1 --axis-x 1000 --axis-y -1000 --out tampered.rwr >/dev/null
    replay verify tampered.txt tampered.rwr
    [ "$status" = 1 ] || fail "tampered replay: exit $status, expected 1: $(cat tampered.txt)"
    grep -q "tick 200" tampered.txt || fail "tampered replay did not name tick 200: $(cat tampered.txt)"

    # Frame boundaries (u32 LE length + 12-byte frame header per frame),
    # then copies cut short and one damaged.
    python3 - match.rwr <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
starts, at = [], 8
while at < len(data):
    starts.append(at)
    at += 12 + struct.unpack_from("<I", data, at)[0]
assert at == len(data), "frames do not tile the file"
mid = starts[len(starts) // 2]
open("boundary.rwr", "wb").write(data[:mid])             # a flush, then the kill
open("torn.rwr", "wb").write(data[:mid + 12 + 3])        # a write cut mid-payload
flipped = bytearray(data)
flipped[mid + 12 + 1] ^= 0x08                            # one bit inside a payload
open("flipped.rwr", "wb").write(flipped)
PY
    for cut in boundary torn; do
      replay verify "$cut.txt" "$cut.rwr"
      [ "$status" = 4 ] || fail "$cut replay: exit $status, expected 4: $(cat "$cut.txt")"
      grep -q "^prefix verified: [1-9][0-9]* ticks" "$cut.txt" || fail "$cut replay: prefix not verified: $(cat "$cut.txt")"
      grep -q "^INCOMPLETE: " "$cut.txt" || fail "$cut replay: not reported incomplete: $(cat "$cut.txt")"
      replay inspect "$cut.inspect.txt" "$cut.rwr"
      [ "$status" = 4 ] || fail "inspect $cut replay: exit $status, expected 4: $(cat "$cut.inspect.txt")"
    done
    grep -q "ends inside a frame" torn.txt || fail "torn replay: $(cat torn.txt)"
    replay verify flipped.txt flipped.rwr
    [ "$status" = 2 ] || fail "flipped replay: exit $status, expected 2: $(cat flipped.txt)"
    grep -q "^file breaks at: hash mismatch" flipped.txt || fail "flipped replay: $(cat flipped.txt)"
    replay inspect flipped.inspect.txt flipped.rwr
    [ "$status" = 2 ] || fail "inspect flipped replay: exit $status, expected 2: $(cat flipped.inspect.txt)"
    ;;
  arena)
    [ "$bots_status" = 0 ] || fail "rewind-bots exited $bots_status"
    [ "$(json bots.json desyncs)" = 0 ] || fail "desyncs in arena"
    rollbacks=$(( $(json server.json rollbacks) + $(json bots.json rollbacks) ))
    [ "$rollbacks" -gt 0 ] || fail "no rollbacks happened: the test did not exercise them"
    check_final_ticks
    "$bin/rewind-replay" verify match.rwr >verify.txt 2>&1 || fail "replay did not verify: $(cat verify.txt)"
    grep -q "verified $ticks ticks (game arena" verify.txt || fail "unexpected verify output: $(cat verify.txt)"
    ;;
  joust)
    [ "$bots_status" = 0 ] || fail "rewind-bots exited $bots_status"
    [ "$(json bots.json desyncs)" = 0 ] || fail "desyncs in joust"
    rollbacks=$(( $(json server.json rollbacks) + $(json bots.json rollbacks) ))
    [ "$rollbacks" -gt 0 ] || fail "no rollbacks happened: the test did not exercise them"
    check_final_ticks
    "$bin/rewind-replay" verify match.rwr >verify.txt 2>&1 || fail "replay did not verify: $(cat verify.txt)"
    grep -q "verified $ticks ticks (game joust" verify.txt || fail "unexpected verify output: $(cat verify.txt)"
    echo "joust: $(head -1 verify.txt); rollbacks: server $(json server.json rollbacks), bots $(json bots.json rollbacks)"
    ;;
  joust_desync)
    [ "$bots_status" = 1 ] || fail "rewind-bots exited $bots_status, expected 1 (desync detected)"
    [ "$(json bots.json desyncs)" = 1 ] || fail "expected exactly one desync, got $(json bots.json desyncs)"
    [ "$(json bots.json resyncs)" -ge 1 ] || fail "the corrupted bot was not resynced"
    grep -q "bot 2: DESYNC at tick 120 " bots.log || fail "desync not detected at tick 120: $(grep DESYNC bots.log)"
    report=$(ls desyncs/desync_p*_t120_*.txt 2>/dev/null | head -1)
    [ -n "$report" ] || fail "no desync report file for tick 120: $(ls desyncs)"
    grep -q "position.x" "$report" || fail "report does not name position.x: $(cat "$report")"
    "$bin/rewind-replay" verify match.rwr >verify.txt 2>&1 || fail "replay did not verify: $(cat verify.txt)"
    grep -q "verified $ticks ticks (game joust" verify.txt || fail "unexpected verify output: $(cat verify.txt)"
    ;;
  arena_desync)
    [ "$bots_status" = 1 ] || fail "rewind-bots exited $bots_status, expected 1 (desync detected)"
    [ "$(json bots.json desyncs)" = 1 ] || fail "expected exactly one desync, got $(json bots.json desyncs)"
    [ "$(json bots.json resyncs)" -ge 1 ] || fail "the corrupted bot was not resynced"
    report=$(ls desyncs/desync_p*_t120_*.txt 2>/dev/null | head -1)
    [ -n "$report" ] || fail "no desync report file for tick 120: $(ls desyncs)"
    grep -q "center.x" "$report" || fail "report does not name center.x: $(cat "$report")"
    "$bin/rewind-replay" verify match.rwr >verify.txt 2>&1 || fail "replay did not verify: $(cat verify.txt)"
    ;;
  desync)
    [ "$bots_status" = 1 ] || fail "rewind-bots exited $bots_status, expected 1 (desync detected)"
    [ "$(json bots.json desyncs)" = 1 ] || fail "expected exactly one desync, got $(json bots.json desyncs)"
    [ "$(json bots.json resyncs)" -ge 1 ] || fail "the corrupted bot was not resynced"
    grep -q "bot 2: DESYNC at tick 120 " bots.log || fail "desync not detected at tick 120: $(grep DESYNC bots.log)"
    [ "$(json server.json desync_reports)" -ge 1 ] || fail "server stored no desync report"
    report=$(ls desyncs/desync_p*_t120_*.txt 2>/dev/null | head -1)
    [ -n "$report" ] || fail "no desync report file for tick 120: $(ls desyncs)"
    grep -q "differing fields" "$report" || fail "report does not name the differing fields: $(cat "$report")"
    grep -q "position.x" "$report" || fail "report does not name position.x: $(cat "$report")"
    "$bin/rewind-replay" verify match.rwr >verify.txt 2>&1 || fail "replay did not verify: $(cat verify.txt)"
    ;;
  latency)
    [ "$bots_status" = 0 ] || fail "rewind-bots exited $bots_status"
    [ "$(json bots.json desyncs)" = 0 ] || fail "desyncs at high latency"
    # Only the first ticks, before the clocks have settled, may miss inputs.
    [ "$(json server.json substituted_inputs)" -lt 60 ] || fail "clients ran too late: $(json server.json substituted_inputs) inputs substituted"
    check_final_ticks
    ;;
  garbage)
    [ "$bots_status" = 0 ] || fail "rewind-bots exited $bots_status"
    [ "$(json bots.json desyncs)" = 0 ] || fail "desyncs under garbage"
    [ "$(json server.json rejected_packets)" -gt 1000 ] || fail "server counted too few rejected packets"
    [ "$(json server.json substituted_inputs)" -lt 40 ] || fail "garbage starved real inputs"
    "$bin/rewind-replay" verify match.rwr >verify.txt 2>&1 || fail "replay did not verify: $(cat verify.txt)"
    ;;
  long)
    played=$(( $(date +%s) - started ))
    [ "$bots_status" = 1 ] || fail "rewind-bots exited $bots_status, expected 1 (the corrupted bot's desync): $(tail -5 bots.log)"
    [ "$(json bots.json failed)" = 0 ] || fail "$(json bots.json failed) bots failed: $(grep -v 'resynced\|DESYNC' bots.log | tail -5)"
    [ "$(json bots.json desyncs)" = 1 ] || fail "expected exactly one desync, got $(json bots.json desyncs): $(grep DESYNC bots.log)"
    grep -q "bot 5: DESYNC at tick $corrupt_at " bots.log || fail "desync not detected at tick $corrupt_at: $(grep DESYNC bots.log)"
    grep -q "bot 5: resynced at tick" bots.log || fail "the corrupted bot was not resynced"
    [ "$(json bots.json resyncs_refused)" = 0 ] || fail "a bot refused a resync snapshot: $(grep 'did not load' bots.log)"
    for counter in resync_snapshot_failures resyncs_refused desync_dumps_unreadable desync_report_write_failures keyframe_load_failures; do
      [ "$(json server.json $counter)" = 0 ] || fail "server $counter: $(json server.json $counter): $(grep WARNING server.log | head -5)"
    done
    [ "$(json server.json desync_reports)" -ge 1 ] || fail "server stored no desync report"
    report=$(ls desyncs/desync_p*_t${corrupt_at}_*.txt 2>/dev/null | head -1)
    [ -n "$report" ] || fail "no desync report file for tick $corrupt_at: $(ls desyncs)"
    grep -q "differing fields" "$report" || fail "report does not name the differing fields: $(cat "$report")"
    # A scheduling hiccup may make a few inputs late; a blowup means the
    # clients could not keep up.
    substituted=$(json server.json substituted_inputs)
    [ "$substituted" -lt $(( players * ticks / 200 )) ] || fail "$substituted inputs substituted (of $(( players * ticks )))"
    verify_started=$(date +%s)
    "$bin/rewind-replay" verify match.rwr >verify.txt 2>&1 || fail "replay did not verify: $(cat verify.txt)"
    grep -q "verified $ticks ticks" verify.txt || fail "unexpected verify output: $(cat verify.txt)"
    echo "long: $players players, $ticks ticks at $tick_rate Hz played in ${played} s; replay verified in $(( $(date +%s) - verify_started )) s; $substituted inputs substituted; rollbacks: server $(json server.json rollbacks), bots $(json bots.json rollbacks)"
    ;;
esac
echo "PASS [$mode]"
