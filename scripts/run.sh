#!/usr/bin/env bash
# Set-up command 1: installs the packages igm needs, builds it, and runs the main job (igm) on its
# built-in default mesh. Extra arguments are passed to igm.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh core
# Only the CLI and the libraries it needs (the tests, benchmarks and Python module are built by
# scripts/test.sh): a few minutes on two cores.
BUILD_DIR="${IGM_BUILD_DIR:-build}"
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE="${IGM_BUILD_TYPE:-Release}" -DIGM_BUILD_TESTS=OFF -DIGM_BUILD_BENCH=OFF \
  -DIGM_BUILD_PYTHON=OFF
cmake --build "$BUILD_DIR" -j "$(nproc)" --target igm
"$BUILD_DIR/igm" "$@"
