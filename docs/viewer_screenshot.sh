#!/usr/bin/env bash
# Makes docs/viewer.png, the README's picture of geolens-view, with the viewer itself: two
# lenses on the demo map, the first selected, the panel shown; then reduced to 256 colours by
# pngquant (Debian's pngquant, for this picture only, when installed) to stay small. Needs
# xvfb-run.
# Usage: bash docs/viewer_screenshot.sh [BUILD_DIR]   (default build/)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
script="$(mktemp)"
trap 'rm -f "$script"' EXIT
printf 'select 1\nframe 40 screenshot docs/viewer.png panel\nquit\n' > "$script"
xvfb-run -a -s "-screen 0 1280x1024x24" "$build/geolens-view" examples/demo.png \
  --lens circle:700,380,70:2.5 --lens circle:760,760,45:2 --size 780x470 --script "$script"
if command -v pngquant > /dev/null; then
  pngquant --force --skip-if-larger --output docs/viewer.png 256 docs/viewer.png
else
  echo "viewer_screenshot.sh: pngquant not installed; docs/viewer.png left at full colour" >&2
fi
