#!/usr/bin/env bash
# Configures and builds igm (Release) with its tests into ${IGM_BUILD_DIR:-build}. Extra args go to
# cmake (after the defaults, so they win). The tests are asked for explicitly: scripts/run.sh may
# have configured the same folder without them.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${IGM_BUILD_DIR:-build}"
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE="${IGM_BUILD_TYPE:-Release}" -DIGM_BUILD_TESTS=ON "$@"
cmake --build "$BUILD_DIR" -j "$(nproc)"
