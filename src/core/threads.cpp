#include "igm/core/threads.h"

#include <oneapi/tbb/info.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
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
  // oneTBB has at most its default concurrency of workers (every core); an arena asking for more
  // would make it print a warning (the library never prints), and would not run faster.
  tbb::task_arena arena(std::min(resolve_threads(threads), tbb::info::default_concurrency()));
  arena.execute(fn);
}

}  // namespace igm
