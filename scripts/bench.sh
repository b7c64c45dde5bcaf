#!/usr/bin/env bash
# Builds geolens (Release, in build/) with the benchmark-only CGAL and runs both benchmark
# executables, medians of 3 repetitions: geolens_bench (the stage timings, bench/README.md) and
# geolens_cgal_bench (CGAL's ARAP parameterizer against geolens's flattening, issue 5). Run as
# root on Debian 12; takes a few minutes, most of it CGAL on the 200 x 200 grid.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_packages.sh libcgal-dev
bash scripts/setup.sh
echo "nproc: $(nproc)"
for exe in geolens_bench geolens_cgal_bench; do
  "./build/bench/$exe" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
done
