#!/usr/bin/env bash
# Installs geolens's build dependencies from Debian's packages and builds it (Release) in build/.
# Run as root on Debian 12. Why each package: Eigen (linear algebra, sparse Cholesky), CLI11
# (command line), nlohmann-json (stats), libspng and libjpeg-turbo (PNG and JPEG), stb (a
# stroke font for plot labels), GoogleTest, Google Benchmark. The viewer, geolens-view: GLFW
# (window, input), libepoxy (loads OpenGL 3.3 core), Dear ImGui (the panel; its static library
# is built with imgui_freetype, so freetype too); its tests run it on an Xvfb server of their own
# (xvfb; xauth for the README's xvfb-run commands, which xvfb only recommends) with Mesa's software
# OpenGL (libgl1-mesa-dri).
# The Python module: pybind11 and Python's headers build it, numpy and pytest test it (with
# Debian's /usr/bin/python3, which has them, whatever python3 comes first on PATH).
# 3D sources: tinyobjloader (OBJ meshes), libnifti2-dev (NIfTI volumes; brings niftiio and
# znzlib), zlib (gzip-encoded volumes).
# SVG and vector-map sources: librsvg (rasterizes SVG per tile), cairo (draws maps and labels
# anti-aliased). Not installed here: libmagics++-data (170 MB), whose Natural Earth shapefiles
# examples/europe.geojson was converted from once (scripts/natural_earth_to_geojson.py).
# The API reference (`--target docs`, ctest's api_docs): doxygen.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(build-essential cmake pkg-config libeigen3-dev libcli11-dev nlohmann-json3-dev
          libspng-dev libjpeg62-turbo-dev libstb-dev libgtest-dev libbenchmark-dev
          libglfw3-dev libepoxy-dev libimgui-dev libfreetype-dev xvfb xauth libgl1-mesa-dri
          pybind11-dev python3-dev python3-numpy python3-pytest
          libtinyobjloader-dev libnifti2-dev zlib1g-dev
          librsvg2-dev libcairo2-dev doxygen)
bash scripts/install_packages.sh "${packages[@]}"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3
cmake --build build -j"$(bash scripts/jobs.sh)"
