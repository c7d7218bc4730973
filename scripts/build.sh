#!/usr/bin/env bash
# Configures and builds rastercheck in Release into build/ (or $RASTERCHECK_BUILD_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${RASTERCHECK_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build_dir" -j "$(nproc)"
