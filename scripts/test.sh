#!/usr/bin/env bash
# Set up, build, and run the whole test suite through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --test
scripts/build.sh
cd "${RASTERCHECK_BUILD_DIR:-build}"
ctest --output-on-failure -j "$(nproc)"
