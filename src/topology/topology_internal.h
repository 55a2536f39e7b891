#pragma once
// Internal to the topology stage (igm/topology/cut_to_canonical_disk.h): helpers its steps share
// (detach.h, normal_form.h, cut_to_canonical_disk.cpp). Not installed, not part of the API.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <queue>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "igm/core/error.h"
#include "igm/mesh/trimesh.h"
#include "igm/topology/cut_to_canonical_disk.h"

namespace igm::topology_internal {

using Clock = std::chrono::steady_clock;
// Seconds since t0, for CutStats.
inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Throws igm::Error(Internal) "topology: what", naming the elements `ids`: a broken invariant.
[[noreturn]] inline void internal(const std::string& what, std::vector<std::int64_t> ids = {}) {
  throw Error(ErrorKind::Internal, "topology: " + what, std::move(ids));
}

// The Euclidean distance of two double points (a search metric only, never a geometric decision).
inline double length(const Vec3d& a, const Vec3d& b) {
  double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// The half-edge a -> b of m; Internal if the edge is missing. O(valence of a).
inline int find_he(const TriMesh& m, int a, int b) {
  int h = m.find_halfedge(a, b);
  if (h < 0) internal("missing edge", {a, b});
  return h;
}

// The min-heap order of (distance, vertex) entries: smaller distance first, then smaller vertex
// (std::greater's order, without the three-way comparison of std::pair).
struct LaterEntry {
  bool operator()(const std::pair<double, int>& a, const std::pair<double, int>& b) const {
    return a.first > b.first || (a.first == b.first && a.second > b.second);
  }
};

using MinQueue = std::priority_queue<std::pair<double, int>, std::vector<std::pair<double, int>>, LaterEntry>;

// Dijkstra from the entries already in pq (their dist set): each vertex is settled once (stale
// entries are skipped) and relax(v, w, d) is called for every half-edge v->w of a settled v at
// distance d; relax updates dist[w] and pushes w itself. Stops once done() holds after a vertex
// is settled: every vertex settled so far has its final distance and parent (a later entry is
// never nearer), so whatever the caller reads off them is as after a full run. O(E log E).
template <class Relax, class Done>
void settle_until(const TriMesh& M, const std::vector<double>& dist, MinQueue& pq, Relax&& relax, Done&& done) {
  while (!pq.empty()) {  // each vertex is pushed at most once per half-edge into it
    auto [d, v] = pq.top();
    pq.pop();
    if (d > dist[v]) continue;
    const int h0 = M.vertex_halfedge(v);
    int h = h0;
    do {
      relax(v, M.target(h), d);
      h = M.next_around_origin(h);
    } while (h != h0);
    if (done()) return;
  }
}

// The same to the end.
template <class Relax>
void settle_all(const TriMesh& M, const std::vector<double>& dist, MinQueue& pq, Relax&& relax) {
  settle_until(M, dist, pq, relax, [] { return false; });
}

// Runs a() here and b() on a second thread when `parallel` (and a thread can be had), else after
// a(); returns once both are done, true if b() ran on a thread. An exception from a() is rethrown
// first, then one from b(): the same one whether or not b() ran on a thread.
template <class A, class B>
bool run_pair(bool parallel, A&& a, B&& b) {
  std::exception_ptr ea, eb;
  auto guarded_b = [&] {
    try {
      b();
    } catch (...) {
      eb = std::current_exception();
    }
  };
  std::thread helper;
  if (parallel) {
    try {
      helper = std::thread(guarded_b);
    } catch (const std::system_error&) {
      // no thread to be had: b runs here after a
    }
  }
  try {
    a();
  } catch (...) {
    ea = std::current_exception();
  }
  const bool threaded = helper.joinable();
  if (threaded) helper.join();
  else if (!ea) guarded_b();
  if (ea) std::rethrow_exception(ea);
  if (eb) std::rethrow_exception(eb);
  return threaded;
}

// make(begin, end) over [0, n): in two halves, the second on a thread of its own when `parallel`
// and n is at least kPointsPerThread (below that a thread costs more than it saves); adds n to
// stats.points_on_two_threads if it ran so. For the exact points of new vertices, each made from
// points made before: no two calls write the same point. Used where the drawing of the kept plan
// has both threads to itself (the crossings); the rounds' and the crosses' chord midpoints gained
// nothing measurable on two threads (cheese: 0.057 s for all of them on one).
inline constexpr std::size_t kPointsPerThread = 1024;

template <class Make>
void make_in_halves(bool parallel, std::size_t n, CutStats& stats, Make&& make) {
  const std::size_t half = n / 2;
  if (run_pair(parallel && n >= kPointsPerThread, [&] { make(0, half); }, [&] { make(half, n); }))
    stats.points_on_two_threads += static_cast<long long>(n);
}

}  // namespace igm::topology_internal
