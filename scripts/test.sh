#!/usr/bin/env bash
# Set-up command 2 (and CI): installs the packages, builds, and runs the whole test suite twice:
#   1. Release build in ${IGM_BUILD_DIR:-build};
#   2. AddressSanitizer + UndefinedBehaviorSanitizer build (-DIGM_SANITIZE=ON, RelWithDebInfo,
#      no benchmarks) in ${IGM_ASAN_BUILD_DIR:-build-asan}: every test again (the 1M-face torus,
#      cheese, the two normal forms of ~150k vertices and a generated genus 200 only in the
#      Release run; the 1M-face sphere on 100k faces), with a twentieth of the random meshes of
#      tests/random (IGM_RANDOM_SCALE=0.05: ~10x slower under the sanitizers; the plain run does
#      them all).
#      IGM_TEST_ASAN=0 skips this part (for quick local runs; CI always runs it).
#   The fuzz targets are built with GCC in both runs and replay their corpus (fuzz/corpus) as
#   tests; IGM_TEST_FUZZ=1 also builds them with clang + libFuzzer between the two runs and runs
#   each a few seconds (scripts/fuzz.sh smoke: ~4.5 min on 2 cores, most of it the clang build of
#   the library; left out of CI by default to keep it under 45 minutes).
# Tests that need ../shared read IGM_DATA_DIR (default: ../shared beside the checkout).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh -DIGM_BUILD_BENCH=ON -DIGM_BUILD_PYTHON=ON
ctest --test-dir "${IGM_BUILD_DIR:-build}" --output-on-failure -j "$(nproc)"

# With IGM_TEST_FUZZ=1: the fuzz targets with clang + libFuzzer, built (only they, at -O1), each
# run a few seconds from its corpus (scripts/fuzz.sh smoke).
if [ "${IGM_TEST_FUZZ:-0}" != 0 ]; then
  echo "[test] the fuzz targets with clang: built, each run a few seconds (scripts/fuzz.sh smoke)"
  bash scripts/fuzz.sh smoke
fi

if [ "${IGM_TEST_ASAN:-1}" != 0 ]; then
  ASAN_DIR="${IGM_ASAN_BUILD_DIR:-build-asan}"
  echo "[test] the whole suite again under AddressSanitizer + UndefinedBehaviorSanitizer ($ASAN_DIR)"
  # -g1: line tables for the sanitizers' stack traces, without the full debug info (a shorter
  # build).
  IGM_BUILD_DIR="$ASAN_DIR" IGM_BUILD_TYPE=RelWithDebInfo bash scripts/build.sh -DIGM_SANITIZE=ON -DIGM_BUILD_BENCH=OFF -DIGM_BUILD_PYTHON=OFF \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG"
  # The slowest cases under the sanitizers (30-70 s each there; their code paths are run by the
  # smaller cases too) are left to the Release run.
  ASAN_RELEASE_ONLY='normal form \(handle slides\)|--restarts: the restarts|generated genus 12, 25 and 50|sizing: --quads Q lands|ring bound: no cut|same bytes alone and under load|generated meshes of genus 1 to 200 are cut|the tightening keeps the root|restarts on shuffled vertex ids|from genus 30 on the crosses run alone|shared clean meshes of genus >= 1 are certified|shared spheres \(tetrahedron \.\. armadillo|genus 2\.\.7 generated meshes, odd and even, every layout|shared open meshes, meshes with several components, and non-manifold'
  # Any report fails the test: UBSan is built with -fno-sanitize-recover, ASan aborts on error.
  ASAN_OPTIONS="abort_on_error=1:detect_leaks=1" IGM_RANDOM_SCALE=0.05 \
  UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
    ctest --test-dir "$ASAN_DIR" --output-on-failure -j "$(nproc)" -E "$ASAN_RELEASE_ONLY"
fi
