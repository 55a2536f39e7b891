// The certifier's threads: std::thread over a static partition (certify/README.md, "Threads").
#include <cstdlib>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

#include "internal.h"

namespace igm::certify::detail {

int thread_count(int threads) {
  if (threads > 0) return threads;
  if (const char* env = std::getenv("IGM_THREADS")) {
    char* end = nullptr;
    const long n = std::strtol(env, &end, 10);
    if (end != env && *end == '\0' && n > 0 && n <= 4096) return static_cast<int>(n);
  }
  const unsigned cores = std::thread::hardware_concurrency();
  return cores > 0 ? static_cast<int>(cores) : 1;
}

int range_count(std::int64_t n, int threads) {
  const std::int64_t t = std::min<std::int64_t>(thread_count(threads), (n + kMinRange - 1) / kMinRange);
  return static_cast<int>(std::max<std::int64_t>(t, 1));
}

void parallel_ranges(std::int64_t n, int ranges, const std::function<void(int, std::int64_t, std::int64_t)>& fn) {
  if (ranges <= 1 || n <= 0) {
    fn(0, 0, std::max<std::int64_t>(n, 0));
    return;
  }
  std::vector<std::exception_ptr> failure(static_cast<std::size_t>(ranges));
  auto run = [&](int r) {
    try {
      fn(r, n * r / ranges, n * (r + 1) / ranges);
    } catch (...) {
      failure[static_cast<std::size_t>(r)] = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(static_cast<std::size_t>(ranges - 1));
  int started = 1;
  try {  // a thread that cannot be started (no memory for its stack, a thread limit): run its range here
    for (; started < ranges; ++started) threads.emplace_back(run, started);
  } catch (const std::system_error&) {
  }
  run(0);
  for (int r = started; r < ranges; ++r) run(r);
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& e : failure)
    if (e) std::rethrow_exception(e);
}

void merge_witnesses(CheckResult& into, std::size_t max_witnesses, CheckResult&& part) {
  into.offending += part.offending;
  for (Witness& w : part.witnesses)
    if (into.witnesses.size() < max_witnesses) into.witnesses.push_back(std::move(w));
  for (const auto& [k, c] : part.histogram) into.histogram[k] += c;
  for (const auto& [k, c] : part.boundary_histogram) into.boundary_histogram[k] += c;
}

}  // namespace igm::certify::detail
