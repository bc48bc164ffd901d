#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
#
# The client SDK's TypeScript declarations, checked as a game uses them:
# client_types_check.ts imports the SDK folder by its package name
# (@rewind/client, through its package.json's "exports" and "types") and is
# compiled by TypeScript (pinned in package-lock.json) under `strict`, with
# misuses that must be refused.
#
# usage: run_client_types.sh NODE SDK_DIR SCRIPT_DIR WORK_DIR
#   SDK_DIR     the SDK folder (client_sdk/web: package.json, rewind-client.d.ts)
#   SCRIPT_DIR  where client_types_check.ts and node_modules/typescript are
set -euo pipefail
test_name=client_types
node=$1 sdk=$2 scripts=$3 work=$4
tsc=$scripts/node_modules/typescript/bin/tsc
[ -f "$tsc" ] || { echo "FAIL [$test_name]: no TypeScript at $tsc (the browser_npm test installs it)" >&2; exit 1; }
rm -rf "$work"
mkdir -p "$work/node_modules/@rewind"
ln -s "$(cd "$sdk" && pwd)" "$work/node_modules/@rewind/client"
cp "$scripts/client_types_check.ts" "$work/"
cat >"$work/tsconfig.json" <<'JSON'
{
  "compilerOptions": {
    "target": "ES2022",
    "module": "ES2022",
    "moduleResolution": "bundler",
    "lib": ["ES2022", "DOM"],
    "types": [],
    "strict": true,
    "noUncheckedIndexedAccess": true,
    "noEmit": true
  },
  "files": ["client_types_check.ts"]
}
JSON
if ! (cd "$work" && "$node" "$tsc" -p tsconfig.json); then
  echo "FAIL [$test_name]: the declarations do not type-check as a game uses them" >&2
  exit 1
fi
echo "PASS [$test_name]: rewind-client.d.ts, through @rewind/client's package.json, under strict"
