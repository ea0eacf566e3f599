#!/usr/bin/env bash
# Builds gridtopo and runs the whole test suite (CTest + GoogleTest). Exits non-zero if any test fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
BUILD_DIR=${GRIDTOPO_BUILD_DIR:-build}
ctest --test-dir "$BUILD_DIR" --output-on-failure -j"$(nproc)" --timeout 900
