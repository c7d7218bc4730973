#!/usr/bin/env bash
# Set up, build, and run the whole test suite through ctest; then hold the gate to the wrong
# rasterizers of tests/mutants.txt, and the tests of compare, the audit, check, bench, the
# HTML report and the printed figures to their lenient mutants there (scripts/mutants.pl); fuzz every input parser for a bounded time
# (scripts/fuzz.sh) and run the whole suite again under ASan + UBSan.
#   scripts/test.sh           everything (what CI runs)
#   scripts/test.sh --quick   the Release suite only
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
# Each phase's time, printed as it ends and summed up at the end: CI has 90 minutes.
phases=""
phase_start=$SECONDS
phase() {
  local took=$((SECONDS - phase_start))
  phases+="$(printf '%5d s  %s' "$took" "$1")"$'\n'
  echo "== $1: ${took} s"
  phase_start=$SECONDS
}
trap 'status=$?; [[ -n "$phases" ]] && printf "== time per phase (%d s in all)\n%s" "$SECONDS" "$phases"; exit $status' EXIT
scripts/setup.sh --test
phase "setup"
scripts/build.sh
phase "Release build"
(cd "${RASTERCHECK_BUILD_DIR:-build}" && ctest --output-on-failure -j "$jobs")
phase "Release suite"
[[ "${1:-}" == "--quick" ]] && exit 0

echo "== the gate against wrong rasterizers and itself made lenient (tests/mutants.txt): each must fail check default hard, or the tests of compare, the audit, check, bench, the report and the printed figures"
perl scripts/mutants.pl --build "${RASTERCHECK_BUILD_DIR:-build}"
phase "mutants"

echo "== fuzzing every input parser (${FUZZ_SECONDS:-30}s each)"
scripts/fuzz.sh
phase "fuzzing (build and runs)"

echo "== the whole suite under AddressSanitizer + UndefinedBehaviorSanitizer"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRASTERCHECK_SANITIZE=ON > /dev/null
cmake --build build-asan -j "$jobs"
phase "sanitizer build"
(cd build-asan && ctest --output-on-failure -j "$jobs")
phase "sanitizer suite"
