#include "igm/core/memory.h"

#include <sys/resource.h>

#include <cstdio>
#include <cstring>

namespace igm {

double peak_resident_mb(bool reset) {
  double mb = -1;
  if (std::FILE* f = std::fopen("/proc/self/status", "r")) {
    char line[256];
    while (std::fgets(line, sizeof line, f))  // bound: the file's lines
      if (std::strncmp(line, "VmHWM:", 6) == 0) {
        long kb = 0;
        if (std::sscanf(line + 6, "%ld", &kb) == 1) mb = static_cast<double>(kb) / 1024.0;
        break;
      }
    std::fclose(f);
  }
  if (mb < 0) {  // no /proc: the peak since the start
    rusage u{};
    if (getrusage(RUSAGE_SELF, &u) == 0) mb = static_cast<double>(u.ru_maxrss) / 1024.0;
  }
  if (reset)
    if (std::FILE* f = std::fopen("/proc/self/clear_refs", "w")) {
      std::fputs("5", f);
      std::fclose(f);
    }
  return mb;
}

double process_cpu_seconds() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0;
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace igm
