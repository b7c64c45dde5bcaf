#!/usr/bin/env bash
# The api_docs test (cmake/docs.cmake): runs doxygen ($DOXYGEN, else doxygen on PATH) with the
# Doxyfile CMake configured into BUILD_DIR/docs/, which writes the API reference to
# BUILD_DIR/docs/api/ and its warnings to BUILD_DIR/docs/doxygen-warnings.txt; prints them and
# fails if there is any (an undocumented public symbol, a reference doxygen cannot resolve).
# Usage: bash scripts/api_docs.sh BUILD_DIR
set -euo pipefail
build="${1:?usage: scripts/api_docs.sh BUILD_DIR}"
doxyfile="$build/docs/Doxyfile"
log="$build/docs/doxygen-warnings.txt"
if [ ! -f "$doxyfile" ]; then
  echo "api_docs: no $doxyfile: configure $build with doxygen installed" >&2
  exit 1
fi
rm -f "$log"
"${DOXYGEN:-doxygen}" "$doxyfile"
if [ -s "$log" ]; then
  echo "api_docs: FAILED: doxygen warned ($(wc -l <"$log") lines of $log):"
  cat "$log"
  exit 1
fi
echo "api_docs: no warnings; the reference is $build/docs/api/index.html"
