#include "igm/topology/sphere_cut.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <queue>
#include <string>
#include <utility>

#include "igm/core/error.h"

namespace igm {

namespace {

using Clock = std::chrono::steady_clock;

// The vertex graph in CSR form (neighbours of v: adj[xadj[v] .. xadj[v+1]-1]), for fast BFS.
struct Graph {
  std::vector<int> xadj, adj;
  explicit Graph(const TriMesh& m) : xadj(m.num_vertices() + 1, 0), adj(m.num_halfedges()) {
    for (int h = 0; h < m.num_halfedges(); ++h) ++xadj[m.origin(h) + 1];
    for (int v = 0; v < m.num_vertices(); ++v) xadj[v + 1] += xadj[v];
    std::vector<int> fill(xadj.begin(), xadj.end() - 1);
    for (int h = 0; h < m.num_halfedges(); ++h) adj[fill[m.origin(h)]++] = m.target(h);
  }
  int size() const { return static_cast<int>(xadj.size()) - 1; }
};

// BFS hop distances from `source` (-1: unreached). O(V + E).
std::vector<int> bfs(const Graph& g, int source) {
  std::vector<int> dist(g.size(), -1);
  std::vector<int> queue{source};
  queue.reserve(g.size());
  dist[source] = 0;
  for (std::size_t q = 0; q < queue.size(); ++q) {  // each vertex enqueued once
    const int v = queue[q];
    for (int k = g.xadj[v]; k < g.xadj[v + 1]; ++k) {
      const int w = g.adj[k];
      if (dist[w] < 0) {
        dist[w] = dist[v] + 1;
        queue.push_back(w);
      }
    }
  }
  return dist;
}

// Splits every edge h leaving v (in ring order) for which split(target) holds, at its midpoint.
// Splitting keeps h leaving v (now towards the new vertex) and the ring's size, so one walk of
// the initial valence visits every original edge once. Returns the number of splits.
template <class Pred>
int split_ring(RefinedSurface& s, int v, Pred&& split) {
  const int valence = s.mesh.valence(v);
  int h = s.mesh.vertex_halfedge(v), count = 0;
  const Rational half(1, 2);
  for (int k = 0; k < valence; ++k) {  // bound: valence(v)
    if (split(s.mesh.target(h))) {
      s.split_edge(h, half);
      ++count;
    }
    h = s.mesh.next_around_origin(h);
  }
  return count;
}

std::array<int, 4> default_cones(const TriMesh& mesh) {
  const Graph m(mesh);
  const int n = m.size();
  auto argmax = [&](const std::vector<int>& score) {
    int best = 0;
    for (int v = 1; v < n; ++v)
      if (score[v] > score[best]) best = v;  // ties: lowest id
    return best;
  };
  std::array<int, 4> c{};
  std::array<std::vector<int>, 4> d;
  c[0] = argmax(bfs(m, 0));
  d[0] = bfs(m, c[0]);
  std::vector<int> mind = d[0];
  for (int i = 1; i < 4; ++i) {
    c[i] = argmax(mind);
    d[i] = bfs(m, c[i]);
    for (int v = 0; v < n; ++v) mind[v] = std::min(mind[v], d[i][v]);
  }
  // The best of the 12 path orders (a path and its reversal are the same cut).
  std::array<int, 4> perm{0, 1, 2, 3}, best{};
  long best_cost = -1;
  do {
    if (perm[0] > perm[3]) continue;
    const long cost = long(d[perm[0]][c[perm[1]]]) + d[perm[1]][c[perm[2]]] + d[perm[2]][c[perm[3]]];
    if (best_cost < 0 || cost < best_cost) {
      best_cost = cost;
      best = perm;
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return {c[best[0]], c[best[1]], c[best[2]], c[best[3]]};
}

}  // namespace

SphereCut cut_sphere(const TriMesh& mesh, const std::vector<Vec3d>& positions, const SphereCutOptions& options) {
  const auto t_start = Clock::now();
  const int n0 = mesh.num_vertices();
  if (static_cast<int>(positions.size()) != n0)
    throw Error(ErrorKind::InvalidArgument, "cut_sphere: " + std::to_string(positions.size()) + " positions for " +
                                                std::to_string(n0) + " vertices");
  const long chi = long(n0) - mesh.num_edges() + mesh.num_faces();
  if (chi != 2)
    throw Error(ErrorKind::InvalidArgument,
                "cut_sphere: the surface is not a sphere (Euler characteristic " + std::to_string(chi) + ")");
  if (!options.cones.empty()) {
    if (options.cones.size() != 4)
      throw Error(ErrorKind::InvalidArgument,
                  "cones: need exactly 4 vertex ids, got " + std::to_string(options.cones.size()));
    for (int i = 0; i < 4; ++i) {
      const int v = options.cones[i];
      if (v < 0 || v >= n0)
        throw Error(ErrorKind::InvalidArgument,
                    "cones: entry " + std::to_string(i) + " is vertex " + std::to_string(v) + ", outside 0.." +
                        std::to_string(n0 - 1),
                    {i});
      for (int j = 0; j < i; ++j)
        if (options.cones[j] == v)
          throw Error(ErrorKind::InvalidArgument,
                      "cones: entry " + std::to_string(i) + " repeats vertex " + std::to_string(v) + " (entry " +
                          std::to_string(j) + ")",
                      {i});
    }
  }
  {  // no two edges between the same pair of vertices (validated meshes have none; splits keep it)
    const Graph g(mesh);
    std::vector<int> stamp(n0, -1);
    for (int v = 0; v < n0; ++v)
      for (int k = g.xadj[v]; k < g.xadj[v + 1]; ++k) {
        const int w = g.adj[k];
        if (stamp[w] == v)
          throw Error(ErrorKind::InvalidArgument,
                      "cut_sphere: two edges join vertices " + std::to_string(v) + " and " + std::to_string(w), {v, w});
        stamp[w] = v;
      }
  }

  SphereCut cut;
  SphereCutStats& st = cut.stats;
  st.vertices_before = n0;
  st.faces_before = mesh.num_faces();
  RefinedSurface& s = cut.surface;
  s.mesh = mesh;
  s.num_input_vertices = n0;
  s.input_positions = positions;

  // 1. at least four vertices: a closed mesh with 3 vertices is two triangles; one face split
  //    makes a tetrahedron (bound: one split).
  if (s.mesh.num_vertices() < 4) {
    s.split_face(0);
    ++st.small_mesh_splits;
  }
  // 2. cones
  if (options.cones.empty())
    cut.cones = default_cones(s.mesh);
  else
    std::copy(options.cones.begin(), options.cones.end(), cut.cones.begin());
  // 3. split every edge at a cone (edges to vertices created here are not cone edges of the input:
  //    they join a cone to a midpoint, never two cones).
  {
    const int before = s.mesh.num_vertices();
    for (int c : cut.cones) st.cone_splits += split_ring(s, c, [&](int w) { return w < before; });
  }
  // 4. the legs, each followed by a pass splitting the chords of the path so far.
  std::vector<int> pos;  // position on the path, -1 off the path
  auto grow = [&] { pos.resize(s.mesh.num_vertices(), -1); };
  grow();
  cut.path = {cut.cones[0]};
  pos[cut.cones[0]] = 0;
  cut.cone_index[0] = 0;
  for (int leg = 0; leg < 3; ++leg) {
    const int from = cut.cones[leg], to = cut.cones[leg + 1];
    const int nv = s.mesh.num_vertices();
    const Graph g(s.mesh);  // rebuilt per leg: the chord splits change the mesh
    // Cost of entering a vertex: (adjacent to a cone still to be visited) * (nv + 1) + 1.
    std::vector<char> blocked(nv, 0), near_later(nv, 0);
    for (int v = 0; v < nv; ++v) blocked[v] = pos[v] >= 0;
    for (int j = leg + 2; j < 4; ++j) {
      blocked[cut.cones[j]] = 1;
      for (int kk = g.xadj[cut.cones[j]]; kk < g.xadj[cut.cones[j] + 1]; ++kk) near_later[g.adj[kk]] = 1;
    }
    blocked[to] = 0;
    std::vector<std::int64_t> cost(nv, -1);
    std::vector<int> parent(nv, -1);
    using Item = std::pair<std::int64_t, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;  // ties: lowest id
    cost[from] = 0;
    heap.push({0, from});
    while (!heap.empty()) {  // Dijkstra: each vertex settles once, O(E log V)
      const auto [c, v] = heap.top();
      heap.pop();
      if (c != cost[v]) continue;
      if (v == to) break;
      for (int kk = g.xadj[v]; kk < g.xadj[v + 1]; ++kk) {
        const int w = g.adj[kk];
        if (blocked[w]) continue;
        const std::int64_t cw = c + 1 + (w != to && near_later[w] ? std::int64_t(nv) + 1 : 0);
        if (cost[w] < 0 || cw < cost[w]) {
          cost[w] = cw;
          parent[w] = v;
          heap.push({cw, w});
        } else if (cw == cost[w] && v < parent[w]) {
          parent[w] = v;  // ties: the lowest parent id (w is already queued with this cost)
        }
      }
    }
    if (cost[to] < 0)
      throw Error(ErrorKind::Internal, "cut_sphere: no path from cone " + std::to_string(from) + " to cone " +
                                           std::to_string(to) + " avoiding the path so far (after " +
                                           std::to_string(leg + 1) + " split passes)",
                  {from, to});
    std::vector<int> piece;
    for (int v = to; v != from; v = parent[v]) piece.push_back(v);  // bound: nv steps
    std::reverse(piece.begin(), piece.end());
    for (int v : piece) {
      pos[v] = static_cast<int>(cut.path.size());
      cut.path.push_back(v);
    }
    st.leg_edges[leg] = static_cast<int>(piece.size());
    cut.cone_index[leg + 1] = static_cast<int>(cut.path.size()) - 1;
    // chords: edges between two path vertices that are not consecutive on the path
    for (std::size_t i = 0; i < cut.path.size(); ++i) {
      const int p = cut.path[i];
      st.chord_splits += split_ring(s, p, [&](int w) {
        return w < static_cast<int>(pos.size()) && pos[w] >= 0 && std::abs(pos[w] - static_cast<int>(i)) != 1;
      });
      grow();
    }
  }
  const int k = static_cast<int>(cut.path.size()) - 1;
  st.path_edges = k;

  // 5. the cut
  const TriMesh& m = s.mesh;
  const int nv = m.num_vertices();
  cut.num_surface_vertices = nv;
  cut.disk_triangles.resize(m.num_faces());
  for (int f = 0; f < m.num_faces(); ++f) cut.disk_triangles[f] = m.face_vertices(f);
  cut.disk_to_surface.resize(nv + k - 1);
  for (int v = 0; v < nv; ++v) cut.disk_to_surface[v] = v;
  for (int i = 1; i < k; ++i) {
    const int p = cut.path[i];
    cut.disk_to_surface[cut.copy2(i)] = p;
    const int fwd = m.find_halfedge(p, cut.path[i + 1]), bwd = m.find_halfedge(p, cut.path[i - 1]);
    if (fwd < 0 || bwd < 0) throw Error(ErrorKind::Internal, "cut_sphere: a path edge is missing", {p});
    // Faces of the half-edges from bwd (ccw) up to fwd lie right of the path: copy 2.
    int h = bwd;
    for (int steps = 0; h != fwd; ++steps) {  // bound: valence(p)
      if (steps > m.num_halfedges()) throw Error(ErrorKind::Internal, "cut_sphere: ring walk does not close", {p});
      cut.disk_triangles[TriMesh::face(h)][h % 3] = cut.copy2(i);
      h = m.next_around_origin(h);
    }
  }
  cut.boundary.reserve(2 * k);
  for (int i = 0; i <= k; ++i) cut.boundary.push_back(cut.path[i]);
  for (int i = k - 1; i >= 1; --i) cut.boundary.push_back(cut.copy2(i));
  const int iB = cut.cone_index[1], iC = cut.cone_index[2];
  cut.corners = {0, iB, iC, k, 2 * k - iC, 2 * k - iB};
  st.vertices_after = nv;
  st.faces_after = m.num_faces();
  st.seconds_total = std::chrono::duration<double>(Clock::now() - t_start).count();
  return cut;
}

}  // namespace igm
