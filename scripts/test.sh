#!/usr/bin/env bash
# Set-up command 2 (and CI): installs the packages, builds, and runs the whole test suite.
# Tests that need ../shared read IGM_DATA_DIR (default: ../shared beside the checkout).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
ctest --test-dir "${IGM_BUILD_DIR:-build}" --output-on-failure -j "$(nproc)"
