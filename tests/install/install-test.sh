#!/usr/bin/env bash
# Installation, the CMake package and the Debian packages (cmake/install.cmake), tested on an
# existing build: ctest runs it (tests/CMakeLists.txt) and nothing is rebuilt.
#
#   install-test.sh prefix SOURCE_DIR BUILD_DIR
#     Installs into a fresh prefix, copies the prefix elsewhere and deletes the original. Then,
#     with the source and build trees hidden (an empty tmpfs over each, in a private mount
#     namespace, as if they were deleted), it builds examples/consumer against the copy with
#     find_package(Tilekit 0.1) and checks, for C = 2, 3, 4 and 8, that the consumer prints what
#     the copied binary prints: `atlas lookup --no-db`, `tile --algo direct` and the atlas cell of
#     each tile of that tiling. The copied binary must also print what the build's binary printed
#     for a reference tile set and for packings stored as data (C = 16, 32).
#   install-test.sh deb SOURCE_DIR BUILD_DIR
#     Makes the .deb files (cpack -G DEB), checks that the runtime package depends only on
#     installed Debian runtime packages, extracts it into a scratch root (dpkg -x), runs
#     `tilekit --version` and one `atlas lookup` from there, and removes it.
#
# The consumer is compiled with CXX, CXXFLAGS and LDFLAGS from the environment (ctest passes the
# build's own, so that a sanitizer build links it). Needs cmake, jq, dpkg-dev (scripts/setup.sh).
set -euo pipefail
mode=${1:?usage: install-test.sh prefix|deb SOURCE_DIR BUILD_DIR}
src=${2:?source dir} build=${3:?build dir}
[ "$mode" = relocated ] || { src=$(cd "$src" && pwd) && build=$(cd "$build" && pwd); }
fail() {
  echo "install-test: FAIL: $*" >&2
  exit 1
}
say() { echo "install-test: $*"; }
same() {  # same WHAT FILE_A FILE_B
  cmp -s "$2" "$3" || { diff "$2" "$3" | head -n 5 >&2 || true; fail "$1 differs"; }
}

# The checks that run against the relocated prefix, after the trees were hidden.
relocated() {  # relocated PREFIX WORK
  local p=$1 work=$2 c
  [ "${TILEKIT_TREES_HIDDEN:-0}" = 0 ] || [ ! -e "$src/CMakeLists.txt" ] || fail "the source tree is still visible"
  cmake -S "$work/consumer-src" -B "$work/consumer-build" -DCMAKE_PREFIX_PATH="$p" >"$work/consumer.log" 2>&1 &&
    cmake --build "$work/consumer-build" >>"$work/consumer.log" 2>&1 || {
    tail -n 30 "$work/consumer.log" >&2
    fail "examples/consumer does not build against the installed package"
  }
  say "examples/consumer built with find_package(Tilekit 0.1) from $p"
  for c in 2 3 4 8; do
    "$work/consumer-build/consumer" "$c" >"$work/consumer.out"
    "$p/bin/tilekit" atlas lookup --kind corner --colors "$c" --no-db >"$work/lookup.json"
    "$p/bin/tilekit" tile --set "complete-corner-$c" --algo direct --size 8x4 --seed 1 --out "$work/tiling.json" --json \
      >/dev/null
    jq -r --slurpfile l "$work/lookup.json" '.cells[] | map($l[0].positions[.] | "\(.[0]),\(.[1])") | join(" ")' \
      "$work/tiling.json" >"$work/cells.txt"
    sed -n 1p "$work/consumer.out" >"$work/consumer.lookup"
    sed -n 2p "$work/consumer.out" >"$work/consumer.tiling"
    tail -n +3 "$work/consumer.out" >"$work/consumer.cells"
    same "C=$c: consumer's lookup vs tilekit atlas lookup" "$work/consumer.lookup" "$work/lookup.json"
    same "C=$c: consumer's direct tiling vs tilekit tile" "$work/consumer.tiling" "$work/tiling.json"
    same "C=$c: consumer's atlas cells vs the lookup's positions" "$work/consumer.cells" "$work/cells.txt"
  done
  say "consumer output equals tilekit atlas lookup, tilekit tile and the lookup's positions for C = 2 3 4 8"
  for c in 16 32; do
    "$p/bin/tilekit" atlas lookup --kind corner --colors "$c" --no-db >"$work/lookup-$c.relocated"
    same "C=$c: relocated atlas lookup vs the build's" "$work/lookup-$c.relocated" "$work/lookup-$c.build"
  done
  "$p/bin/tilekit" aperiodic verify "$p/share/tilekit/aperiodic/data/periodic-10-15.tiles" --json >"$work/known.json"
  [ "$(jq -r .verdict "$work/known.json")" = periodic ] || fail "the installed known-status set periodic-10-15 is not periodic"
  say "the installed known-status sets (share/tilekit/aperiodic/data) verify from the relocated prefix"
  "$p/bin/tilekit" tileset show culik-13 --json >"$work/culik.relocated"
  same "relocated tileset show culik-13 vs the build's" "$work/culik.relocated" "$work/culik.build"
  say "the relocated binary reads its stored packings (C = 16, 32) and reference tile sets without the build tree"
}

