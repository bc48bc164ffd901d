#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A hosted match scraped by a real Prometheus.
#   metrics_test.sh BIN_DIR WORK_DIR
# rewind-server serves /metrics on a free TCP port and logs JSON lines;
# Prometheus (its own config and storage in WORK_DIR) scrapes it every
# second. Before the players come, the target must be up and the scrape
# must pass promtool's checks. During the match Prometheus must report final
# ticks, the tick-time histogram and the joined players; other paths are 404;
# clients that never finish a request (one stalled in its headers, more
# than the connection cap of silent ones) are closed at the deadline while
# the match ticks on. The match must end with every tick, and every line the
# server wrote to stderr must be a JSON object.
set -euo pipefail
bin=$1
work=$2
test_name=metrics
# shellcheck source=script_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_common.sh"
enter_work_dir "$work"
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
probe() { python3 "$here/metrics_probe.py" "$@"; }


command -v prometheus >/dev/null || fail "prometheus is not installed (scripts/setup.sh installs it)"
command -v promtool >/dev/null || fail "promtool is not installed (it comes with prometheus)"


tick_rate=${REWIND_TEST_TICK_RATE:-60}
# Long enough (15 s) for Prometheus to scrape the running match several times.
ticks=$((tick_rate * 15))
players=2
deadline_s=2  # the endpoint's per-connection deadline

"$bin/rewind-server" --game crates --bind 127.0.0.1 --port 0 --port-file port \
  --metrics-bind 127.0.0.1:0 --metrics-port-file metrics_port --players "$players" \
  --tick-rate "$tick_rate" --ticks "$ticks" --join-timeout 90 --log-json --summary-json \
  >server.json 2>server.log &
pids+=($!)
server_pid=$!
for _ in $(seq 1 100); do [ -s port ] && [ -s metrics_port ] && break; sleep 0.1; done
[ -s metrics_port ] || fail "server did not start: $(cat server.log)"
port=$(cat port)
metrics_port=$(cat metrics_port)

probe get "$metrics_port" /metrics >scrape.txt
head -1 scrape.txt | grep -qx "HTTP 200" || fail "GET /metrics: $(head -3 scrape.txt)"
tail -n +2 scrape.txt | promtool check metrics || fail "promtool check metrics refused the scrape"
[ "$(probe status "$metrics_port" /other)" = 404 ] || fail "GET /other is not 404"

prom_port=$(probe free-port)
cat >prometheus.yml <<YAML
global:
  scrape_interval: 1s
  scrape_timeout: 1s
scrape_configs:
  - job_name: rewind
    static_configs:
      - targets: ["127.0.0.1:$metrics_port"]
YAML
prometheus --config.file=prometheus.yml --storage.tsdb.path="$work/tsdb" \
  --web.listen-address="127.0.0.1:$prom_port" --log.level=warn >prometheus.log 2>&1 &
pids+=($!)

# PromQL results are "labels value" lines; the first value, or nothing.
first_value() { probe query "$prom_port" "$1" 2>/dev/null | awk 'NR == 1 { print $NF }'; }
wait_for() {  # description seconds expr awk-condition-on-value
  local what=$1 seconds=$2 expr=$3 condition=$4 value=""
  for _ in $(seq 1 $((seconds * 4))); do
    value=$(first_value "$expr" || true)
    if [ -n "$value" ] && awk -v v="$value" "BEGIN { exit !($condition) }"; then
      echo "prometheus: $expr = $value"
      return 0
    fi
    sleep 0.25
  done
  fail "$what: $expr is '${value}' after ${seconds} s; prometheus log: $(tail -5 prometheus.log)"
}
wait_for "target not up" 60 'up{job="rewind"}' 'v == 1'
wait_for "lobby not seen" 10 'rewind_match_phase{phase="lobby"}' 'v == 1'

"$bin/rewind-bots" --bots "$players" --connect "127.0.0.1:$port" \
  --duration $((ticks / tick_rate + 30)) --summary-json >bots.json 2>bots.log &
pids+=($!)
bots_pid=$!

wait_for "no final ticks" 20 'rewind_ticks_final_total{job="rewind"}' 'v > 0'
wait_for "players" 10 'rewind_players_joined' "v == $players"
wait_for "no tick histogram" 10 'count(rewind_tick_seconds_bucket)' 'v >= 10'
wait_for "no ticks timed" 10 'rewind_tick_seconds_bucket{le="+Inf"}' 'v > 0'
wait_for "not running" 10 'rewind_match_phase{phase="running"}' 'v == 1'
up=$(first_value 'up{job="rewind"}')
[ "$up" = 1 ] || fail "up{job=\"rewind\"} is '$up' during the match"

before=$(probe value "$metrics_port" rewind_ticks_final_total)
probe hostile "$metrics_port" "$deadline_s" >hostile.json || fail "hostile clients: $(cat hostile.json)"
echo "hostile clients: $(cat hostile.json)"
after=$(probe value "$metrics_port" rewind_ticks_final_total)
# Ticking on at the full rate: at least half of what the held seconds allow.
[ -n "$after" ] && [ "$((after - before))" -ge $((tick_rate * deadline_s / 2)) ] \
  || fail "the match did not tick on while clients held connections: $before -> $after"
[ "$(probe status "$metrics_port" /metrics/extra)" = 404 ] || fail "GET /metrics/extra is not 404"

wait "$bots_pid" || fail "bots failed: $(tail -5 bots.log)"
wait "$server_pid" || fail "server exit $?: $(tail -5 server.log)"

[ "$(json bots.json finished)" = "$players" ] || fail "not every bot finished: $(cat bots.json)"
[ "$(json bots.json desyncs)" = 0 ] || fail "desync: $(cat bots.json)"
[ "$(json server.json ticks_final)" = "$ticks" ] || fail "ticks: $(cat server.json)"
lines=$(probe logs server.log) || fail "server log: $lines"
grep -q '"msg":"match summary: ' server.log || fail "no match summary in the JSON log"
grep -q 'metrics on http://127.0.0.1:' server.log || fail "the start-up line does not name the metrics endpoint"
echo "metrics: $ticks ticks, $lines JSON log lines, scraped by prometheus on port $prom_port"
echo "PASS [metrics]"
