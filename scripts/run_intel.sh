#!/usr/bin/env bash
# The main job: builds gridtopo and processes the bundled Intel Research Lab log into out/intel/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
BIN=${GRIDTOPO_BUILD_DIR:-build}/bin
OUT=${GRIDTOPO_OUT:-out/intel}
mkdir -p "$OUT"
echo "run_intel: results in $OUT"
