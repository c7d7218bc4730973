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
# The sanitizer build runs in the background from the mutants on (below); it ends with the script.
sanitizer_build=""
trap 'status=$?; [[ -n "$sanitizer_build" ]] && kill -- "-$sanitizer_build" 2>/dev/null
      [[ -n "$phases" ]] && printf "== time per phase (%d s in all)\n%s" "$SECONDS" "$phases"; exit $status' EXIT
scripts/setup.sh --test
phase "setup"
scripts/build.sh
phase "Release build"
(cd "${RASTERCHECK_BUILD_DIR:-build}" && ctest --output-on-failure -j "$jobs")
phase "Release suite"
[[ "${1:-}" == "--quick" ]] && exit 0

# The sanitizer build takes both cores for about 17 minutes, and the mutants keep one busy (each
# rebuilds one file and runs one check or test). So it builds beside the mutants and the
# fuzzing, at a lower priority, from a copy of the source taken now, since the mutants edit
# this one in turn. The copy is refreshed, not remade, so that a second run builds only what
# changed.
echo "== the sanitizer build (ASan + UBSan) starts in the background: build-sanitize/build from a copy in build-sanitize/src"
mkdir -p build-sanitize/src
tar -cf - --exclude=./.git --exclude='./build*' --exclude=./out . | tar -xf - -C build-sanitize/src
# Its tests read ../shared/data beside this checkout, not beside the copy.
setsid --wait bash -c "cmake -S build-sanitize/src -B build-sanitize/build -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DRASTERCHECK_SANITIZE=ON -DRASTERCHECK_SHARED_DATA_DIR='$PWD/../shared/data' > /dev/null &&
  nice -n 10 cmake --build build-sanitize/build -j $jobs" \
  > build-sanitize/build.log 2>&1 &
sanitizer_build=$!
sanitizer_start=$SECONDS

echo "== the gate against wrong rasterizers and itself made lenient (tests/mutants.txt): each must fail check default hard, or the tests of compare, the audit, check, bench, the report and the printed figures"
perl scripts/mutants.pl --build "${RASTERCHECK_BUILD_DIR:-build}"
phase "mutants"

echo "== fuzzing every input parser (${FUZZ_SECONDS:-30}s each)"
scripts/fuzz.sh
phase "fuzzing (build and runs)"

echo "== the whole suite under AddressSanitizer + UndefinedBehaviorSanitizer"
build_status=0
wait "$sanitizer_build" || build_status=$?
sanitizer_build=""
cat build-sanitize/build.log
if ((build_status != 0)); then
  echo "the sanitizer build failed (exit $build_status): build-sanitize/build.log above"
  exit 1
fi
echo "== the sanitizer build took $((SECONDS - sanitizer_start)) s, beside the mutants and the fuzzing"
phase "sanitizer build (what was left of it)"
(cd build-sanitize/build && ctest --output-on-failure -j "$jobs")
phase "sanitizer suite"
