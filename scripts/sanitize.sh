#!/usr/bin/env bash
# Builds the library, the CLI and the tests with AddressSanitizer + UndefinedBehaviorSanitizer in
# build-asan/ (-O1 -g, Eigen's assertions on) and runs the whole suite; any finding, in a test or in
# a geolens process a CLI test starts, fails the run. Assumes scripts/setup.sh has installed the
# packages.
set -euo pipefail
cd "$(dirname "$0")/.."
build="build-asan"
logs="$PWD/$build/sanitizer-logs"
flags=("-fsanitize=address,undefined" -fno-omit-frame-pointer -fno-sanitize-recover=undefined)

# LeakSanitizer needs ptrace, which some containers forbid: probe it on an empty program.
rm -rf "$logs"
mkdir -p "$logs"
echo 'int main() { return 0; }' > "$build/lsan_probe.cpp"
"${CXX:-c++}" "${flags[@]}" "$build/lsan_probe.cpp" -o "$build/lsan_probe"
if ASAN_OPTIONS=detect_leaks=1 "$build/lsan_probe" 2> /dev/null; then
  leaks=1
else
  leaks=0
  echo "sanitize.sh: LeakSanitizer does not work here; leak checking is off" >&2
fi

# Every report goes to a file in $logs (suffixed with the pid) instead of stderr, so a finding in
# a child process is caught even if its exit code is one the test expects, and is printed below.
common="halt_on_error=1:print_stacktrace=1:exitcode=86:log_path=$logs/report"
export ASAN_OPTIONS="$common:detect_leaks=$leaks:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="$common"
# Leaks in system libraries that keep caches for the process's life (scripts/lsan.supp says which).
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DCMAKE_CXX_FLAGS="${flags[*]}" -DCMAKE_EXE_LINKER_FLAGS="${flags[*]}" -DGEOLENS_BUILD_BENCH=OFF \
  -DGEOLENS_BUILD_PYTHON=OFF  # a sanitized module does not load into an uninstrumented python3
cmake --build "$build" -j"$(bash scripts/jobs.sh)"
status=0
ctest --test-dir "$build" --output-on-failure -j"$(bash scripts/jobs.sh)" || status=$?
if compgen -G "$logs/report*" > /dev/null; then
  echo "sanitize.sh: sanitizer findings:" >&2
  cat "$logs"/report* >&2
  status=1
fi
exit "$status"
