#!/usr/bin/env bash
# Fuzzes the readers: builds the libFuzzer targets of fuzz/ (clang 14; the library and the
# targets with AddressSanitizer + UndefinedBehaviorSanitizer, -O1 -g, Eigen's assertions on) in
# build-fuzz/ and runs each for SECONDS (default 10) on a copy of its seed corpus,
# fuzz/corpus/<kind>/, which is never written to: `bash scripts/fuzz.sh 600` for a long run,
# `bash scripts/fuzz.sh 600 ply nrrd` for some of the targets (fuzz/<kind>_fuzz.cpp). Any
# finding (a crash, a sanitizer report, an exception other than InvalidInput escaping a reader, a
# leak, an input slower than 10 s, more than 2 GiB) fails the run, naming the target, its log and
# the input that found it (build-fuzz/findings/<kind>/); copy that input into
# fuzz/corpus/<kind>/ as regression-<what> once the reader is fixed. Run as root on Debian 12:
# installs clang and libFuzzer (clang-14, libclang-rt-14-dev) and the library's packages (those
# of scripts/setup.sh that the library needs) when missing.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-10}"
shift || true
kinds=("$@")
if [ ${#kinds[@]} -eq 0 ]; then
  for source in fuzz/*_fuzz.cpp; do kinds+=("$(basename "$source" _fuzz.cpp)"); done
fi
build="build-fuzz"
# A fixed seed (GEOLENS_FUZZ_SEED, default 1) makes a run's inputs a property of the commit and the
# corpus; GEOLENS_FUZZ_RUNS caps the inputs a target runs (default none): CI runs a capped prefix
# of a sequence a longer run here has passed, so its verdict does not depend on its speed.
seed="${GEOLENS_FUZZ_SEED:-1}"
runs_cap="${GEOLENS_FUZZ_RUNS:--1}"
packages=(build-essential cmake pkg-config clang-14 libclang-rt-14-dev
          libeigen3-dev libcli11-dev nlohmann-json3-dev libspng-dev libjpeg62-turbo-dev libstb-dev
          libtinyobjloader-dev libnifti2-dev zlib1g-dev librsvg2-dev libcairo2-dev)
bash scripts/install_packages.sh "${packages[@]}"

start=$SECONDS
cmake -S . -B "$build" -DGEOLENS_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g"
cmake --build "$build" --target fuzz_targets -j"$(bash scripts/jobs.sh)"
echo "fuzz.sh: built in $((SECONDS - start)) s"

# LeakSanitizer needs ptrace, which some containers forbid: probe it on an empty program.
echo 'int main() { return 0; }' > "$build/lsan_probe.cpp"
clang++-14 -fsanitize=address "$build/lsan_probe.cpp" -o "$build/lsan_probe"
leaks=1
if ! ASAN_OPTIONS=detect_leaks=1 "$build/lsan_probe" 2> /dev/null; then
  leaks=0
  echo "fuzz.sh: LeakSanitizer does not work here; leak checking is off" >&2
fi

# The targets write their inputs into folders of their own under TMPDIR: keep them in build-fuzz/.
export TMPDIR="$PWD/$build/tmp"
rm -rf "$TMPDIR" "$build/runs" "$build/findings"
mkdir -p "$TMPDIR"
failed=()
for kind in "${kinds[@]}"; do
  # Inputs a few times the seeds' size: big enough for the formats' variants, small enough that
  # an input costs milliseconds (a larger image or volume only costs more time).
  case "$kind" in
    image|mask|tiles|levels) max_len=16384 ;;
    *) max_len=4096 ;;
  esac
  corpus="$PWD/$build/runs/$kind"
  findings="$PWD/$build/findings/$kind"
  mkdir -p "$corpus" "$findings"
  cp -r "fuzz/corpus/$kind/." "$corpus/"
  log="$PWD/$build/runs/$kind.log"
  status=0
  ASAN_OPTIONS="detect_leaks=$leaks" \
    LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0" \
    "$build/fuzz/${kind}_fuzz" -max_total_time="$seconds" -runs="$runs_cap" -seed="$seed" \
    -rss_limit_mb=2048 -timeout=10 -max_len="$max_len" -detect_leaks="$leaks" \
    -print_final_stats=1 -artifact_prefix="$findings/" "$corpus" > "$log" 2>&1 || status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  if [ "$status" -ne 0 ] || compgen -G "$findings/*" > /dev/null; then
    echo "fuzz.sh: $kind: FINDING (exit $status); log $log" >&2
    grep -E '^(==[0-9]+==ERROR|SUMMARY|fuzz: finding|terminate called|  what\(\))' "$log" \
      | head -5 >&2 || true
    for input in "$findings"/*; do
      [ -e "$input" ] && echo "fuzz.sh: $kind: input: $input (replay:" \
        "GEOLENS_FUZZ_VERBOSE=1 $build/fuzz/${kind}_fuzz $input)" >&2
    done
    failed+=("$kind")
  else
    echo "fuzz.sh: $kind: ${runs:-?} runs (within ${seconds} s), no finding"
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz.sh: findings in: ${failed[*]}" >&2
  exit 1
fi
