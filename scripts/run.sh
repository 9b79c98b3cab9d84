#!/usr/bin/env bash
# Sets up, builds and runs the main job on the embedded default (see README.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
exec "$root/scripts/main-job.sh" "$@"
