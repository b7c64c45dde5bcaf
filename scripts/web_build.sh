#!/usr/bin/env bash
# The lens engine in WebAssembly (issue 31, web/): installs Debian's emscripten and node, builds
# web/dist/geolens.mjs + geolens.wasm (web/CMakeLists.txt, in build-web/): about 2.5 minutes on
# 2 cores. Its tests: scripts/web_test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_packages.sh emscripten nodejs libeigen3-dev
# emcc's JavaScript tools need Debian's node modules (acorn).
export NODE_PATH=/usr/share/nodejs
emcmake cmake -S web -B build-web -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build-web -j"$(bash scripts/jobs.sh)"
mkdir -p web/dist
cp build-web/geolens.mjs build-web/geolens.wasm web/dist/
ls -l web/dist
