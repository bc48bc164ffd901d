#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# The Docker image and the compose match, end to end, on Debian 12 as root,
# with nothing but Debian's archive: no image registry is needed.
#
# Usage: scripts/container_test.sh [--work DIR] [--ticks N] [--programs prebuilt|source]
#                                  [--cache-dir DIR] [--mirror URL]
#   --work DIR        logs, summaries and the replay check go here
#                     (default build/container-test)
#   --ticks N         length of the compose match, 60 to 36000 ticks at 60 Hz (default 600)
#   --programs P      the Dockerfile's REWIND_PROGRAMS: prebuilt (default) copies the
#                     release build's four programs (building them first if needed);
#                     source builds them inside the image, as `docker compose up --build` does
#   --cache-dir DIR   where the debootstrapped base image tarballs are kept
#                     (default /var/cache/rewind)
#   --mirror URL      Debian mirror for debootstrap (default: the one apt uses here)
#
# Steps, each timed: Debian's docker.io, docker-compose and debootstrap (installed
# when missing); the Docker daemon (one already answering is used; otherwise
# Debian's dockerd is started with the vfs storage driver and no bridge network,
# and stopped at exit); the base images debian:12 and debian:12-slim (when the
# daemon lacks them: a bookworm minbase made by debootstrap and `docker import`ed,
# its tarballs cached); the image rewind:local (BuildKit, host network), and its
# refusal to run without a key (its default command reads one from /run/secrets)
# or tokenless on 0.0.0.0; the secure compose match on the host network (a key
# in its own volume, mounted as the server's secret; tokens in the replays
# volume; the server; 4 bots behind simulated latency and loss); its summaries
# (ended on its tick budget, every player joined over a secure session, every
# bot finished, no desync); the replay from the volume verified by rewind-replay
# in a container.
# The match's containers and volumes are removed at exit; the images are kept,
# so a second run starts warm.
#
# Exit codes: 0 passed; 1 a step failed (the message names it); 2 bad usage.
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$repo/build/container-test
ticks=600
programs=prebuilt
cache_dir=/var/cache/rewind
mirror=""

usage() { sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; }
need_value() { [[ -n ${2:-} ]] || { echo "container_test: $1 needs a value" >&2; exit 2; }; }
while (($#)); do
  case "$1" in
    --work) need_value "$@"; work=$2; shift 2 ;;
    --ticks) need_value "$@"; ticks=$2; shift 2 ;;
    --programs) need_value "$@"; programs=$2; shift 2 ;;
    --cache-dir) need_value "$@"; cache_dir=$2; shift 2 ;;
    --mirror) need_value "$@"; mirror=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "container_test: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
