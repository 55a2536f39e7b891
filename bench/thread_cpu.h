#pragma once
// Thread CPU time for the benchmarks (the machine is shared: wall time would count other
// processes). Header-only: each bench/<name>_bench.cpp is its own executable.
#include <ctime>

namespace igm_bench {

/// This thread's CPU time in nanoseconds (CLOCK_THREAD_CPUTIME_ID).
inline double thread_cpu_ns() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e9 * static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec);
}

}  // namespace igm_bench
