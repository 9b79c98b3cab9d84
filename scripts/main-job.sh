#!/usr/bin/env bash
# The main job on the embedded default. Grows with the product (see README.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tk="$root/build/tilekit"
"$tk" tileset show complete-corner-3