done
if ! [[ $ticks =~ ^[0-9]+$ ]] || ((10#$ticks < 60 || 10#$ticks > 36000)); then
  echo "container_test: --ticks must be a whole number from 60 to 36000, not '$ticks'" >&2
  exit 2
fi
ticks=$((10#$ticks))
case "$programs" in
  prebuilt|source) ;;
  *) echo "container_test: --programs must be 'prebuilt' or 'source', not '$programs'" >&2; exit 2 ;;
esac

fail() { echo "FAIL [container]: $*" >&2; exit 1; }

# Debian's client and compose, not whatever else is first on PATH: they are
# the ones this test installs and knows to work with Debian's daemon.
export PATH=/usr/sbin:/usr/bin:/sbin:/bin:$PATH
docker=/usr/bin/docker
compose=(/usr/bin/docker-compose -p rewindcontainertest -f "$repo/docker/compose.yaml")

# --- timing ------------------------------------------------------------------
started_at=$(date +%s.%N)
step_names=()
step_seconds=()
step_name=""
step_began=0
now() { date +%s.%N; }
elapsed() { python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" "$1" "$2"; }
end_step() {
  [[ -n $step_name ]] || return 0
  local s
  s=$(elapsed "$step_began" "$(now)")
  step_names+=("$step_name")
  step_seconds+=("$s")
  echo "    ${s} s"
  step_name=""
}
step() {
  end_step
  step_name=$1
  step_began=$(now)
  echo "==> $1"
}
print_timings() {
  echo
  echo "container test timings:"
  local i
  for i in "${!step_names[@]}"; do
    printf '  %8s s  %s\n' "${step_seconds[$i]}" "${step_names[$i]}"
  done
  printf '  %8s s  total\n' "$(elapsed "$started_at" "$(now)")"
}

# --- cleanup: only what this run started or created ----------------------------
dockerd_pid=""
netns_was_mounted=0
match_created=0
cleanup() {
  local status=$?
  end_step || true
  if ((match_created)); then
    "${compose[@]}" down -v --remove-orphans >>"$work/compose-down.log" 2>&1 \
      || echo "container_test: warning: 'docker-compose down' failed (see $work/compose-down.log)" >&2
  fi
  if [[ -n $dockerd_pid ]]; then
    kill -TERM "$dockerd_pid" 2>/dev/null || true
    for _ in $(seq 1 60); do kill -0 "$dockerd_pid" 2>/dev/null || break; sleep 0.5; done
    if kill -0 "$dockerd_pid" 2>/dev/null; then
      echo "container_test: dockerd did not stop on SIGTERM; killing its process group" >&2
      kill -KILL -- "-$dockerd_pid" 2>/dev/null || true
    fi
    # dockerd bind-mounts the host's network namespace and leaves it behind.
    if ((!netns_was_mounted)) && mountpoint -q /run/docker/netns/default; then
      umount /run/docker/netns/default || true
    fi
  fi
  print_timings
  if ((status == 0)); then echo "PASS [container]"; fi
  exit "$status"
}

# --- preconditions -----------------------------------------------------------
((EUID == 0)) || fail "run as root: it installs packages and starts dockerd"
# shellcheck disable=SC1091
[[ -r /etc/os-release ]] && . /etc/os-release
[[ ${ID:-} == debian && ${VERSION_ID:-} == 12 ]] \
  || fail "needs Debian 12 (its archive provides docker.io, docker-compose and debootstrap); this is ${PRETTY_NAME:-unknown}"
rm -rf "$work"
mkdir -p "$work" "$cache_dir"
trap cleanup EXIT
echo "container test: work dir $work, $ticks-tick match, programs $programs"

# --- 1. packages ---------------------------------------------------------------
step "Debian packages: docker.io docker-compose debootstrap"
packages=(docker.io docker-compose debootstrap)
missing=()
for p in "${packages[@]}"; do
  [[ $(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true) == installed ]] || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "    installing ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive apt-get update -q >"$work/apt.log" 2>&1 \
    || fail "apt-get update failed: $(tail -5 "$work/apt.log")"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}" \
    >>"$work/apt.log" 2>&1 || fail "apt-get install ${missing[*]} failed: $(tail -5 "$work/apt.log")"
else
  echo "    already installed"
fi

# --- 2. the programs the image copies ------------------------------------------
if [[ $programs == prebuilt ]]; then
  step "release build of the four programs (build/release/bin)"
  cd "$repo"
  if [[ ! -f build/release/CMakeCache.txt ]]; then
    cmake --preset release >"$work/cmake.log" 2>&1 || fail "cmake --preset release: $(tail -5 "$work/cmake.log")"
  fi
  cmake --build --preset release -j"$(nproc)" \
    --target rewind-server rewind-bots rewind-replay rewind-token >>"$work/cmake.log" 2>&1 \
    || fail "building the programs failed: $(tail -10 "$work/cmake.log")"
fi

# --- 3. the daemon -------------------------------------------------------------
step "Docker daemon"
if "$docker" info >/dev/null 2>&1; then
  echo "    using the daemon already running ($("$docker" info -f '{{.ServerVersion}}, storage {{.Driver}}'))"
else
  # vfs: no overlay mounts needed; no bridge, no iptables: the containers of
  # this test use the host's network.
  netns_was_mounted=0
  if mountpoint -q /run/docker/netns/default 2>/dev/null; then netns_was_mounted=1; fi
  setsid /usr/sbin/dockerd --storage-driver=vfs --iptables=false --ip6tables=false \
    --bridge=none --ip-masq=false >"$work/dockerd.log" 2>&1 &
  dockerd_pid=$!
  for _ in $(seq 1 120); do
    "$docker" info >/dev/null 2>&1 && break
    kill -0 "$dockerd_pid" 2>/dev/null || fail "dockerd exited at start: $(tail -5 "$work/dockerd.log")"
    sleep 0.5
  done
  "$docker" info >/dev/null 2>&1 || fail "dockerd did not answer within 60 s: $(tail -5 "$work/dockerd.log")"
  echo "    started dockerd (pid $dockerd_pid, $("$docker" info -f '{{.ServerVersion}}, storage {{.Driver}}'))"
fi

# --- 4. base images --------------------------------------------------------------
# apt's sources here: the first Debian archive serving bookworm, and its
# security archive, as "MIRROR SECURITY_MIRROR" (the second may be empty).
apt_mirrors() {
  python3 - <<'EOF'
import glob, re
main, security = "", ""
def consider(uris, suites):
    global main, security
    for uri in uris:
        if not re.match(r"https?://", uri):
            continue
        if "bookworm-security" in suites and not security:
            security = uri
        if "bookworm" in suites and not main:
            main = uri
for path in sorted(glob.glob("/etc/apt/sources.list.d/*.sources")):
    for stanza in open(path).read().split("\n\n"):
        fields = {}
        for line in stanza.splitlines():
            if line.startswith("#") or ":" not in line:
                continue
            key, value = line.split(":", 1)
            fields[key.strip().lower()] = value.split()
        if "deb" in fields.get("types", []):
            consider(fields.get("uris", []), fields.get("suites", []))
for path in ["/etc/apt/sources.list"] + sorted(glob.glob("/etc/apt/sources.list.d/*.list")):
    try:
        lines = open(path).read().splitlines()
    except OSError:
        continue
    for line in lines:
        words = re.sub(r"\[[^]]*\]", "", line.split("#", 1)[0]).split()
        if len(words) >= 3 and words[0] == "deb":
            consider([words[1]], [words[2]])
print(main or "http://deb.debian.org/debian", security)
EOF
}

# make_base_tarballs: a bookworm minbase by debootstrap, written as
# debian-12.tar and (without documentation, manuals and translations, as the
# official slim image) debian-12-slim.tar in the cache.
make_base_tarballs() {
  local rootfs=$cache_dir/rootfs.tmp security
  read -r auto_mirror security < <(apt_mirrors)
  mirror=${mirror:-$auto_mirror}
  echo "    debootstrap --variant=minbase bookworm from $mirror"
  rm -rf "$rootfs"
  debootstrap --variant=minbase bookworm "$rootfs" "$mirror" >"$work/debootstrap.log" 2>&1 \
    || fail "debootstrap failed: $(tail -5 "$work/debootstrap.log")"
  {
    echo "deb $mirror bookworm main"
    echo "deb $mirror bookworm-updates main"
    [[ -z $security ]] || echo "deb $security bookworm-security main"
  } >"$rootfs/etc/apt/sources.list"
  # Package files and lists are the bulk of a fresh rootfs; every image build
  # runs apt-get update first anyway.
  rm -rf "$rootfs"/var/cache/apt/archives/*.deb "$rootfs"/var/cache/apt/*.bin \
    "$rootfs"/var/lib/apt/lists/*
  tar -C "$rootfs" --numeric-owner -cf "$cache_dir/debian-12.tar.tmp" . \
    || fail "could not write $cache_dir/debian-12.tar"
  mkdir -p "$rootfs/etc/dpkg/dpkg.cfg.d"
  printf '%s\n' 'path-exclude /usr/share/doc/*' 'path-include /usr/share/doc/*/copyright' \
    'path-exclude /usr/share/man/*' 'path-exclude /usr/share/info/*' \
    'path-exclude /usr/share/locale/*' >"$rootfs/etc/dpkg/dpkg.cfg.d/slim"
  find "$rootfs/usr/share/doc" -mindepth 1 ! -type d ! -name copyright -delete
  rm -rf "$rootfs"/usr/share/man/* "$rootfs"/usr/share/info/* "$rootfs"/usr/share/locale/*
  tar -C "$rootfs" --numeric-owner -cf "$cache_dir/debian-12-slim.tar.tmp" . \
    || fail "could not write $cache_dir/debian-12-slim.tar"
  mv "$cache_dir/debian-12.tar.tmp" "$cache_dir/debian-12.tar"
  mv "$cache_dir/debian-12-slim.tar.tmp" "$cache_dir/debian-12-slim.tar"
  rm -rf "$rootfs"
}

step "base images debian:12 and debian:12-slim"
for tag in 12 12-slim; do
  if "$docker" image inspect "debian:$tag" >/dev/null 2>&1; then
    echo "    debian:$tag present"
    continue
  fi
  if [[ ! -s $cache_dir/debian-$tag.tar ]]; then
    make_base_tarballs
  else
    echo "    cached $cache_dir/debian-$tag.tar"
  fi
  "$docker" import "$cache_dir/debian-$tag.tar" "debian:$tag" >/dev/null \
    || fail "docker import of $cache_dir/debian-$tag.tar failed"
  echo "    imported debian:$tag ($(du -h "$cache_dir/debian-$tag.tar" | cut -f1))"
done

# --- 5. the image ------------------------------------------------------------------
step "image rewind:local (REWIND_PROGRAMS=$programs)"
cd "$repo"
DOCKER_BUILDKIT=1 "$docker" build --network host --progress plain \
  --build-arg "REWIND_PROGRAMS=$programs" -f docker/Dockerfile -t rewind:local . \
  >"$work/image-build.log" 2>&1 || fail "docker build failed: $(tail -15 "$work/image-build.log")"
echo "    $("$docker" image inspect -f '{{.Size}}' rewind:local | awk '{printf "%.0f MB", $1 / 1e6}')"
# Secure by default: without a key mounted the default command refuses to
# start (saying how to make one), and so does a command that leaves the key
# out on 0.0.0.0.
status=0
"$docker" run --rm --network host rewind:local >"$work/no-key.log" 2>&1 || status=$?
((status == 64)) && grep -q "rewind_server_key: cannot read it" "$work/no-key.log" \
  && grep -q "rewind-token keygen" "$work/no-key.log" \
  || fail "the image ran without a key (exit $status): $(tail -3 "$work/no-key.log")"
status=0
"$docker" run --rm --network host rewind:local --bind 0.0.0.0 --port 0 >"$work/tokenless.log" 2>&1 \
  || status=$?
((status == 1)) && grep -q "refusing to run tokenless on 0.0.0.0" "$work/tokenless.log" \
  || fail "the image ran tokenless on 0.0.0.0 (exit $status): $(tail -3 "$work/tokenless.log")"
echo "    without a key: refused (exit 64); tokenless on 0.0.0.0: refused (exit 1)"

# --- 6. the compose match ------------------------------------------------------------
step "compose match: keys, server, 4 bots ($ticks ticks at 60 Hz, host network)"
# A free UDP port, so the match cannot collide with a server already on 7777.
port=$(python3 -c "import socket; s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(('127.0.0.1', 0)); print(s.getsockname()[1])")
export REWIND_TICKS=$ticks REWIND_PORT=$port REWIND_MATCH_ID=container-test REWIND_PROGRAMS=$programs
"${compose[@]}" down -v --remove-orphans >"$work/compose-down.log" 2>&1 || true
match_created=1
match_limit=$((ticks / 60 + 120))
status=0
timeout "$match_limit" "${compose[@]}" up --no-build --no-color >"$work/compose-up.log" 2>&1 || status=$?
((status != 124)) || fail "the compose match did not end within $match_limit s: $(tail -10 "$work/compose-up.log")"
((status == 0)) || fail "docker-compose up exited $status: $(tail -10 "$work/compose-up.log")"

# Each service's stdout (its --summary-json line) and stderr, kept apart.
for service in keys server bots; do
  id=$("${compose[@]}" ps -q "$service")
  [[ -n $id ]] || fail "no $service container"
  "$docker" logs "$id" >"$work/$service.json" 2>"$work/$service.log"
  code=$("$docker" inspect -f '{{.State.ExitCode}}' "$id")
  ((code == 0)) || fail "$service exited $code: $(tail -5 "$work/$service.log") $(tail -5 "$work/$service.json")"
done

# --- 7. the summaries ----------------------------------------------------------------
step "summaries of the server and the bots"
json() {
  python3 -c "import json,sys; print(json.loads(open(sys.argv[1]).read().strip().splitlines()[-1])[sys.argv[2]])" "$1" "$2" \
    2>/dev/null || fail "$1 has no JSON summary with '$2': $(tail -3 "$1")"
}
expect() {  # expect FILE FIELD VALUE
  local got
  got=$(json "$1" "$2")
  [[ $got == "$3" ]] || fail "$(basename "$1" .json) summary: $2 is '$got', expected '$3': $(tail -1 "$1")"
}
server=$work/server.json
bots=$work/bots.json
expect "$server" end_reason "tick budget reached"
expect "$server" ticks_final "$ticks"
expect "$server" players_joined 4
expect "$server" desync_reports 0
expect "$server" secure True
expect "$server" secure_sessions 4
expect "$bots" joined 4
expect "$bots" finished 4
expect "$bots" failed 0
expect "$bots" desyncs 0
echo "    server: $(json "$server" ticks_final) ticks, $(json "$server" players_joined) players," \
  "$(json "$server" secure_sessions) secure sessions, ended: $(json "$server" end_reason)," \
  "final checksum $(json "$server" final_checksum)"
echo "    bots: $(json "$bots" finished) of 4 finished, $(json "$bots" desyncs) desyncs," \
  "$(json "$bots" rollbacks) rollbacks, rtt $(json "$bots" rtt_ms_avg) ms"

# --- 8. the replay -------------------------------------------------------------------
step "replay verified in a container (rewind-replay verify)"
"${compose[@]}" run --rm --no-deps -T --entrypoint rewind-replay server \
  verify /var/lib/rewind/match.rwr >"$work/verify.txt" 2>"$work/verify.log" \
  || fail "rewind-replay verify: $(cat "$work/verify.txt" "$work/verify.log")"
grep -q "^verified $ticks ticks (game crates, 4 players) checksum of last tick $(json "$server" final_checksum)" \
  "$work/verify.txt" || fail "the replay does not verify the match's $ticks ticks: $(cat "$work/verify.txt")"
echo "    $(head -1 "$work/verify.txt")"
end_step
