#!/usr/bin/env bash
# The browser build's tests (issue 31): the engine built (scripts/web_build.sh) and tested under
# node (web/test/: against the native CLI, errors, memory, the npm package), then the pages in
# Debian's chromium, headless with SwiftShader's WebGL2, driven by playwright-core from npm
# (web/browser-test/); both with node's own test runner. The tests compare with the native CLI,
# so the native build (scripts/setup.sh) comes first; .ci/run runs this after the native suite.
# About 6 minutes on 2 cores, installing included.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/web_build.sh
bash scripts/install_packages.sh chromium
# npm comes with some node packages (NodeSource's); Debian's node needs Debian's npm.
command -v npm >/dev/null || bash scripts/install_packages.sh npm
(cd web && npm ci --no-audit --no-fund --loglevel=error)
node --test web/test/ web/browser-test/
