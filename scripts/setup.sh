#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# Installs every system package Rewind needs to build, test, fuzz and run its
# determinism matrix, from Debian 12's own archive (nothing else is fetched).
#
# Idempotent: when every package is already installed it only says so; apt is
# touched (update + install) only when something is missing. Non-interactive.
# Run as root, or as a user with sudo.
#
# Usage: scripts/setup.sh [--check] [--wasm] [--viewer]
#   --check   only report what is missing; exit 1 if anything is
#   --wasm    also the WebAssembly toolchain (emscripten, node) for the
#             WebAssembly determinism check (scripts/test.sh --label wasm)
#   --viewer  also what the browser viewer and its tests need: emscripten and
#             node to build it, Chromium to test it headless, and npm (Debian's,
#             only when no npm is on the PATH) for the tests' puppeteer-core
# Exit codes: 0 everything present (or installed now); 1 packages missing and
# they could not be installed (not root and no usable sudo, or apt failed).
set -euo pipefail

packages=(
  # toolchain and build
  build-essential cmake ninja-build pkg-config git python3
  # clang: second compiler of the matrix; its runtime for -fsanitize=fuzzer
  clang libclang-rt-14-dev clang-format
  # libraries
  libasio-dev libprotobuf-dev protobuf-compiler libxxhash-dev libsodium-dev
  # the HTTP endpoints (metrics, control API, the Agones SDK client): Boost.Beast, JSON
  libboost1.81-dev nlohmann-json3-dev libssl-dev openssl
  libgtest-dev libgmock-dev libbenchmark-dev
  # peer engines for the side-by-side benchmarks (bench/ only) and the charts
  libbullet-dev libbox2d-dev gnuplot-nox
  # determinism matrix: aarch64 cross compiler, run under qemu-user
  g++-aarch64-linux-gnu qemu-user
  # the metrics integration test scrapes a match with a real Prometheus
  prometheus
  # the API reference from the public headers (docs/Doxyfile, test api_reference)
  doxygen
)

check_only=0
while (($#)); do
  case "$1" in
    --check) check_only=1 ;;
    --wasm) packages+=(emscripten nodejs) ;;
    --viewer)
      packages+=(emscripten nodejs chromium)
      command -v npm >/dev/null 2>&1 || packages+=(npm)
      ;;
    -h|--help) sed -n '4,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "setup: unknown option '$1' (try --help)" >&2; exit 1 ;;
  esac
  shift
done

if [[ -r /etc/os-release ]]; then
  # shellcheck disable=SC1091
  . /etc/os-release
  if [[ ${ID:-} != debian || ${VERSION_ID:-} != 12 ]]; then
    echo "setup: warning: this script targets Debian 12; this is ${PRETTY_NAME:-unknown}." \
         "Package names may differ." >&2
  fi
fi

is_installed() {
  [[ $(dpkg-query -W -f='${db:Status-Status}' "$1" 2>/dev/null || true) == installed ]]
}

missing=()
for p in "${packages[@]}"; do
  is_installed "$p" || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: missing: ${missing[*]}"
if ((check_only)); then
  exit 1
fi

as_root=()
if ((EUID != 0)); then
  if command -v sudo >/dev/null 2>&1; then
    # Without a terminal sudo cannot ask for a password: fail fast instead of hanging.
    if [[ -t 0 ]]; then as_root=(sudo); else as_root=(sudo -n); fi
  else
    echo "setup: ERROR: not root and sudo is not available; as root, run:" >&2
    echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
fi

apt_env=(env DEBIAN_FRONTEND=noninteractive)
if ! "${as_root[@]}" "${apt_env[@]}" apt-get update -q; then
  echo "setup: ERROR: 'apt-get update' failed${as_root:+ (is sudo allowed for this user?)}" >&2
  exit 1
fi
if ! "${as_root[@]}" "${apt_env[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"; then
  echo "setup: ERROR: 'apt-get install ${missing[*]}' failed" >&2
  exit 1
fi

still_missing=()
for p in "${missing[@]}"; do
  is_installed "$p" || still_missing+=("$p")
done
if ((${#still_missing[@]})); then
  echo "setup: ERROR: still not installed: ${still_missing[*]}" >&2
  exit 1
fi
echo "setup: installed ${#missing[@]} package(s); all ${#packages[@]} present"
