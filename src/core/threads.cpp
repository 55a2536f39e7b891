#include "igm/core/threads.h"

#include <oneapi/tbb/task_arena.h>

#include <cstdlib>
#include <string>
#include <thread>

#include "igm/core/error.h"

namespace igm {

int resolve_threads(int threads) {
  if (threads < 0)
    throw Error(ErrorKind::InvalidArgument, "threads must be >= 0 (0: all cores), got " + std::to_string(threads));
  if (threads > 0) return threads;
  if (const char* env = std::getenv("IGM_THREADS")) {
    char* end = nullptr;
    const long n = std::strtol(env, &end, 10);
    if (end != env && *end == '\0' && n > 0 && n <= 4096) return static_cast<int>(n);
  }
  const unsigned cores = std::thread::hardware_concurrency();
  return cores > 0 ? static_cast<int>(cores) : 1;
}

void with_threads(int threads, const std::function<void()>& fn) {
  tbb::task_arena arena(resolve_threads(threads));
  arena.execute(fn);
}

}  // namespace igm
