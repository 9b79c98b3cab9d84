#!/usr/bin/env bash
# Sets up, builds and runs the main job on the embedded default (see README.md). One line per
# phase on stderr, with its time: the build from scratch takes minutes on 2 cores.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
start=$SECONDS
phase() { echo "run.sh: $1 ($((SECONDS - start)) s so far)" >&2; }
phase "setting up (Debian packages, textures)"
"$root/scripts/setup.sh"
phase "building build/tilekit (Release; several minutes from scratch on 2 cores)"
"$root/scripts/build.sh" >/dev/null
phase "running the main job"
"$root/scripts/main-job.sh" "$@"
phase "done"
