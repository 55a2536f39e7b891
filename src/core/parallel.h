#pragma once
// Internal to igm_core: deterministic parallel loops over oneTBB, run in the caller's task arena
// (igm/core/threads.h sets its concurrency). The work is cut into chunks fixed by the loop's size
// and the chunk size, never by the thread count; results that are combined (sums) are combined
// chunk by chunk in chunk order. So every output is the same for any number of threads.
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace igm::parallel {

/// body(begin, end) on the chunks [c * chunk, min(n, (c + 1) * chunk)) of [0, n), in parallel.
/// The chunks must be independent (disjoint writes). Pre: chunk >= 1.
template <class Body>
void for_chunks(std::int64_t n, std::int64_t chunk, const Body& body) {
  if (n <= 0) return;
  const std::int64_t chunks = (n + chunk - 1) / chunk;
  if (chunks == 1) {
    body(std::int64_t{0}, n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, chunks, 1),
                    [&](const tbb::blocked_range<std::int64_t>& r) {
                      for (std::int64_t c = r.begin(); c != r.end(); ++c)
                        body(c * chunk, std::min(n, (c + 1) * chunk));
                    },
                    tbb::simple_partitioner());
}

/// body(i) for every i in [0, n), in parallel, in chunks of `chunk`.
template <class Body>
void for_each_index(std::int64_t n, std::int64_t chunk, const Body& body) {
  for_chunks(n, chunk, [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t i = b; i < e; ++i) body(i);
  });
}

/// The reduction combine(..., combine(combine(init, r_0), r_1), ...) of the chunks' results
/// r_c = chunk_fn(begin, end), in chunk order.
template <class T, class ChunkFn, class Combine>
T reduce_chunks(std::int64_t n, std::int64_t chunk, T init, const ChunkFn& chunk_fn, const Combine& combine) {
  if (n <= 0) return init;
  const std::int64_t chunks = (n + chunk - 1) / chunk;
  std::vector<T> partial(static_cast<std::size_t>(chunks));
  for_chunks(n, chunk, [&](std::int64_t b, std::int64_t e) { partial[static_cast<std::size_t>(b / chunk)] = chunk_fn(b, e); });
  for (const T& p : partial) init = combine(init, p);
  return init;
}

/// The sum of chunk_sum(begin, end) over the chunks of [0, n) (as for_chunks), added up in chunk
/// order: the same bits for any thread count.
template <class T, class ChunkSum>
T sum_chunks(std::int64_t n, std::int64_t chunk, const ChunkSum& chunk_sum) {
  return reduce_chunks<T>(n, chunk, T{}, chunk_sum, [](const T& a, const T& b) { return a + b; });
}

}  // namespace igm::parallel
