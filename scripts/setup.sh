#!/usr/bin/env bash
# Installs geolens's build dependencies from Debian's packages and builds it (Release) in build/.
# Run as root on Debian 12. Why each package: Eigen (linear algebra, sparse Cholesky), CLI11
# (command line), nlohmann-json (stats), libspng and libjpeg-turbo (PNG and JPEG), stb (a
# stroke font for plot labels), GoogleTest, Google Benchmark.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(build-essential cmake pkg-config libeigen3-dev libcli11-dev nlohmann-json3-dev
          libspng-dev libjpeg62-turbo-dev libstb-dev libgtest-dev libbenchmark-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
