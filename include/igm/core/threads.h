#pragma once
// How many threads the library's parallel stages use (per-patch maps, smoothing's assembly and
// exact checks, the sparse factorization, the isolines, the quality report, the certifier). Every
// output is the same for any thread count: parallel work is split into pieces fixed by the input,
// never by the threads, and combined in a fixed order.
#include <functional>

namespace igm {

/// The thread count that `threads` stands for: itself if > 0; if 0, the environment's IGM_THREADS
/// when it is a positive integer, else every core of this machine (at least 1). Negative:
/// igm::Error(InvalidArgument).
int resolve_threads(int threads);

/// Runs fn with the library's parallel loops limited to resolve_threads(threads) threads, at most
/// the cores oneTBB sees (a oneTBB task arena of that concurrency; nested calls make their own).
/// Exceptions from fn propagate.
void with_threads(int threads, const std::function<void()>& fn);

}  // namespace igm
