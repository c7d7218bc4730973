#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) into build-fuzz/ and runs each for a
# bounded time (FUZZ_SECONDS, default 30) from the seed corpus in fuzz/corpus/. Exits non-zero
# when a target finds a crash, a leak or a sanitizer report; the reproducer is left in
# build-fuzz/findings/. Needs: clang, libclang-rt-14-dev (scripts/setup.sh --test).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-30}
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DRASTERCHECK_FUZZ=ON -DRASTERCHECK_BUILD_TESTS=OFF > /dev/null
cmake --build build-fuzz -j "$(nproc)" --target fuzz_obj fuzz_gltf fuzz_scene_file fuzz_exr_pair fuzz_baseline fuzz_bench_json rastercheck

work=build-fuzz/work
rm -rf "$work"
mkdir -p "$work" build-fuzz/findings
for target in obj gltf scene; do cp -r "fuzz/corpus/$target" "$work/$target"; done
# EXR seeds are rendered, not committed: a raster and a reference image joined at the split mark.
mkdir -p "$work/exr"
for scene in cube sphere; do
  build-fuzz/app/rastercheck render "$scene" --size 8x6 --backend raster -o "$work/a.exr" > /dev/null
  build-fuzz/app/rastercheck render "$scene" --size 8x6 --backend reference -o "$work/b.exr" > /dev/null
  { cat "$work/a.exr"; printf -- '--RC-SPLIT--'; cat "$work/b.exr"; } > "$work/exr/$scene.pair"
done
# Baseline seeds are written the same way: a compare report and a check report of 8x6 renders.
mkdir -p "$work/baseline"
build-fuzz/app/rastercheck compare "$work/a.exr" "$work/b.exr" --json "$work/baseline/compare.json" > /dev/null
build-fuzz/app/rastercheck check cube sphere --size 8x6 -q --json "$work/baseline/check.json" > /dev/null
mkdir -p "$work/bench"
build-fuzz/app/rastercheck bench cube --size 8x6 --runs 1 -q --json "$work/bench/cube.json" > /dev/null

status=0
for pair in obj:fuzz_obj gltf:fuzz_gltf scene:fuzz_scene_file exr:fuzz_exr_pair baseline:fuzz_baseline bench:fuzz_bench_json; do
  corpus=${pair%%:*}
  target=${pair##*:}
  echo "fuzz: $target for ${seconds}s"
  # The targets write each input to a file under TMPDIR (fuzz/fuzz_input.h): keep it in the
  # work folder, so nothing is left in the system's temporary folder.
  mkdir -p "$work/tmp"
  if ! TMPDIR="$PWD/$work/tmp" "build-fuzz/fuzz/$target" "$work/$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=512 \
       -max_len=65536 -artifact_prefix=build-fuzz/findings/"$target"- -print_final_stats=1 \
       > "build-fuzz/$target.log" 2>&1; then
    echo "fuzz: $target FOUND A PROBLEM; see build-fuzz/$target.log and build-fuzz/findings/"
    tail -40 "build-fuzz/$target.log"
    status=1
  else
    grep -E "stat::number_of_executed_units|cov:" "build-fuzz/$target.log" | tail -2 | sed "s/^/fuzz: $target: /"
  fi
done
exit $status
