#!/usr/bin/env bash
# Runs tests/tilemap/wfc_reference.test.js (`tilekit fill` against the npm port of WFC) with the
# npm packages of tests/npm/package.json. Usage: wfc-reference-test.sh REPO TILEKIT TMPDIR [SEEDS]
set -euo pipefail
repo=$1
command -v node >/dev/null || { echo "skipped: node is not installed (scripts/setup.sh installs nodejs)"; exit 0; }
dir=$(bash "$repo/scripts/npm-deps.sh" 2>/dev/null) || { echo "skipped: the npm packages are missing (scripts/npm-deps.sh)"; exit 0; }
NODE_PATH="$dir/node_modules" exec node "$repo/tests/tilemap/wfc_reference.test.js" "$@"
