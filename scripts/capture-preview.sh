#!/usr/bin/env bash
# Captures one view of a `tilekit texture preview` page with Debian's chromium, headless, WebGL2 on
# SwiftShader (no GPU, no display), network off. Writes a W x H PNG of the canvas (H >= 150).
# Usage: scripts/capture-preview.sh PAGE.html 'u=U&v=V&scale=S&seed=N&tilt=T[&method=M&aniso=A]' WxH OUT.png
#   TILEKIT_CHROMIUM  the browser (default: chromium)
set -euo pipefail
if [ $# -ne 4 ]; then
  echo "usage: $0 PAGE.html QUERY WxH OUT.png" >&2
  exit 2
fi
page=$(realpath "$1")
query=$2
size=$3
out=$4
[[ $size =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "capture-preview: size must be WxH, got '$size'" >&2; exit 2; }
w=${BASH_REMATCH[1]}
h=${BASH_REMATCH[2]}
# Chromium 156's headless window shows less than the requested height below about 145 px (the
# screenshot's lower part stays empty), so captures are at least 150 px tall.
((h >= 150 && w >= 1)) || { echo "capture-preview: the height must be at least 150 px, got $size" >&2; exit 2; }
[ -f "$page" ] || { echo "capture-preview: no page $page" >&2; exit 2; }
browser=${TILEKIT_CHROMIUM:-chromium}
command -v "$browser" >/dev/null || { echo "capture-preview: $browser is not installed (scripts/setup.sh installs it)" >&2; exit 1; }
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
rm -f "$out"
# --no-sandbox: root in a container has no user namespaces for chromium's sandbox; the page is ours.
# The --disable-*/--no-* flags keep the browser off the network (no updates, sync, metrics).
timeout "${TILEKIT_CAPTURE_SECONDS:-180}" "$browser" --headless=new --use-angle=swiftshader --enable-unsafe-swiftshader \
  --no-sandbox --force-device-scale-factor=1 --hide-scrollbars --no-first-run --no-default-browser-check \
  --disable-background-networking --disable-component-update --disable-sync --disable-extensions \
  --disable-default-apps --disable-domain-reliability --metrics-recording-only --no-pings --mute-audio \
  --user-data-dir="$profile" --window-size="$w,$h" --screenshot="$out" \
  "file://$page?capture=1&size=${w}x$h&$query" >"$profile/log" 2>&1 || {
  echo "capture-preview: $browser failed or timed out; its log:" >&2
  grep -v -e dbus -e zygote "$profile/log" >&2 || true
  exit 1
}
[ -s "$out" ] || { echo "capture-preview: no screenshot written" >&2; exit 1; }
