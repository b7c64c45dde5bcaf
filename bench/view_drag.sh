#!/usr/bin/env bash
# Frame time of geolens-view (issue 15, "How it is measured"): a circle lens (r = 150, zoom 2)
# dragged across a 2048 x 2048 image over 300 frames in a 1280 x 1024 window under Xvfb and
# Mesa's software OpenGL, at 100 x 100 and 200 x 200 meshes, next to the floor the same program
# measures: the image alone drawn every frame (two textured triangles over the same area, no
# lens, --redraw). Prints each run's --stats lines (median and 95th percentile of the frame time
# and of move-to-shown, the median solve shown, and what the picture cache did). The runs marked
# --redraw draw every frame afresh (the image in place as one quad, the triangles that move over
# it) instead of copying the cached picture.
# Usage: bash bench/view_drag.sh [BUILD_DIR]   (default build/; needs geolens and geolens-view)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# The demo map upscaled to 2048 x 2048 through a zoom-1 lens (the identity).
"$build/geolens" magnify examples/demo.png -o "$work/big.png" --lens circle:512,512,10:1 \
  --size 2048x2048
printf 'drag 1 1750 1024 300\nframe 301 quit\n' > "$work/drag.txt"
printf 'frame 300 quit\n' > "$work/still.txt"
view() { xvfb-run -a -s "-screen 0 1280x1024x24" "$build/geolens-view" "$work/big.png" \
  --size 1280x1024 --stats "$@"; }
stats() { grep -E '^(frames|picture)'; }
echo "floor (no lens, --redraw):";  view --script "$work/still.txt" --redraw | stats
echo "no lens, cached:";             view --script "$work/still.txt" | stats
for mesh in 100 200; do
  lens=(--lens circle:300,1024,150:2 --mesh "$mesh")
  echo "drag, $mesh x $mesh mesh:";           view "${lens[@]}" --script "$work/drag.txt" | stats
  echo "still lens, $mesh x $mesh:";          view "${lens[@]}" --script "$work/still.txt" | stats
  echo "drag, $mesh x $mesh, --redraw:";      view "${lens[@]}" --script "$work/drag.txt" --redraw | stats
  echo "still lens, $mesh x $mesh, --redraw:"; view "${lens[@]}" --script "$work/still.txt" --redraw | stats
done
