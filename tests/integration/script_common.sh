# SPDX-License-Identifier: MIT
# Sourced by the integration scripts: a fresh work directory to run in,
# failing with the test's name, and one field of a --summary-json line.
#   test_name=...; source script_common.sh; enter_work_dir "$work"
# shellcheck shell=bash

enter_work_dir() {
  rm -rf "$1"
  mkdir -p "$1"
  cd "$1"
}

fail() { echo "FAIL [$test_name]: $*" >&2; exit 1; }

# json FILE FIELD: FIELD of the JSON object on FILE's last line.
json() {
  python3 -c "import json,sys; print(json.loads(open(sys.argv[1]).read().strip().splitlines()[-1])[sys.argv[2]])" "$1" "$2"
}
