#!/usr/bin/env bash
# The main job on a fresh machine: set up, build in Release, and run `rastercheck check` on the
# built-in default scenes, writing renders, heatmaps and a JSON report to out/.
# Extra arguments go to `rastercheck check` (scenes, --mode affine, thresholds, ...).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
exec "${RASTERCHECK_BUILD_DIR:-build}/app/rastercheck" check --out out --json out/check.json "$@"
