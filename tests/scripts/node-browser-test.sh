#!/usr/bin/env bash
# Runs one node test of Tilekit's outputs in the users' tools (npm packages of tests/npm/package.json,
# installed by scripts/npm-deps.sh; headless chromium driven by tests/scripts/chromium_eval.mjs).
# Usage: tests/scripts/node-browser-test.sh TEST.mjs TILEKIT
# Exit 77 (skipped) where node or the npm packages are missing, unless TILEKIT_REQUIRE_BROWSER=1.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
skip() {
  if [ "${TILEKIT_REQUIRE_BROWSER:-0}" = 1 ]; then echo "FAIL: $1" >&2; exit 1; fi
  echo "skipped: $1"
  exit 77
}
command -v node >/dev/null || skip "node is not installed (scripts/setup.sh installs nodejs)"
dir=$("$root/scripts/npm-deps.sh") || skip "the npm packages could not be installed (scripts/npm-deps.sh)"
NODE_PATH=$dir/node_modules exec node --experimental-websocket --no-warnings "$1" "$2" "$root"
