#!/usr/bin/env bash
# Checks geolens as an installed package: builds it shared and static (Release, no tests, no
# benchmarks), installs each into a prefix of its own, then builds examples/consumer against each
# prefix twice, with find_package(geolens CONFIG) and with pkg-config alone, runs the four
# programs and the installed CLI, and checks that all four print the same; the same for
# examples/drag_session against the lens engine alone (geolens::lens, geolens-lens.pc), which must
# name and load none of the libraries the readers and renderers need; each module's pkg-config
# file names only what that module and those below it need (geolens-io no cairo or librsvg); and
# every installed header compiles alone. Assumes
# scripts/setup.sh has installed the packages; everything is built in a temporary folder, removed
# at the end (GEOLENS_PACKAGE_KEEP=1 keeps it). Stops at the first error, naming the step.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
jobs=$(bash scripts/jobs.sh)
work=$(mktemp -d "${TMPDIR:-/tmp}/geolens-package.XXXXXX")
if [ "${GEOLENS_PACKAGE_KEEP:-0}" = 1 ]; then
  echo "keeping $work"
else
  trap 'rm -rf "$work"' EXIT
fi

step() { echo "== $*"; }
fail() {
  echo "package_check: FAILED: $*" >&2
  exit 1
}
# Runs a command quietly, its output kept in $work/<name>.log and shown if it fails.
run() {
  local name=$1
  shift
  if ! "$@" >"$work/$name.log" 2>&1; then
    tail -n 40 "$work/$name.log" >&2
    fail "$name: $*"
  fi
}

for kind in shared static; do
  prefix=$work/prefix-$kind
  shared=$([ "$kind" = shared ] && echo ON || echo OFF)
  step "$kind: build and install into $prefix"
  # Configured for the default prefix and installed elsewhere: both package files must relocate.
  run "configure-$kind" cmake -S "$root" -B "$work/build-$kind" -DCMAKE_BUILD_TYPE=Release \
    -DBUILD_SHARED_LIBS="$shared" -DGEOLENS_BUILD_TESTS=OFF -DGEOLENS_BUILD_BENCH=OFF \
    -DGEOLENS_BUILD_VIEWER=OFF -DGEOLENS_BUILD_PYTHON=OFF
  run "build-$kind" cmake --build "$work/build-$kind" --target geolens_cli -j"$jobs"
  run "install-$kind" cmake --install "$work/build-$kind" --prefix "$prefix"
  "$prefix/bin/geolens" --version >/dev/null || fail "$kind: the installed CLI does not run"

  step "$kind: consumer with find_package(geolens CONFIG)"
  run "consumer-cmake-$kind" cmake -S "$root/examples/consumer" -B "$work/consumer-$kind" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix"
  grep -q "^geolens_DIR:PATH=$prefix/" "$work/consumer-$kind/CMakeCache.txt" ||
    fail "$kind: find_package found a geolens outside $prefix"
  run "consumer-cmake-build-$kind" cmake --build "$work/consumer-$kind" -j"$jobs"
  "$work/consumer-$kind/consumer" | tee "$work/out-cmake-$kind.txt" ||
    fail "$kind: the find_package consumer failed"

  step "$kind: consumer with pkg-config"
  export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
  query=(pkg-config --cflags --libs)
  if [ "$kind" = static ]; then query+=(--static); fi
  flags=$("${query[@]}" geolens) || fail "$kind: ${query[*]} geolens"
  echo "${query[*]} geolens: $flags"
  libdir=$(pkg-config --variable=libdir geolens)
  # shellcheck disable=SC2086  # the flags are words
  run "consumer-pkg-config-$kind" g++ -std=c++20 -O2 "$root/examples/consumer/main.cpp" \
    -o "$work/consumer-pc-$kind" $flags -Wl,-rpath,"$libdir"
  "$work/consumer-pc-$kind" | tee "$work/out-pc-$kind.txt" ||
    fail "$kind: the pkg-config consumer failed"
  unset PKG_CONFIG_PATH

  step "$kind: the lens engine alone (examples/drag_session), with find_package and pkg-config"
  run "drag-cmake-$kind" cmake -S "$root/examples/drag_session" -B "$work/drag-$kind" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix"
  run "drag-cmake-build-$kind" cmake --build "$work/drag-$kind" -j"$jobs"
  export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
  lens_flags=$("${query[@]}" geolens-lens) || fail "$kind: ${query[*]} geolens-lens"
  echo "${query[*]} geolens-lens: $lens_flags"
  unset PKG_CONFIG_PATH
  # shellcheck disable=SC2086  # the flags are words
  run "drag-pkg-config-$kind" g++ -std=c++20 -O2 "$root/examples/drag_session/main.cpp" \
    -o "$work/drag-pc-$kind" $lens_flags -Wl,-rpath,"$libdir"
  outside="spng|jpeg|cairo|rsvg|nifti|znz|tinyobj|libz\.|-lz\b|nlohmann|stb"
  if grep -Eq "$outside" <<<"$lens_flags"; then fail "$kind: geolens-lens names $lens_flags"; fi
  export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
  for module in io sources render eval; do
    "${query[@]}" "geolens-$module" >"$work/pc-$module-$kind.txt" ||
      fail "$kind: ${query[*]} geolens-$module"
  done
  unset PKG_CONFIG_PATH
  if grep -Eq "cairo|rsvg" "$work/pc-io-$kind.txt"; then
    fail "$kind: geolens-io names $(cat "$work/pc-io-$kind.txt")"
  fi
  for exe in "$work/drag-$kind/drag_session" "$work/drag-pc-$kind"; do
    "$exe" > "$work/drag-out-$kind-$(basename "$exe").txt" || fail "$exe failed"
    libraries=$(ldd "$exe")
    modules="libgeolens_(io|sources|render|eval)\.so"
    if grep -Eq "$outside|$modules" <<<"$libraries"; then
      fail "$exe, which solves lenses only, loads: $(grep -E "$outside|$modules" <<<"$libraries")"
    fi
    if [ "$kind" = shared ]; then
      grep -q "libgeolens_lens\.so.* => $prefix/" <<<"$libraries" ||
        fail "$exe does not load libgeolens_lens.so from $prefix"
    fi
  done

  # The shared consumers load the installed modules they use (the lens engine and the renderer,
  # and any other only from $prefix); the static ones need none.
  for exe in "$work/consumer-$kind/consumer" "$work/consumer-pc-$kind"; do
    libraries=$(ldd "$exe")
    if [ "$kind" = shared ]; then
      for module in lens render; do
        grep -q "libgeolens_$module\.so.* => $prefix/" <<<"$libraries" ||
          fail "$exe does not load libgeolens_$module.so from $prefix"
      done
      if grep "libgeolens" <<<"$libraries" | grep -vq " => $prefix/"; then
        fail "$exe loads a libgeolens from outside $prefix: $(grep libgeolens <<<"$libraries")"
      fi
    elif grep -q libgeolens <<<"$libraries"; then
      fail "$exe loads a shared libgeolens"
    fi
  done
