#!/usr/bin/env bash
# Installs those of the Debian packages named as arguments that are missing (apt-get update
# first, only then): the one place setup.sh, fuzz.sh and bench.sh install what they need. Run as
# root.
set -euo pipefail
missing=()
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
fi
