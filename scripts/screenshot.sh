#!/usr/bin/env bash
# Screenshot a page of the built site with headless Chromium (no network, throw-away profile).
#   scripts/screenshot.sh PAGE.html [OUT.png] [WIDTHxHEIGHT]
#   scripts/screenshot.sh _build/html/index.html /tmp/index.png          # desktop, 1280x900
#   scripts/screenshot.sh _build/html/sparc.html /tmp/phone.png 390x844  # phone
# A tall size (1280x4000) shows a whole page: the screenshot is of the window, not the document.
set -euo pipefail
page=${1:?usage: scripts/screenshot.sh PAGE.html [OUT.png] [WIDTHxHEIGHT]}
out=${2:-screenshot.png}
size=${3:-1280x900}
browser=${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}
[ -n "$browser" ] || { echo "screenshot.sh: no chromium found (apt-get install chromium)" >&2; exit 1; }
[ -f "$page" ] || { echo "screenshot.sh: no such page: $page" >&2; exit 1; }
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
"$browser" --headless --no-sandbox --disable-gpu --disable-background-networking \
  --disable-component-update --disable-sync --no-first-run --hide-scrollbars \
  --user-data-dir="$profile" --window-size="${size/x/,}" --virtual-time-budget=3000 \
  --screenshot="$(realpath -m "$out")" "file://$(realpath "$page")" 2>/dev/null
echo "$out"
