#!/usr/bin/env bash
# Real fuzzing with clang + libFuzzer (not part of CI): builds the fuzz targets in
# ${IGM_FUZZ_BUILD_DIR:-build-fuzz} and runs them ONE AT A TIME under `nice -n 19`, each for
# SECONDS (default 600) of wall time, on a scratch corpus in ${IGM_FUZZ_WORK:-/tmp/igm-fuzz}
# seeded from fuzz/corpus/<target>/. Crashes, timeouts and leaks land in the work dir as
# <target>-crash-*, -timeout-*, -oom-*; minimize one with `fuzz_<target> -minimize_crash=1 FILE`,
# then add it to fuzz/corpus/<target>/ and a regression test.
# Usage: bash scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: pipeline read_obj read_off
#        read_ply read_stl certify predicates; default all, pipeline first)
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH="${1:-600}"
shift || true
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then TARGETS=(pipeline read_obj read_off read_ply read_stl certify predicates); fi
BUILD="${IGM_FUZZ_BUILD_DIR:-build-fuzz}"
WORK="${IGM_FUZZ_WORK:-/tmp/igm-fuzz}"
CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DIGM_BUILD_FUZZERS=ON \
  -DIGM_BUILD_TESTS=OFF -DIGM_BUILD_BENCH=OFF >/dev/null
for t in "${TARGETS[@]}"; do nice -n 19 cmake --build "$BUILD" -j2 --target "fuzz_$t" >/dev/null; done
mkdir -p "$WORK"
for t in "${TARGETS[@]}"; do
  mkdir -p "$WORK/$t"
  echo "[fuzz] $t for ${SECONDS_EACH}s (log: $WORK/$t.log)"
  start=$(date +%s)
  # -timeout: one input may take at most 300 s of wall time (the machine is shared and the
  # fuzzer runs at the lowest priority); -rss_limit_mb: memory proportional to a declared but
  # absent size is a finding.
  rc=0
  nice -n 19 "$BUILD/fuzz/fuzz_$t" -max_total_time="$SECONDS_EACH" -timeout=300 -rss_limit_mb=4096 \
    -print_final_stats=1 -artifact_prefix="$WORK/$t-" "$WORK/$t" "fuzz/corpus/$t" >"$WORK/$t.log" 2>&1 || rc=$?
  runs=$(grep -E '^stat::number_of_executed_units' "$WORK/$t.log" | awk '{print $2}')
  echo "[fuzz] $t: exit $rc, ${runs:-?} executions in $(( $(date +%s) - start )) s"
done
