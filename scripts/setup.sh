#!/usr/bin/env bash
# Idempotent set-up: installs the Debian packages Tilekit builds and tests with, if missing, and
# fetches the real textures (scripts/fetch-textures.sh).
# EGL/GLES + Mesa (libegl-dev, libgles-dev, libegl-mesa0, libgl1-mesa-dri): the headless GLSL renderer.
# spirv-tools: spirv-val checks the SPIR-V of the Vulkan GLSL and HLSL samplers (tests/render/test_shader_languages.cpp).
# chromium: the browser test of `texture preview` (headless, WebGL2 on SwiftShader; scripts/capture-preview.sh).
set -euo pipefail
PKGS=(g++ cmake make pkg-config libboost-graph-dev libsqlite3-dev sqlite3 libfmt-dev libgtest-dev
      libgmock-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev libstb-dev libpng-dev
      glslang-tools cadical spirv-tools libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
      clang libfuzzer-14-dev libclang-rt-14-dev libomp-dev  # fuzzing and the sanitizer builds
      tiled libpugixml-dev  # tilemap/: Tiled's XML reader; Tiled 1.8 and tmxrasterizer for tests/tilemap
      unzip        # scripts/fetch-textures.sh reads OpenArena's pk3 (a zip)
      jq dpkg-dev  # the install and Debian package tests (tests/install/install-test.sh)
      ninja-build  # the build (scripts/build.sh)
      chromium     # the browser test of `texture preview`
      nodejs       # the preview page's JavaScript against its golden vectors (tests/render/preview_golden.test.js)
      libtiff-dev libopenexr-dev  # image/: TIFF (libtiff) and OpenEXR input, OpenEXR output of float tiles and atlases
      openmpi-bin libopenmpi-dev)  # `pack --mpi` (cluster/mpi_work.*) and its mpirun tests (optional in the build)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  # One apt at a time on a shared machine: flock waits for another session's install.
  apt=(apt-get)
  command -v flock >/dev/null && apt=(flock /tmp/tilekit-apt.lock apt-get)
  $SUDO "${apt[@]}" install -y -q "${missing[@]}" >/dev/null 2>&1 || {
    $SUDO "${apt[@]}" update -q >/dev/null
    $SUDO "${apt[@]}" install -y -q "${missing[@]}" >/dev/null
  }
fi
# Real textures for the texture tests, benchmarks and main job (cached, never committed).
"$(dirname "$0")/fetch-textures.sh"
