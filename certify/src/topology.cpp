// Check 1: the certifier's own adjacency (sorted edge keys + union-find), independent of the
// producer's TriMesh.
#include <algorithm>
#include <numeric>
#include <utility>

#include "internal.h"

namespace igm::certify::detail {

namespace {

struct UnionFind {
  std::vector<std::int64_t> parent;
  explicit UnionFind(std::int64_t n) : parent(static_cast<std::size_t>(n)) {
    std::iota(parent.begin(), parent.end(), std::int64_t(0));
  }
  std::int64_t find(std::int64_t x) {
    std::int64_t r = x;
    while (parent[r] != r) r = parent[r];  // bound: n (path halving below keeps it short)
    while (parent[x] != r) {                // bound: n
      std::int64_t n = parent[x];
      parent[x] = r;
      x = n;
    }
    return r;
  }
  void unite(std::int64_t a, std::int64_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Boundary vertices, each vertex's outgoing boundary half-edge, and the boundary loops (total and
// per component). In a manifold, consistently oriented mesh the corners at a boundary vertex form
// one open fan, whose first corner's outgoing edge and last corner's incoming edge are its only
// boundary edges: one boundary half-edge leaves the vertex, so following "the boundary half-edge
// leaving my target" walks each loop. Loops stay -1 when the mesh is not manifold and oriented.
void count_boundary_loops(Topology& t) {
  const std::int64_t C = std::int64_t(t.corner_vertex->size());
  t.boundary_out.assign(static_cast<std::size_t>(t.V), -1);
  std::vector<char> seen(static_cast<std::size_t>(t.V), 0);
  bool unique_out = true;
  std::int64_t halfedges = 0;
  for (std::int64_t h = 0; h < C; ++h) {  // bound: C
    if (!t.on_boundary(h)) continue;
    ++halfedges;
    for (std::int64_t v : {t.origin(h), t.target(h)}) {
      if (!seen[v]) ++t.boundary_vertices;
      seen[v] = 1;
    }
    std::int64_t& out = t.boundary_out[t.origin(h)];
    if (out >= 0) unique_out = false;
    out = h;
  }
  if (!t.manifold_oriented || !unique_out) return;
  t.boundary_loops = 0;
  for (auto& c : t.components) c.boundary_loops = 0;
  std::vector<char> visited(static_cast<std::size_t>(C), 0);
  for (std::int64_t h = 0; h < C; ++h) {  // bound: C, plus the loop walks below
    if (visited[h] || !t.on_boundary(h)) continue;
    std::int64_t g = h, steps = 0;
    do {  // bound: `halfedges` steps over all loops together (each half-edge visited once)
      visited[g] = 1;
      g = t.boundary_out[t.target(g)];
    } while (g >= 0 && g != h && !visited[g] && ++steps <= halfedges);
    if (g != h) {  // cannot happen in a manifold, oriented mesh (internal cross-check)
      t.boundary_loops = -1;
      for (auto& c : t.components) c.boundary_loops = -1;
      return;
    }
    ++t.boundary_loops;
    ++t.components[t.vertex_component[t.origin(h)]].boundary_loops;
  }
}

}  // namespace

void fill_mesh(Report& rep, const Topology& t, CheckResult& check) {
  rep.num_vertices = t.V;
  rep.num_edges = t.E;
  rep.num_faces = t.F;
  rep.euler_characteristic = t.euler;
  rep.num_boundary_edges = t.boundary_edges;
  if (t.boundary_loops >= 0) rep.boundary_loops = t.boundary_loops;
  std::int64_t genus_sum = 0;
  bool all_genera = true;
  for (const auto& c : t.components) {  // bound: number of components <= V
    ComponentInfo info;
    info.first_vertex = c.first_vertex;
    info.vertices = c.V;
    info.edges = c.E;
    info.faces = c.F;
    info.boundary_edges = c.boundary_edges;
    info.euler_characteristic = c.euler();
    const std::int64_t twice_genus = 2 - c.euler() - c.boundary_loops;
    if (c.boundary_loops >= 0) info.boundary_loops = c.boundary_loops;
    if (c.boundary_loops >= 0 && twice_genus >= 0 && twice_genus % 2 == 0) {
      info.genus = twice_genus / 2;
      genus_sum += twice_genus / 2;
    } else {
      all_genera = false;
    }
    rep.components.push_back(info);
  }
  if (t.ok && all_genera) rep.genus = genus_sum;
  check.counts.emplace_back("genus", rep.genus ? *rep.genus : -1);
}

void add_witness(CheckResult& check, std::size_t max_witnesses, Witness w) {
  ++check.offending;
  if (check.witnesses.size() < max_witnesses) check.witnesses.push_back(std::move(w));
}

std::string point_string(const mpq_class& x, const mpq_class& y) {
  std::string s = "(";
  s += x.get_str();
  s += ", ";
  s += y.get_str();
  s += ')';
  return s;
}

Topology analyze_topology(std::int64_t V, const std::vector<std::int64_t>& face_begin,
                          const std::vector<int>& corner_vertex, const Options& opt,
                          CheckResult& check) {
  const std::size_t max_witnesses = opt.max_witnesses;
  Topology t;
  t.V = V;
  t.F = std::int64_t(face_begin.size()) - 1;
  t.face_begin = &face_begin;
  t.corner_vertex = &corner_vertex;
  const std::int64_t C = std::int64_t(corner_vertex.size());
  t.corner_face.resize(static_cast<std::size_t>(C));
  for (std::int64_t f = 0; f < t.F; ++f)  // bound: C corners in total
    for (std::int64_t c = face_begin[f]; c < face_begin[f + 1]; ++c) t.corner_face[c] = f;

  std::int64_t degenerate_faces = 0, boundary = 0, nonmanifold_edges = 0, inconsistent = 0;
  std::int64_t nonmanifold_vertices = 0, unreferenced = 0, components = 0;

  // Faces repeating a vertex.
  std::vector<int> tmp;
  for (std::int64_t f = 0; f < t.F; ++f) {  // bound: F faces, sort of each face's corners
    tmp.assign(corner_vertex.begin() + face_begin[f], corner_vertex.begin() + face_begin[f + 1]);
    std::sort(tmp.begin(), tmp.end());
    if (std::adjacent_find(tmp.begin(), tmp.end()) != tmp.end()) {
      ++degenerate_faces;
      add_witness(check, max_witnesses, {"face", {f}, "face repeats a vertex", {}});
    }
  }

  // Undirected edges: sort (key, half-edge).
  std::vector<std::pair<std::uint64_t, std::int64_t>> keys;
  keys.reserve(static_cast<std::size_t>(C));
  for (std::int64_t h = 0; h < C; ++h) {  // bound: C
    std::uint64_t a = std::uint64_t(t.origin(h)), b = std::uint64_t(t.target(h));
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    keys.emplace_back((a << 32) | b, h);
  }
  std::sort(keys.begin(), keys.end());
  t.edge_of.assign(static_cast<std::size_t>(C), -1);
  t.twin.assign(static_cast<std::size_t>(C), -1);
  t.edge_halfedges.reserve(keys.size());
  UnionFind corners(C);
  for (std::size_t i = 0; i < keys.size();) {  // bound: |keys|, each group consumed once
    std::size_t j = i;
    while (j < keys.size() && keys[j].first == keys[i].first) ++j;
    const std::int64_t e = std::int64_t(t.edge_start.size());
    t.edge_start.push_back(std::int64_t(t.edge_halfedges.size()));
    for (std::size_t k = i; k < j; ++k) {
      t.edge_of[keys[k].second] = e;
      t.edge_halfedges.push_back(keys[k].second);
    }
    const std::int64_t u = std::int64_t(keys[i].first >> 32), v = std::int64_t(keys[i].first & 0xffffffffu);
    const std::size_t n = j - i;
    if (n == 1) {
      ++boundary;
      if (!opt.allow_boundary)
        add_witness(check, max_witnesses, {"edge", {u, v}, "boundary edge (one face)", {}});
    } else if (n > 2) {
      ++nonmanifold_edges;
      add_witness(check, max_witnesses,
                  {"edge", {u, v}, "non-manifold edge", {{"faces", std::to_string(n)}}});
    } else {
      const std::int64_t h1 = keys[i].second, h2 = keys[i + 1].second;
      if (t.origin(h1) == t.origin(h2)) {
        ++inconsistent;
        add_witness(check, max_witnesses,
                    {"edge", {u, v}, "faces on both sides use the edge in the same direction", {}});
      } else {
        t.twin[h1] = h2;
        t.twin[h2] = h1;
      }
    }
    // Corners at u (resp. v) of all faces on this edge belong to one fan.
    if (n >= 2) {
      auto corner_at = [&](std::int64_t h, std::int64_t w) { return t.origin(h) == w ? h : t.next(h); };
      for (std::size_t k = i + 1; k < j; ++k) {
        corners.unite(corner_at(keys[i].second, u), corner_at(keys[k].second, u));
        corners.unite(corner_at(keys[i].second, v), corner_at(keys[k].second, v));
      }
    }
    i = j;
  }
  t.E = std::int64_t(t.edge_start.size());
  t.edge_start.push_back(std::int64_t(t.edge_halfedges.size()));

  // Vertex fans and connectivity.
  t.vertex_corner.assign(static_cast<std::size_t>(V), -1);
  t.vertex_degree.assign(static_cast<std::size_t>(V), 0);
  t.vertex_manifold.assign(static_cast<std::size_t>(V), 1);
  std::vector<std::int64_t> vertex_root(static_cast<std::size_t>(V), -1);
  UnionFind verts(V);
  for (std::int64_t h = 0; h < C; ++h) {  // bound: C
    const std::int64_t v = t.origin(h);
    ++t.vertex_degree[v];
    if (t.vertex_corner[v] < 0) t.vertex_corner[v] = h;
    const std::int64_t r = corners.find(h);
    if (vertex_root[v] < 0) {
      vertex_root[v] = r;
    } else if (vertex_root[v] != r && t.vertex_manifold[v]) {
      t.vertex_manifold[v] = 0;
      ++nonmanifold_vertices;
      add_witness(check, max_witnesses, {"vertex", {v}, "non-manifold vertex (several fans)", {}});
    }
    verts.unite(v, t.target(h));
  }
  // Components: the union-find root of a component is its smallest vertex (unite keeps the
  // smaller root), met first in increasing order.
  t.vertex_component.assign(static_cast<std::size_t>(V), -1);
  for (std::int64_t v = 0; v < V; ++v) {  // bound: V
    if (t.vertex_corner[v] < 0) {
      ++unreferenced;
      add_witness(check, max_witnesses, {"vertex", {v}, "vertex used by no face", {}});
      continue;
    }
    const std::int64_t r = verts.find(v);
    if (r == v) {
      ++components;
      t.vertex_component[v] = static_cast<std::int32_t>(t.components.size());
      t.components.push_back({});
      t.components.back().first_vertex = v;
      if (components > 1 && !opt.allow_components)
        add_witness(check, max_witnesses,
                    {"vertex", {v}, "first vertex of another connected component", {}});
    } else {
      t.vertex_component[v] = t.vertex_component[r];  // r < v: already numbered
    }
    ++t.components[t.vertex_component[v]].V;
  }
  for (std::int64_t f = 0; f < t.F; ++f)  // bound: F
    ++t.components[t.vertex_component[corner_vertex[face_begin[f]]]].F;
  for (std::int64_t e = 0; e < t.E; ++e) {  // bound: E
    const std::int64_t h = t.edge_halfedges[t.edge_start[e]];
    Topology::Component& c = t.components[t.vertex_component[t.origin(h)]];
    ++c.E;
    if (t.edge_start[e + 1] - t.edge_start[e] == 1) ++c.boundary_edges;
  }

  t.euler = V - t.E + t.F;
  t.boundary_edges = boundary;
  t.manifold_oriented = nonmanifold_edges == 0 && inconsistent == 0 && nonmanifold_vertices == 0 &&
                        degenerate_faces == 0;
  count_boundary_loops(t);
  t.ok = t.manifold_oriented && (boundary == 0 || opt.allow_boundary) &&
         (components == 1 || opt.allow_components) && unreferenced == 0 && t.F > 0;
  check.counts = {{"vertices", V},
                  {"edges", t.E},
                  {"faces", t.F},
                  {"euler_characteristic", t.euler},
                  {"boundary_edges", boundary},
                  {"nonmanifold_edges", nonmanifold_edges},
                  {"inconsistently_oriented_edges", inconsistent},
                  {"nonmanifold_vertices", nonmanifold_vertices},
                  {"faces_repeating_a_vertex", degenerate_faces},
                  {"unreferenced_vertices", unreferenced},
                  {"connected_components", components},
                  {"boundary_vertices", t.boundary_vertices},
                  {"boundary_loops", t.boundary_loops}};
  if (t.F == 0) check.note = "no faces";
  check.status = t.ok ? Status::Pass : Status::Fail;
  return t;
}

std::int64_t find_edge(const Topology& t, std::int64_t u, std::int64_t v) {
  if (u == v || u < 0 || v < 0 || u >= t.V || v >= t.V) return -1;
  if (u > v) std::swap(u, v);
  auto key = [&](std::int64_t e) {
    const std::int64_t h = t.edge_halfedges[t.edge_start[e]];
    const std::int64_t a = t.origin(h), b = t.target(h);
    return std::pair(std::min(a, b), std::max(a, b));
  };
  std::int64_t lo = 0, hi = t.E;  // edges are numbered in increasing key order
  while (lo < hi) {               // bound: log2(E) + 1 halvings
    const std::int64_t mid = lo + (hi - lo) / 2;
    if (key(mid) < std::pair(u, v)) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return lo < t.E && key(lo) == std::pair(u, v) ? lo : -1;
}

}  // namespace igm::certify::detail
