#!/usr/bin/env bash
# Set-up command 1: installs the packages, builds, and runs the main job (igm) on its
# built-in default mesh. Extra arguments are passed to igm.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
"${IGM_BUILD_DIR:-build}/igm" "$@"
