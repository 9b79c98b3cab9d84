#!/usr/bin/env bash
# Installs the npm packages of tests/npm/package.json (the users' tools that tests check our
# outputs against: ktx-parse and three's KTX2Loader for KTX2, the wavefunctioncollapse port for
# the WFC comparison) into one cache folder, once per version of that file, and prints the folder
# whose node_modules holds them. Usage: dir=$(scripts/npm-deps.sh); NODE_PATH=$dir/node_modules node ...
# TILEKIT_NPM_DIR overrides the folder (default ~/.cache/tilekit/npm).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dir=${TILEKIT_NPM_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/tilekit/npm}
mkdir -p "$dir"
if ! cmp -s "$root/tests/npm/package.json" "$dir/package.json" || [ ! -d "$dir/node_modules" ]; then
  command -v npm >/dev/null || { echo "npm-deps: npm is not installed (scripts/setup.sh installs it)" >&2; exit 2; }
  (
    command -v flock >/dev/null && exec 9>"$dir.lock" && flock 9
    cp "$root/tests/npm/package.json" "$dir/package.json.new"
    mv "$dir/package.json.new" "$dir/package.json"
    cd "$dir" && npm install --no-audit --no-fund --loglevel=error >/dev/null
  ) || { rm -f "$dir/package.json"; echo "npm-deps: npm install failed in $dir" >&2; exit 2; }
fi
echo "$dir"
