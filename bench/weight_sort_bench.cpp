// ns per item of sort_by_weight_descending against std::sort with the same comparator, on fresh
// uniform weights in [0, 10) with ascending ids (the radix path's precondition), per size. Each
// repetition sorts a new input: repeating one input lets the branch predictor learn it, which
// flatters std::sort below ~8k items.
// Usage: igm_bench_weight_sort [items_per_size]   (default 4000000: repetitions = that / size)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <utility>
#include <vector>

#include "thread_cpu.h"
#include "igm/core/weight_sort.h"

namespace {

using Items = std::vector<std::pair<double, int>>;

using igm_bench::thread_cpu_ns;

}  // namespace

int main(int argc, char** argv) {
  const long per_size = argc > 1 ? std::atol(argv[1]) : 4000000L;
  if (per_size < 1) {
    std::fprintf(stderr, "usage: igm_bench_weight_sort [items_per_size >= 1]\n");
    return 2;
  }
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> weight(0.0, 10.0);
  std::printf("%8s %12s %12s\n", "items", "library", "std::sort");
  for (long n : {16L, 64L, 127L, 128L, 512L, 4096L, 16384L, 65536L, 262143L, 262144L, 1048576L}) {
    const long reps = std::max(3L, per_size / n);
    Items items(static_cast<std::size_t>(n));
    double t_lib = 0, t_std = 0;
    for (long r = 0; r < reps; ++r) {
      for (long i = 0; i < n; ++i) items[static_cast<std::size_t>(i)] = {weight(rng), static_cast<int>(i)};
      Items a = items, b = items;
      double t0 = thread_cpu_ns();
      igm::sort_by_weight_descending(a);
      double t1 = thread_cpu_ns();
      std::sort(b.begin(), b.end(), [](const auto& x, const auto& y) {
        return x.first != y.first ? x.first > y.first : x.second < y.second;
      });
      double t2 = thread_cpu_ns();
      t_lib += t1 - t0, t_std += t2 - t1;
      if (a != b) {
        std::fprintf(stderr, "different orders at %ld items\n", n);
        return 1;
      }
    }
    std::printf("%8ld %9.1f ns %9.1f ns\n", n, t_lib / static_cast<double>(reps * n), t_std / static_cast<double>(reps * n));
  }
  return 0;
}
