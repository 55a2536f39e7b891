#pragma once
// Internal pieces of the certifier shared by its translation units (not installed).
#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "certify/certify.h"

namespace igm::certify::detail {

/// Half-edge adjacency of a polygon soup, built by sorting the undirected edge keys.
/// Half-edge h is corner h: it starts at corner_vertex[h] and ends at corner_vertex[next(h)].
struct Topology {
  std::int64_t V = 0, F = 0, E = 0;
  const std::vector<std::int64_t>* face_begin = nullptr;
  const std::vector<int>* corner_vertex = nullptr;
  std::vector<std::int64_t> corner_face;   // face of each corner
  std::vector<std::int64_t> twin;          // opposite half-edge when the edge has exactly two
                                           // oppositely oriented half-edges, else -1
  std::vector<std::int64_t> edge_of;       // undirected edge id per half-edge, -1 for a loop (u->u)
  std::vector<std::int64_t> edge_start;    // size E+1: half-edges of edge e are
  std::vector<std::int64_t> edge_halfedges;//   edge_halfedges[edge_start[e] .. edge_start[e+1])
  std::vector<std::int64_t> vertex_corner; // one corner per vertex, -1 if unreferenced
  std::vector<std::int32_t> vertex_degree; // number of corners at each vertex
  std::vector<char> vertex_manifold;       // 1 when its corners form one fan
  std::vector<std::int64_t> boundary_out;  // per vertex: outgoing boundary half-edge, -1 if none
  std::vector<std::int32_t> vertex_component;  // index into components, -1 if unreferenced
  struct Component {
    std::int64_t first_vertex = 0, V = 0, E = 0, F = 0, boundary_edges = 0;
    std::int64_t boundary_loops = -1;      // -1 unless manifold_oriented
    std::int64_t euler() const { return V - E + F; }
  };
  std::vector<Component> components;       // by increasing first (smallest) vertex
  bool manifold_oriented = false;          // no non-manifold or inconsistent edge/vertex, no face
                                           // repeating a vertex (boundary edges allowed)
  bool ok = false;                         // check 1 passed (also connected, no degenerate faces)
  std::int64_t euler = 0;
  std::int64_t boundary_edges = 0, boundary_vertices = 0;
  std::int64_t boundary_loops = -1;        // -1 unless manifold_oriented

  /// h lies on an edge with exactly one half-edge (a boundary edge).
  bool on_boundary(std::int64_t h) const {
    const std::int64_t e = edge_of[h];
    return e >= 0 && edge_start[e + 1] - edge_start[e] == 1;
  }

  std::int64_t origin(std::int64_t h) const { return (*corner_vertex)[h]; }
  std::int64_t next(std::int64_t h) const {
    const std::int64_t f = corner_face[h];
    return h + 1 == (*face_begin)[f + 1] ? (*face_begin)[f] : h + 1;
  }
  std::int64_t prev(std::int64_t h) const {
    const std::int64_t f = corner_face[h];
    return h == (*face_begin)[f] ? (*face_begin)[f + 1] - 1 : h - 1;
  }
  std::int64_t target(std::int64_t h) const { return origin(next(h)); }
};

/// The undirected edge {u, v} (edges are numbered by sorted (min, max) key), or -1 when no face
/// has u and v as consecutive corners (also for u == v or ids outside [0, V)). Cost O(log E).
std::int64_t find_edge(const Topology& t, std::int64_t u, std::int64_t v);

/// Builds the adjacency and fills check 1 (topology) counts, status and witnesses; boundary
/// edges and several components pass where options allow them. Also counts boundary loops
/// (walking boundary half-edges) and per-component V, E, F, loops when manifold and oriented.
/// Pre: every corner_vertex in [0, V). Cost O(C log C) for C corners.
Topology analyze_topology(std::int64_t V, const std::vector<std::int64_t>& face_begin,
                          const std::vector<int>& corner_vertex, const Options& options,
                          CheckResult& check);

/// Fills the report's mesh fields (counts, euler, genus, boundary loops, components) from the
/// topology and appends the "genus" count to check 1 (or 5).
void fill_mesh(Report& report, const Topology& t, CheckResult& check);

/// Adds a witness unless the cap is reached; always counts it in check.offending.
void add_witness(CheckResult& check, std::size_t max_witnesses, Witness w);

/// The whole file's bytes; ok = false when it cannot be opened or read.
std::string read_file(const std::string& path, bool& ok);

std::string point_string(const mpq_class& x, const mpq_class& y);

/// Threads (certify/README.md, "Threads"): Options::threads, or when 0 the environment's
/// IGM_THREADS if a positive integer, else every core (at least 1).
int thread_count(int threads);
/// Elements per range at least (smaller inputs use fewer ranges).
inline constexpr std::int64_t kMinRange = 4096;
/// How many ranges [0, n) is cut into for `threads` (Options::threads): at most thread_count, at
/// least kMinRange elements each (at least 1 range).
int range_count(std::int64_t n, int threads);
/// fn(r, begin, end) for the ranges r = 0 .. ranges-1 of the static partition of [0, n):
/// [n r / ranges, n (r + 1) / ranges), each on its own std::thread (range 0 on the caller's). The
/// ranges' results must be combined in range order by the caller. An exception from a range is
/// rethrown after all have joined (the lowest range's).
void parallel_ranges(std::int64_t n, int ranges, const std::function<void(int, std::int64_t, std::int64_t)>& fn);
/// Appends a range's witnesses (up to max_witnesses in all), offending count and histograms to
/// `into`: merging the ranges in order gives what one pass in element order gives.
void merge_witnesses(CheckResult& into, std::size_t max_witnesses, CheckResult&& part);

}  // namespace igm::certify::detail