case "$mode" in
  prefix)
    work=$(mktemp -d "${TMPDIR:-/tmp}/tilekit-install-test.XXXXXX")
    trap 'rm -rf "$work"' EXIT
    export HOME=$work/home XDG_DATA_HOME=$work/home/data XDG_CACHE_HOME=$work/home/cache
    cmake --install "$build" --prefix "$work/prefix" >"$work/install.log" || fail "cmake --install failed"
    for f in bin/tilekit lib/cmake/Tilekit/TilekitConfig.cmake lib/cmake/Tilekit/TilekitConfigVersion.cmake \
      lib/cmake/Tilekit/TilekitTargets.cmake lib/libtilekit_atlas.a lib/libtilekit_tiling.a lib/libtilekit_results.a \
      include/tilekit/atlas/lookup.hpp include/tilekit/tiling/direct_tiling.hpp include/tilekit/results/results_db.hpp \
      include/tilekit/tilesets/tile_grid.hpp include/tilekit/base/error.hpp include/tilekit/image/image.hpp \
      share/doc/tilekit/README.md share/doc/tilekit/examples/consumer/main.cpp \
      share/tilekit/aperiodic/data/README.md share/tilekit/aperiodic/data/finite-14.tiles; do
      [ -e "$work/prefix/$f" ] || fail "$f was not installed"
    done
    say "installed into a fresh prefix: $(wc -l <"$build/install_manifest.txt") files"
    # What the build's binary prints, to compare the relocated one with.
    for c in 16 32; do "$build/tilekit" atlas lookup --kind corner --colors "$c" --no-db >"$work/lookup-$c.build"; done
    "$build/tilekit" tileset show culik-13 --json >"$work/culik.build"
    cp -a "$work/prefix" "$work/moved"
    rm -rf "$work/prefix"
    cp -a "$src/examples/consumer" "$work/consumer-src"
    cp "$0" "$work/install-test.sh"
    # Hide the source and build trees: an empty tmpfs over each, seen only by this mount namespace
    # (as root, else as root of a new user namespace).
    hide='mount -t tmpfs tilekit-hidden "$1" && { case "$2/" in "$1"/*) ;; *) mount -t tmpfs tilekit-hidden "$2" ;; esac; }'
    run='TILEKIT_TREES_HIDDEN=1 exec bash "$3" relocated "$1" "$2" "$4" "$5"'
    for ns in "unshare --mount" "unshare --mount --map-root-user"; do
      if $ns true 2>/dev/null; then
        $ns bash -c "$hide && $run" _ "$src" "$build" "$work/install-test.sh" "$work/moved" "$work"
        exit
      fi
    done
    fail "no mount namespace here (unshare --mount): cannot hide the build tree"
    ;;
  relocated)  # internal: prefix mode's second half, inside the mount namespace
    relocated "$4" "$5"
    ;;
  deb)
    work=$(mktemp -d "${TMPDIR:-/tmp}/tilekit-deb-test.XXXXXX")
    trap 'rm -rf "$work"' EXIT
    export HOME=$work/home XDG_DATA_HOME=$work/home/data XDG_CACHE_HOME=$work/home/cache
    cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/pkg" >"$work/cpack.log" 2>&1 || {
      tail -n 20 "$work/cpack.log" >&2
      fail "cpack -G DEB failed"
    }
    deb=$(ls "$work"/pkg/tilekit_*.deb)
    dev=$(ls "$work"/pkg/libtilekit-dev_*.deb)
    say "made $(basename "$deb") ($(du -k "$deb" | cut -f1) KB) and $(basename "$dev") ($(du -k "$dev" | cut -f1) KB)"
    depends=$(dpkg-deb -f "$deb" Depends)
    say "tilekit depends on: $depends"
    for want in libc6 libstdc++6 libgomp1 libsqlite3-0 libfmt; do
      grep -q "$want" <<<"$depends" || fail "the runtime package does not depend on $want"
    done
    # Each dependency (alternatives too) must be a Debian package installed here, and none a -dev.
    while read -r name; do
      case "$name" in *-dev) fail "the runtime package depends on the development package $name" ;; esac
      dpkg-query -W -f='${Status}' "$name" 2>/dev/null | grep -q "install ok installed" ||
        fail "dependency $name is not an installed Debian package"
    done < <(tr ',|' '\n\n' <<<"$depends" | sed 's/(.*)//; s/ //g' | grep .)
    dpkg-deb -c "$dev" >"$work/dev.list"
    grep -q "usr/lib/cmake/Tilekit/TilekitConfig.cmake" "$work/dev.list" || fail "libtilekit-dev lacks TilekitConfig.cmake"
    grep -q "usr/include/tilekit/atlas/lookup.hpp" "$work/dev.list" || fail "libtilekit-dev lacks the headers"
    root=$work/root
    dpkg -x "$deb" "$root"
    [ -x "$root/usr/bin/tilekit" ] || fail "no usr/bin/tilekit in $(basename "$deb")"
    "$root/usr/bin/tilekit" --version >"$work/version.deb"
    "$build/tilekit" --version >"$work/version.build"
    same "tilekit --version from the package vs the build's" "$work/version.deb" "$work/version.build"
    grep -Eq '^tilekit [0-9]+\.[0-9]+\.[0-9]+ \(commit [0-9a-f]{12}(-dirty)?\)$' "$work/version.deb" ||
      fail "tilekit --version printed '$(cat "$work/version.deb")'"
    "$root/usr/bin/tilekit" atlas lookup --kind corner --colors 3 --no-db >"$work/lookup.deb"
    "$build/tilekit" atlas lookup --kind corner --colors 3 --no-db >"$work/lookup.build"
    same "atlas lookup from the package vs the build's" "$work/lookup.deb" "$work/lookup.build"
    say "the extracted package runs: $(cat "$work/version.deb"), atlas lookup C=3 as the build's"
    rm -rf "$root"
    [ ! -e "$root" ] || fail "could not remove $root"
    say "removed the scratch root"
    ;;
  *) fail "unknown mode $mode (prefix or deb)" ;;
esac
