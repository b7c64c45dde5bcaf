#!/usr/bin/env bash
# Sets up, then magnifies the bundled demo map with one geometric lens at zoom 2. Writes only
# under out/: out/demo_magnified.png, out/demo_stats.json and out/demo_before_after.jpg (the
# README's docs/demo_before_after.jpg is a copy of that picture, tracked).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mkdir -p out
./build/geolens magnify examples/demo.png -o out/demo_magnified.png \
  --lens circle:430,470,150:2 --size 640x640 --stats out/demo_stats.json \
  --before-after out/demo_before_after.jpg
echo "wrote out/demo_magnified.png, out/demo_stats.json, out/demo_before_after.jpg"
