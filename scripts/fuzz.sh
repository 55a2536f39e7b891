#!/usr/bin/env bash
# Fuzzing with clang + libFuzzer (ASan + UBSan), two modes:
#
# Real fuzzing (not part of CI): bash scripts/fuzz.sh [SECONDS] [TARGET...]
#   builds the fuzz targets (RelWithDebInfo) in ${IGM_FUZZ_BUILD_DIR:-build-fuzz} and runs them ONE
#   AT A TIME under `nice -n 19`, each for SECONDS (default 600) of wall time, on a scratch corpus in
#   ${IGM_FUZZ_WORK:-/tmp/igm-fuzz} seeded from fuzz/corpus/<target>/. Crashes, timeouts and leaks
#   land in the work dir as <target>-crash-*, -timeout-*, -oom-*; minimize one with
#   `fuzz_<target> -minimize_crash=1 FILE`, then add it to fuzz/corpus/<target>/ and a regression
#   test. Targets: pipeline read_obj read_off read_ply read_stl certify predicates; default all,
#   pipeline first.
#
# Smoke run (scripts/test.sh with IGM_TEST_FUZZ=1): bash scripts/fuzz.sh smoke
#   builds only the fuzz targets, the cheapest way (-O1, no debug info: ~330 s of CPU against ~480 s
#   for RelWithDebInfo) in ${IGM_FUZZ_SMOKE_DIR:-build-fuzz-smoke}, then runs each for
#   ${IGM_FUZZ_SMOKE_SECONDS:-5} s from its corpus (pipeline: from its five quickest entries; CTest
#   replays all of them) in a scratch folder, so that the checked-in corpus is not written. Any
#   finding (a crash, a sanitizer report, a timeout past 120 s, 4 GB) fails it.
set -euo pipefail
cd "$(dirname "$0")/.."
ALL=(pipeline read_obj read_off read_ply read_stl certify predicates)

if [ "${1:-}" = smoke ]; then
  BUILD="${IGM_FUZZ_SMOKE_DIR:-build-fuzz-smoke}"
  SECS="${IGM_FUZZ_SMOKE_SECONDS:-5}"
  CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
    -DIGM_BUILD_FUZZERS=ON -DIGM_BUILD_TESTS=OFF -DIGM_BUILD_BENCH=OFF -DIGM_BUILD_PYTHON=OFF >/dev/null
  start=$(date +%s)
  cmake --build "$BUILD" -j "$(nproc)" --target "${ALL[@]/#/fuzz_}" >/dev/null
  echo "[fuzz smoke] built ${#ALL[@]} targets in $(( $(date +%s) - start )) s"
  WORK=$(mktemp -d)
  trap 'rm -rf "$WORK"' EXIT
  for t in "${ALL[@]}"; do
    mkdir -p "$WORK/$t"
    if [ "$t" = pipeline ]; then
      for f in tetra_refined g0_plain several_2_g3 open_g0_b1_plain g1_tiny; do cp "fuzz/corpus/$t/$f" "$WORK/$t/"; done
      seeds=()
    else
      seeds=("fuzz/corpus/$t")
    fi
    rc=0
    "$BUILD/fuzz/fuzz_$t" -max_total_time="$SECS" -timeout=120 -rss_limit_mb=4096 -print_final_stats=1 \
      -artifact_prefix="$WORK/$t-" "$WORK/$t" "${seeds[@]}" >"$WORK/$t.log" 2>&1 || rc=$?
    runs=$(grep -E '^stat::number_of_executed_units' "$WORK/$t.log" | awk '{print $2}')
    echo "[fuzz smoke] $t: exit $rc, ${runs:-?} executions"
    if [ "$rc" != 0 ]; then
      tail -n 40 "$WORK/$t.log"
      exit 1
    fi
  done
  exit 0
fi

SECONDS_EACH="${1:-600}"
shift || true
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then TARGETS=("${ALL[@]}"); fi
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