done

step "the four consumers agree"
for out in "$work"/out-*.txt; do
  cmp -s "$out" "$work/out-cmake-shared.txt" || fail "$(basename "$out") differs from out-cmake-shared.txt"
done
step "the four drag_session builds agree"
cat "$work/drag-out-shared-drag_session.txt"
for out in "$work"/drag-out-*.txt; do
  cmp -s "$out" "$work/drag-out-shared-drag_session.txt" || fail "$(basename "$out") differs"
done
step "every installed header compiles alone against the installed prefix"
# A public header that includes a private one (not installed) or misses an include of its own
# fails here; the flags are the package's own (pkg-config).
cflags=$(PKG_CONFIG_PATH="$work/prefix-shared/lib/pkgconfig" pkg-config --cflags geolens)
(cd "$work/prefix-shared/include" && find geolens -name '*.h' | sort) >"$work/headers.txt"
# shellcheck disable=SC2086 # the flags are words
xargs -P "$jobs" -I{} sh -c 'echo "#include \"{}\"" | c++ -std=c++20 -fsyntax-only $0 -x c++ - ||
  { echo "package_check: {} does not compile alone" >&2; exit 255; }' "$cflags" <"$work/headers.txt" ||
  fail "an installed header does not compile alone"
echo "$(wc -l <"$work/headers.txt") headers, each compiled alone"

step "installed (shared prefix)"
(cd "$work/prefix-shared" && find . -type f -o -type l | sort | grep -v '^./include/geolens/.*\.h$')
echo "and $(find "$work/prefix-shared/include/geolens" -name '*.h' | wc -l) headers in include/geolens/"
echo "package_check: OK"
