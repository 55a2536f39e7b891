#pragma once
// The process's peak resident memory and CPU time, for the per-stage measurements of the
// pipeline (StageEvent) and the benchmarks.

namespace igm {

/// The peak resident set size of this process in MB since it started or since the last reset
/// (Linux: VmHWM of /proc/self/status); with `reset`, the peak is then reset to the current
/// resident size (writing 5 to /proc/self/clear_refs), so that the next call measures from here.
/// -1 where it cannot be read; where the reset is refused, later peaks count from the start.
double peak_resident_mb(bool reset = false);

/// CPU seconds (user + system) this process has used so far, all threads.
double process_cpu_seconds();

}  // namespace igm
