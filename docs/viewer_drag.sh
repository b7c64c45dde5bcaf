#!/usr/bin/env bash
# Makes docs/viewer_drag_{1,2,3}.jpg, docs/viewer.md's three frames of a drag in geolens-view, with
# the viewer itself: a zoom-2.5 lens on the demo map dragged across it, a
# screenshot every 15 frames (each once the solver has answered). Needs xvfb-run.
# Usage: bash docs/viewer_drag.sh [BUILD_DIR]   (default build/)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
script="$(mktemp)"
trap 'rm -f "$script"' EXIT
cat > "$script" << 'END'
set panel off
frame 2 screenshot docs/viewer_drag_1.jpg
frame 3 drag 1 560 560 15
frame 20 screenshot docs/viewer_drag_2.jpg
frame 21 drag 1 760 380 15
frame 38 screenshot docs/viewer_drag_3.jpg
quit
END
xvfb-run -a -s "-screen 0 1280x1024x24" "$build/geolens-view" examples/demo.png \
  --lens circle:330,330,80:2.5 --size 320x320 --script "$script"
