#include "igm/topology/cut_to_canonical_disk.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <queue>
#include <string>
#include <unordered_set>
#include <utility>

#include "igm/core/error.h"
#include "igm/topology/handle_slides.h"

namespace igm {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

[[noreturn]] void internal(const std::string& what, std::vector<std::int64_t> ids = {}) {
  throw Error(ErrorKind::Internal, "topology: " + what, std::move(ids));
}

double length(const Vec3d& a, const Vec3d& b) {
  double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// The positions scaled by one power of two so that the largest |coordinate| is in [1, 2): edge
// lengths and path sums are then finite (at most 2*sqrt(3) per edge) whatever the input's
// magnitude (1e300 would overflow the squares to inf, and Dijkstra would reach nothing), and a
// power-of-two scale changes no comparison except by underflow to 0, which only makes ties.
// The lengths only choose among homotopy bases: any finite non-negative lengths are correct.
// Throws NonFinite for a NaN or infinite coordinate.
std::vector<Vec3d> unit_scaled(const std::vector<Vec3d>& positions) {
  double m = 0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const Vec3d& p = positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(ErrorKind::NonFinite, "vertex " + std::to_string(v) + " has a non-finite coordinate",
                  {static_cast<std::int64_t>(v)});
    m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  }
  if (m == 0) return positions;
  const int e = std::ilogb(m);  // m in [2^e, 2^(e+1))
  std::vector<Vec3d> out(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v)
    out[v] = {std::ldexp(positions[v].x, -e), std::ldexp(positions[v].y, -e), std::ldexp(positions[v].z, -e)};
  return out;
}

int find_he(const TriMesh& m, int a, int b) {
  int h = m.find_halfedge(a, b);
  if (h < 0) internal("missing edge", {a, b});
  return h;
}

struct Dsu {
  std::vector<int> p;
  explicit Dsu(int n) : p(n) { std::iota(p.begin(), p.end(), 0); }
  int find(int x) {
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
  }
  bool unite(int a, int b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    p[a] = b;
    return true;
  }
};

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// A point of a strand before realization: a mesh vertex (>= 0) or a crossing (-1 - crossing id).
struct Crossing {
  int edge;    // canonical half-edge (h < twin(h)) of the crossed edge
  int side;    // the endpoint the strand goes around
  int strand;  // tour index
  int vertex = -1;
};

struct FaceArc {
  int face;
  int a, b;  // point codes
};

// Triangulates a convex polygon whose vertices lie on the sides of one face (side masks: bit k =
// lies on side k). Appends ccw triangles; adds one interior vertex (via add_steiner) only when no
// fan from a polygon vertex avoids flat triangles. Cost O(m^2) for m vertices.
template <class AddSteiner>
void triangulate_polygon(const std::vector<int>& ids, const std::vector<unsigned>& mask,
                         std::vector<std::array<int, 3>>& out, AddSteiner&& add_steiner) {
  const int m = static_cast<int>(ids.size());
  if (m < 3) internal("polygon with fewer than three vertices");
  for (int v = 0; v < m; ++v) {
    bool ok = true;
    for (int k = 1; k + 1 < m && ok; ++k)
      if (mask[v] & mask[(v + k) % m] & mask[(v + k + 1) % m]) ok = false;
    if (!ok) continue;
    for (int k = 1; k + 1 < m; ++k) out.push_back({ids[v], ids[(v + k) % m], ids[(v + k + 1) % m]});
    return;
  }
  const int s = add_steiner(ids);
  for (int i = 0; i < m; ++i) out.push_back({s, ids[i], ids[(i + 1) % m]});
}


// Cuts the surface along res.loops: fills disk_triangles, disk_to_surface, boundary and sides.
// The boundary walk starts with the cut half-edge `first` leaving the root (any if -1). O(n).
void build_cut(CutResult& res, int first) {
  const int root = res.root;
  const int nloops = static_cast<int>(res.loops.size());
  const int genus = res.genus;
  res.disk_triangles.clear();
  res.disk_to_surface.clear();
  res.boundary.clear();
  res.sides.clear();
  {
    const auto& Mm = res.surface.mesh;
    const int nh = Mm.num_halfedges();
    std::vector<int> loop_of(Mm.num_vertices(), -1), pos_in_loop(Mm.num_vertices(), -1);
    std::vector<char> is_cut(nh, 0);
    for (int i = 0; i < nloops; ++i) {
      const auto& L = res.loops[i];
      for (std::size_t j = 0; j < L.size(); ++j) {
        const int h = find_he(Mm, L[j], L[(j + 1) % L.size()]);
        if (is_cut[h]) internal("loop edge used twice", {L[j]});
        is_cut[h] = is_cut[Mm.twin(h)] = 1;
        if (j > 0) {
          if (loop_of[L[j]] >= 0) internal("loops share a vertex other than the root", {L[j]});
          loop_of[L[j]] = i, pos_in_loop[L[j]] = static_cast<int>(j);
        }
      }
    }
    std::vector<int> wedge(nh, -1);
    auto& d2s = res.disk_to_surface;
    for (int v = 0; v < Mm.num_vertices(); ++v) {
      const int h0 = Mm.vertex_halfedge(v);
      int start = h0;
      for (int h = Mm.next_around_origin(h0);; h = Mm.next_around_origin(h)) {  // <= valence steps
        if (is_cut[h]) { start = h; break; }
        if (h == h0) break;
      }
      int copy = static_cast<int>(d2s.size());
      d2s.push_back(v);
      int h = start;
      do {  // one turn around v: valence steps
        wedge[h] = copy;
        h = Mm.next_around_origin(h);
        if (h != start && is_cut[h]) {
          copy = static_cast<int>(d2s.size());
          d2s.push_back(v);
        }
      } while (h != start);
    }
    res.disk_triangles.resize(Mm.num_faces());
    for (int f = 0; f < Mm.num_faces(); ++f)
      res.disk_triangles[f] = {wedge[3 * f], wedge[3 * f + 1], wedge[3 * f + 2]};
    // Boundary: cut half-edges, chained through the fan of their target (clockwise).
    int ncut = 0;
    for (int h = 0; h < nh; ++h)
      if (is_cut[h]) {
        ++ncut;
        if (first < 0 && Mm.origin(h) == root) first = h;
      }
    if (first < 0 || !is_cut[first] || Mm.origin(first) != root) internal("bad start of the boundary walk");
    std::vector<int> bh;
    int h = first;
    do {
      bh.push_back(h);
      if (static_cast<int>(bh.size()) > ncut) internal("disk boundary does not close");
      int g = TriMesh::next(h);
      int guard = 0;
      while (!is_cut[g]) {
        g = TriMesh::next(Mm.twin(g));
        if (++guard > nh) internal("boundary walk lost");
      }
      h = g;
    } while (h != first);
    if (static_cast<int>(bh.size()) != ncut) internal("the cut has more than one boundary cycle");
    for (int x : bh) res.boundary.push_back(wedge[x]);
    // Sides.
    for (std::size_t i = 0; i < bh.size(); ++i) {
      if (Mm.origin(bh[i]) == root) res.sides.push_back({});
      res.sides.back().disk_vertices.push_back(wedge[bh[i]]);
    }
    for (std::size_t s = 0; s < res.sides.size(); ++s) {
      auto& S = res.sides[s];
      S.disk_vertices.push_back(res.sides[(s + 1) % res.sides.size()].disk_vertices.front());
      if (S.disk_vertices.size() < 3) internal("side without interior vertex");
      int x = d2s[S.disk_vertices[1]];
      S.loop = loop_of[x];
      if (S.loop < 0) internal("side leaves the root off a loop", {x});
      S.inverse = pos_in_loop[x] != 1;
    }
    if (static_cast<int>(res.sides.size()) != 4 * genus)
      internal("boundary has " + std::to_string(res.sides.size()) + " sides, expected " + std::to_string(4 * genus));
    for (std::size_t s = 0; s < res.sides.size(); ++s)
      for (std::size_t t = 0; t < res.sides.size(); ++t)
        if (t != s && res.sides[t].loop == res.sides[s].loop) res.sides[s].mate = static_cast<int>(t);
  }
}

Word word_of(const CutResult& res) {
  Word w;
  for (const auto& s : res.sides) w.push_back({s.loop, s.inverse});
  return w;
}

bool cyclically_equal(const Word& a, const Word& b) {
  if (a.size() != b.size()) return false;
  const std::size_t n = a.size();
  for (std::size_t r = 0; r < n; ++r) {
    bool ok = true;
    for (std::size_t i = 0; i < n && ok; ++i) ok = a[(i + r) % n] == b[i];
    if (ok) return true;
  }
  return false;
}

// Makes the embedding pre-conditions hold by edge splits at midpoints. `full`: split every edge off
// the loops that joins two loop vertices (the root included); this also connects the vertices on
// no loop (used before handle slides). Otherwise only what the disk needs: edges off the loops
// joining two vertices of one loop or a loop vertex to the root, then one edge off the loops in
// every triangle whose three vertices are on loops. Afterwards no interior disk edge joins two
// vertices of one side, no triangle has three boundary vertices, and every root wedge holds a
// vertex on no loop. Returns the number of splits. O(n).
int precondition_pass(CutResult& res, bool full) {
  auto& rs = res.surface;
  auto& Mm = rs.mesh;
  const int root = res.root;
  std::vector<int> loop_of(Mm.num_vertices(), -1);
  std::unordered_set<std::uint64_t> loop_edges;
  for (int i = 0; i < static_cast<int>(res.loops.size()); ++i) {
    const auto& L = res.loops[i];
    for (std::size_t j = 0; j < L.size(); ++j) {
      loop_of[L[j]] = i;
      loop_edges.insert(edge_key(L[j], L[(j + 1) % L.size()]));
    }
  }
  loop_of[root] = -2;
  auto on_loop = [&](int v) { return v < static_cast<int>(loop_of.size()) && loop_of[v] != -1; };
  std::vector<std::pair<int, int>> todo;
  for (int h = 0; h < Mm.num_halfedges(); ++h) {
    if (h > Mm.twin(h)) continue;
    const int a = Mm.origin(h), b = Mm.target(h);
    if (!on_loop(a) || !on_loop(b) || loop_edges.count(edge_key(a, b))) continue;
    if (full || loop_of[a] == loop_of[b] || a == root || b == root) todo.push_back({a, b});
  }
  for (auto [a, b] : todo) rs.split_edge(find_he(Mm, a, b), make_rational(1, 2));
  int splits = static_cast<int>(todo.size());
  if (!full) {
    // Faces created by a split hold the new vertex, so one pass in id order suffices: O(F).
    for (int f = 0; f < Mm.num_faces(); ++f) {
      const auto c = Mm.face_vertices(f);
      if (!on_loop(c[0]) || !on_loop(c[1]) || !on_loop(c[2])) continue;
      int h = -1;
      for (int i = 0; i < 3 && h < 0; ++i)
        if (!loop_edges.count(edge_key(c[i], c[(i + 1) % 3]))) h = 3 * f + i;
      if (h < 0) internal("triangle bounded by loop edges only", {f});
      rs.split_edge(h, make_rational(1, 2));
      ++splits;
    }
  }
  return splits;
}

// Brings the word into a1 b1 a1^-1 b1^-1 ... by the planned handle slides, each realized as a
// shortest path between two root wedges through vertices on no loop; relabels and reorients the
// loops and rebuilds the cut with the boundary starting at loop 0. Pre: build_cut done, no edge
// off the loops joins two loop vertices. At most 2g slides, each O(n).
void normalize(CutResult& res, bool check_each_slide) {
  const int root = res.root;
  auto& rs = res.surface;
  Word cur = word_of(res);
  Word planned_final;
  const std::vector<Slide> plan = plan_handle_slides(cur, &planned_final);
  std::vector<char> on_loop(rs.mesh.num_vertices(), 0);
  std::unordered_set<std::uint64_t> loop_edges;
  for (const auto& L : res.loops)
    for (std::size_t j = 0; j < L.size(); ++j) {
      on_loop[L[j]] = 1;
      loop_edges.insert(edge_key(L[j], L[(j + 1) % L.size()]));
    }
  auto first_vertex = [&](Letter l) { const auto& L = res.loops[l.loop]; return l.inverse ? L.back() : L[1]; };
  for (const Slide& s : plan) {
    auto& M = rs.mesh;
    // The vertices on no loop next to the root inside the wedge that starts at corner c.
    auto wedge_vertices = [&](int corner) {
      std::vector<int> out;
      const int h0 = find_he(M, root, first_vertex(cur[corner]));
      for (int h = M.next_around_origin(h0); h != h0; h = M.next_around_origin(h)) {  // <= valence
        const int w = M.target(h);
        if (loop_edges.count(edge_key(root, w))) break;
        if (!on_loop[w]) out.push_back(w);
      }
      return out;
    };
    // Cheapest path between the two wedges through vertices on no loop; a vertex next to a loop
    // vertex other than the root costs more (it would need a split later). Dijkstra with small
    // integer costs: O(E log E). If the free vertices do not connect the wedges, the edges joining
    // loop vertices are split (which connects them) and the search is repeated once.
    // A wedge without a free vertex gets one: split its first spoke, or the edge opposite the
    // root in its only face. O(valence(root)).
    auto open_wedge = [&](int corner) {
      if (!wedge_vertices(corner).empty()) return;
      const int h0 = find_he(M, root, first_vertex(cur[corner]));
      const int g = M.next_around_origin(h0);
      if (!loop_edges.count(edge_key(root, M.target(g)))) {
        rs.split_edge(g, make_rational(1, 2));
      } else {
        rs.split_edge(TriMesh::next(h0), make_rational(1, 2));  // edge opposite the root in face(h0)
      }
      on_loop.resize(M.num_vertices(), 0);
      ++res.stats.precondition_splits;
      if (wedge_vertices(corner).empty()) internal("could not open a root wedge", {root});
    };
    open_wedge(s.from_corner);
    open_wedge(s.to_corner);
    int hit = -1;
    std::vector<int> from;
    for (int attempt = 0; attempt < 2 && hit < 0; ++attempt) {
      if (attempt == 1) {
        ++res.stats.slide_retries;
        res.stats.precondition_splits += precondition_pass(res, true);
        on_loop.assign(M.num_vertices(), 0);
        for (const auto& L : res.loops)
          for (int v : L) on_loop[v] = 1;
      }
      const std::vector<int> src = wedge_vertices(s.from_corner), dst = wedge_vertices(s.to_corner);
      if (src.empty() || dst.empty()) internal("empty root wedge");
      from.assign(M.num_vertices(), -2);
      std::vector<int> cost(M.num_vertices(), INT32_MAX);
      std::vector<char> is_dst(M.num_vertices(), 0);
      for (int v : dst) is_dst[v] = 1;
      auto vertex_cost = [&](int v) {
        const int h0 = M.vertex_halfedge(v);
        int h = h0;
        do {
          const int w = M.target(h);
          if (w != root && on_loop[w]) return 9;
          h = M.next_around_origin(h);
        } while (h != h0);
        return 1;
      };
      using Item = std::pair<int, int>;
      std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
      for (int v : src) {
        from[v] = -1;
        cost[v] = vertex_cost(v);
        pq.push({cost[v], v});
      }
      while (!pq.empty()) {  // each vertex settles once, each edge relaxes once
        auto [c, v] = pq.top();
        pq.pop();
        if (c > cost[v]) continue;
        if (is_dst[v]) {
          hit = v;
          break;
        }
        const int h0 = M.vertex_halfedge(v);
        int h = h0;
        do {
          const int w = M.target(h);
          if (!on_loop[w]) {
            const int nc = c + vertex_cost(w);
            if (nc < cost[w]) {
              cost[w] = nc;
              from[w] = v;
              pq.push({nc, w});
            }
          }
          h = M.next_around_origin(h);
        } while (h != h0);
      }
    }
    if (hit < 0) internal("handle slide: no path between the root wedges of corners " + std::to_string(s.from_corner) +
                          " and " + std::to_string(s.to_corner));
    std::vector<int> path;
    for (int v = hit; v >= 0; v = from[v]) path.push_back(v);
    std::reverse(path.begin(), path.end());
    // Replace loop s.loop by root, path (from corner i to corner j).
    auto& old = res.loops[s.loop];
    for (std::size_t j = 0; j < old.size(); ++j) loop_edges.erase(edge_key(old[j], old[(j + 1) % old.size()]));
    for (std::size_t j = 1; j < old.size(); ++j) on_loop[old[j]] = 0;
    old.assign(1, root);
    old.insert(old.end(), path.begin(), path.end());
    for (std::size_t j = 0; j < old.size(); ++j) {
      on_loop[old[j]] = 1;
      loop_edges.insert(edge_key(old[j], old[(j + 1) % old.size()]));
    }
    cur = apply_slide(cur, s);
    ++res.stats.num_slides;
    if (check_each_slide) {
      build_cut(res, -1);
      if (!cyclically_equal(word_of(res), cur))
        internal("handle slide realized " + to_string(word_of(res)) + ", planned " + to_string(cur));
    }
  }
  const int r = commutator_rotation(cur);
  if (r < 0) internal("planned word is not in commutator blocks: " + to_string(cur));
  const int n = static_cast<int>(cur.size());
  std::vector<std::vector<int>> loops(res.loops.size());
  for (int k = 0; k < n / 4; ++k)
    for (int t = 0; t < 2; ++t) {
      const Letter l = cur[(r + 4 * k + t) % n];
      auto L = res.loops[l.loop];
      if (l.inverse) std::reverse(L.begin() + 1, L.end());
      loops[2 * k + t] = std::move(L);
    }
  res.loops = std::move(loops);
}
}  // namespace

std::string CutResult::word() const {
  std::string w;
  for (const auto& s : sides) {
    if (!w.empty()) w += ' ';
    w += 'L' + std::to_string(s.loop);
    if (s.inverse) w += "'";
  }
  return w;
}

CutResult cut_to_canonical_disk(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                const CutOptions& options) {
  const auto t_start = Clock::now();
  const int nv0 = mesh.num_vertices();
  if (static_cast<int>(positions.size()) != nv0)
    throw Error(ErrorKind::InvalidArgument, "positions (" + std::to_string(positions.size()) +
                                                ") do not match the mesh vertices (" + std::to_string(nv0) + ")");
  if (nv0 == 0) throw Error(ErrorKind::Empty, "mesh has no vertices");
  for (int v = 0; v < nv0; ++v)
    if (mesh.vertex_halfedge(v) < 0)
      throw Error(ErrorKind::InvalidArgument, "vertex " + std::to_string(v) + " is used by no face", {v});
  const int chi = mesh.num_vertices() - mesh.num_edges() + mesh.num_faces();
  if (chi > 2 || chi % 2 != 0) throw Error(ErrorKind::InvalidArgument, "Euler characteristic " + std::to_string(chi));
  const int genus = (2 - chi) / 2;
  if (genus == 0) throw Error(ErrorKind::Unsupported, "genus 0 surface: the topology stage needs genus >= 1");

  int root = options.root;
  if (root == -1) {
    int best = -1;
    for (int v = 0; v < nv0; ++v) {
      int val = mesh.valence(v);
      if (val > best) best = val, root = v;
    }
  } else if (root < 0 || root >= nv0) {
    throw Error(ErrorKind::InvalidArgument, "root vertex " + std::to_string(root) + " out of range [0, " +
                                                std::to_string(nv0) + ")", {root});
  }

  CutResult res;
  res.root = root;
  res.genus = genus;
  res.stats.genus = genus;
  res.stats.vertices_before = nv0;
  res.stats.faces_before = mesh.num_faces();
  RefinedSurface& rs = res.surface;
  rs.mesh = mesh;
  rs.num_input_vertices = nv0;
  rs.input_positions = positions;

  // ---- 1. greedy homotopy basis: shortest-path tree + dual maximum spanning tree ----
  const std::vector<Vec3d> unit = unit_scaled(positions);  // lengths finite at any magnitude
  std::vector<double> dist(nv0, INFINITY);
  std::vector<int> parent(nv0, -1);
  {
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> pq;
    dist[root] = 0;
    pq.push({0.0, root});
    // Each vertex is settled once; each half-edge relaxed once: O(E log E) iterations.
    while (!pq.empty()) {
      auto [d, v] = pq.top();
      pq.pop();
      if (d > dist[v]) continue;
      int h0 = mesh.vertex_halfedge(v), h = h0;
      do {
        int w = mesh.target(h);
        double nd = d + length(unit[v], unit[w]);
        if (nd < dist[w]) {
          dist[w] = nd;
          parent[w] = v;
          pq.push({nd, w});
        }
        h = mesh.next_around_origin(h);
      } while (h != h0);
    }
    for (int v = 0; v < nv0; ++v)
      if (!(dist[v] < INFINITY))
        throw Error(ErrorKind::SeveralComponents, "vertex " + std::to_string(v) + " is not connected to the root", {v});
  }
  std::vector<std::pair<int, int>> bands;  // (u, v) with the loop root~u, uv, v~root
  {
    const int nh = mesh.num_halfedges();
    std::vector<char> in_tree(nh, 0);
    for (int h = 0; h < nh; ++h) {
      int a = mesh.origin(h), b = mesh.target(h);
      if (parent[b] == a || parent[a] == b) in_tree[h] = 1;
    }
    std::vector<std::pair<double, int>> cand;
    for (int h = 0; h < nh; ++h) {
      if (h > mesh.twin(h) || in_tree[h]) continue;
      int a = mesh.origin(h), b = mesh.target(h);
      cand.push_back({dist[a] + dist[b] + length(unit[a], unit[b]), h});
    }
    std::sort(cand.begin(), cand.end(), [](const auto& x, const auto& y) {
      return x.first != y.first ? x.first > y.first : x.second < y.second;
    });
    Dsu dsu(mesh.num_faces());
    for (const auto& [w, h] : cand) {
      (void)w;
      if (!dsu.unite(TriMesh::face(h), TriMesh::face(mesh.twin(h)))) bands.push_back({mesh.origin(h), mesh.target(h)});
    }
    if (static_cast<int>(bands.size()) != 2 * genus)
      internal("tree-cotree left " + std::to_string(bands.size()) + " edges, expected 2g = " + std::to_string(2 * genus));
  }
  res.stats.seconds_basis = seconds_since(t_start);
  const auto t_detach = Clock::now();

  // ---- 2. detach: band splits, extended tree, strands as normal curves ----
  std::vector<int> leaf_a(bands.size()), leaf_b(bands.size());
  for (std::size_t i = 0; i < bands.size(); ++i) {
    auto [u, v] = bands[i];
    int a = rs.split_edge(find_he(rs.mesh, u, v), make_rational(1, 3));
    int b = rs.split_edge(find_he(rs.mesh, a, v), make_rational(1, 2));
    parent.resize(rs.mesh.num_vertices(), -1);
    parent[a] = u;
    parent[b] = v;
    leaf_a[i] = a;
    leaf_b[i] = b;
  }
  auto& M = rs.mesh;
  std::vector<char> pruned(M.num_vertices(), 0), is_leaf(M.num_vertices(), 0);
  for (std::size_t i = 0; i < bands.size(); ++i) {
    is_leaf[leaf_a[i]] = is_leaf[leaf_b[i]] = 1;
    for (int x : {leaf_a[i], leaf_b[i]})
      // Climbs at most once per vertex (stops at marked ones): O(V) in total.
      for (; x >= 0 && !pruned[x]; x = parent[x]) pruned[x] = 1;
  }
  if (!pruned[root]) internal("root not on the tree");
  // A strand around x enters x's sector from the parent side; the sector before the first child
  // must hold at least one edge, else the curve would run along an edge: split the chord.
  {
    std::vector<std::pair<int, int>> chords;
    for (int x = 0; x < M.num_vertices(); ++x) {
      if (!pruned[x] || x == root || is_leaf[x]) continue;
      int g = M.next_around_origin(find_he(M, x, parent[x]));
      int c = M.target(g);
      if (pruned[c] && parent[c] == x) chords.push_back({parent[x], c});
    }
    for (auto [p, c] : chords) {
      int h = M.find_halfedge(p, c);
      if (h < 0) continue;  // already split (each chord is listed once; kept for safety)
      rs.split_edge(h, make_rational(1, 2));
    }
    parent.resize(M.num_vertices(), -1);
    pruned.resize(M.num_vertices(), 0);
    is_leaf.resize(M.num_vertices(), 0);
  }
  const int nv1 = M.num_vertices();
  // Children in ccw order after the parent (root: after its stored half-edge); DFS leaf order.
  std::vector<int> leaf_index(nv1, -1), max_leaf(nv1, -1);
  std::vector<int> leaves;  // tour order
  {
    auto children = [&](int x) {
      std::vector<int> ch;
      int h0 = x == root ? M.vertex_halfedge(root) : find_he(M, x, parent[x]);
      int h = x == root ? h0 : M.next_around_origin(h0);
      if (x == root) {
        do {
          int w = M.target(h);
          if (pruned[w] && parent[w] == x) ch.push_back(w);
          h = M.next_around_origin(h);
        } while (h != h0);
      } else {
        for (; h != h0; h = M.next_around_origin(h)) {
          int w = M.target(h);
          if (pruned[w] && parent[w] == x) ch.push_back(w);
        }
      }
      return ch;
    };
    // Iterative DFS; each pruned vertex pushed once: O(V + E).
    std::vector<std::pair<int, std::vector<int>>> stack;
    std::vector<std::size_t> pos;
    stack.push_back({root, children(root)});
    pos.push_back(0);
    while (!stack.empty()) {
      auto& [x, ch] = stack.back();
      if (pos.back() < ch.size()) {
        int c = ch[pos.back()++];
        if (is_leaf[c]) {
          leaf_index[c] = static_cast<int>(leaves.size());
          max_leaf[c] = leaf_index[c];
          leaves.push_back(c);
        } else {
          stack.push_back({c, children(c)});
          pos.push_back(0);
        }
      } else {
        int xv = x;
        int mx = -1;
        for (int c : ch) mx = std::max(mx, max_leaf[c]);
        max_leaf[xv] = mx;
        stack.pop_back();
        pos.pop_back();
      }
    }
    if (static_cast<int>(leaves.size()) != 4 * genus) internal("tour found " + std::to_string(leaves.size()) + " strand ends");
  }

  std::vector<Crossing> crossings;
  std::vector<FaceArc> arcs;
  std::vector<std::vector<int>> strand_points(leaves.size());  // point codes
  for (int k = 0; k < static_cast<int>(leaves.size()); ++k) {
    std::vector<int> path;
    // The parent chain is acyclic (a shortest-path tree): at most V steps.
    for (int x = leaves[k]; x != root; x = parent[x]) path.push_back(x);
    path.push_back(root);
    std::reverse(path.begin(), path.end());
    const int m = static_cast<int>(path.size()) - 1;
    int j0 = 1;
    while (j0 <= m && max_leaf[path[j0]] != k) ++j0;
    if (j0 > m) internal("strand does not reach its leaf", {leaves[k]});
    auto& pts = strand_points[k];
    pts.push_back(root);
    int prev_pt = root;
    int face_cur = -1;
    for (int j = 1; j < j0; ++j) {
      const int x = path[j];
      const int h_in = find_he(M, x, path[j - 1]), h_out = find_he(M, x, path[j + 1]);
      if (j > 1 && face_cur != TriMesh::face(h_in)) internal("strand leaves its face", {x});
      face_cur = TriMesh::face(h_in);
      // Sweep the edges at x ccw from the parent to the child: at most valence(x) steps.
      for (int g = M.next_around_origin(h_in); g != h_out; g = M.next_around_origin(g)) {
        if (g == h_in) internal("sweep around a tree vertex did not meet the child", {x});
        int e = std::min(g, M.twin(g));
        crossings.push_back({e, x, k});
        int code = -1 - static_cast<int>(crossings.size() - 1);
        arcs.push_back({face_cur, prev_pt, code});
        pts.push_back(code);
        prev_pt = code;
        face_cur = TriMesh::face(g);
      }
    }
    if (j0 > 1) arcs.push_back({face_cur, prev_pt, path[j0]});
    for (int j = j0; j <= m; ++j) pts.push_back(path[j]);
  }

  // Place crossings on their edges: the ones around the origin first (nearest = highest tour index),
  // then the ones around the target; parameters i/(n+1).
  int next_vertex = nv1;
  {
    std::vector<int> order(crossings.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int p, int q) {
      const Crossing &a = crossings[p], &b = crossings[q];
      if (a.edge != b.edge) return a.edge < b.edge;
      int oa = M.origin(a.edge), ob = M.origin(b.edge);
      bool a_first = a.side == oa, b_first = b.side == ob;
      if (a_first != b_first) return a_first;
      return a_first ? a.strand > b.strand : a.strand < b.strand;
    });
    rs.constructed.reserve(rs.constructed.size() + crossings.size());
    for (std::size_t i = 0; i < order.size();) {
      std::size_t j = i;
      const int e = crossings[order[i]].edge;
      while (j < order.size() && crossings[order[j]].edge == e) ++j;
      const long n = static_cast<long>(j - i);
      SurfacePoint pa = rs.point(M.origin(e)), pb = rs.point(M.target(e));
      for (std::size_t k = i; k < j; ++k) {
        crossings[order[k]].vertex = next_vertex++;
        rs.constructed.push_back(lerp(pa, pb, make_rational(static_cast<long>(k - i + 1), n + 1)));
      }
      i = j;
    }
  }
  res.stats.crossings = static_cast<int>(crossings.size());
  auto vid = [&](int code) { return code >= 0 ? code : crossings[-1 - code].vertex; };

  // Re-triangulate every face along its arcs.
  std::vector<std::array<int, 3>> tris;
  tris.reserve(M.num_faces() + 3 * crossings.size());
  {
    const int nf = M.num_faces();
    std::vector<std::vector<int>> edge_pts(M.num_halfedges());  // by canonical half-edge, origin->target
    {
      std::vector<int> order(crossings.size());
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(), [&](int p, int q) { return crossings[p].vertex < crossings[q].vertex; });
      for (int i : order) edge_pts[crossings[i].edge].push_back(crossings[i].vertex);
    }
    std::vector<std::vector<std::pair<int, int>>> face_arcs(nf);
    for (const auto& a : arcs) face_arcs[a.face].push_back({vid(a.a), vid(a.b)});
    auto add_steiner = [&](const std::vector<int>& ids) {
      std::vector<SurfacePoint> ps;
      for (int v : ids) ps.push_back(rs.point(v));
      rs.constructed.push_back(average(ps));
      ++res.stats.steiner_vertices;
      return next_vertex++;
    };
    std::vector<int> cyc;
    std::vector<unsigned> mask;
    for (int f = 0; f < nf; ++f) {
      cyc.clear();
      mask.clear();
      bool has_pts = false;
      for (int i = 0; i < 3; ++i) {
        const int h = 3 * f + i;
        cyc.push_back(M.origin(h));
        mask.push_back((1u << i) | (1u << ((i + 2) % 3)));
        const int e = std::min(h, M.twin(h));
        const auto& ep = edge_pts[e];
        if (!ep.empty()) has_pts = true;
        if (e == h)
          for (int v : ep) cyc.push_back(v), mask.push_back(1u << i);
        else
          for (auto it = ep.rbegin(); it != ep.rend(); ++it) cyc.push_back(*it), mask.push_back(1u << i);
      }
      if (!has_pts && face_arcs[f].empty()) {
        tris.push_back({cyc[0], cyc[1], cyc[2]});
        continue;
      }
      const int n = static_cast<int>(cyc.size());
      // Chords as position intervals; innermost first. Non-crossing is checked, not assumed.
      std::vector<std::pair<int, int>> chords;
      for (auto [a, b] : face_arcs[f]) {
        int pa = static_cast<int>(std::find(cyc.begin(), cyc.end(), a) - cyc.begin());
        int pb = static_cast<int>(std::find(cyc.begin(), cyc.end(), b) - cyc.begin());
        if (pa == n || pb == n) internal("arc endpoint not on its face", {f});
        if (pa > pb) std::swap(pa, pb);
        if (pb - pa < 2 || (pa == 0 && pb == n - 1)) internal("arc along a face side", {f});
        chords.push_back({pa, pb});
      }
      std::sort(chords.begin(), chords.end(), [](auto x, auto y) { return x.second - x.first < y.second - y.first; });
      std::vector<char> alive(n, 1);
      std::vector<int> ids;
      std::vector<unsigned> pm;
      for (auto [pa, pb] : chords) {
        if (!alive[pa] || !alive[pb]) internal("strands cross inside a face", {f});
        ids.clear();
        pm.clear();
        for (int p = pa; p <= pb; ++p) {
          if (!alive[p]) continue;
          ids.push_back(cyc[p]);
          pm.push_back(mask[p]);
          if (p != pa && p != pb) alive[p] = 0;
        }
        triangulate_polygon(ids, pm, tris, add_steiner);
      }
      ids.clear();
      pm.clear();
      for (int p = 0; p < n; ++p)
        if (alive[p]) ids.push_back(cyc[p]), pm.push_back(mask[p]);
      triangulate_polygon(ids, pm, tris, add_steiner);
    }
  }
  rs.mesh = TriMesh::from_triangles(next_vertex, tris);
  if (rs.num_input_vertices + static_cast<int>(rs.constructed.size()) != rs.mesh.num_vertices())
    internal("constructed points out of step with the mesh");

  // Loops: strand to a, band a-b, strand to b backwards.
  const int nloops = static_cast<int>(bands.size());
  res.loops.resize(nloops);
  {
    std::vector<std::vector<int>> strand_vertices(leaves.size());
    for (std::size_t k = 0; k < leaves.size(); ++k)
      for (int c : strand_points[k]) strand_vertices[k].push_back(vid(c));
    for (int i = 0; i < nloops; ++i) {
      const auto& sa = strand_vertices[leaf_index[leaf_a[i]]];
      const auto& sb = strand_vertices[leaf_index[leaf_b[i]]];
      auto& L = res.loops[i];
      L = sa;
      for (std::size_t j = sb.size() - 1; j >= 1; --j) L.push_back(sb[j]);
    }
  }

  res.stats.seconds_detach = seconds_since(t_detach);
  const auto t_cut = Clock::now();

  // ---- 4. normal form by handle slides, then the cut ----
  build_cut(res, -1);
  if (options.normal_form) normalize(res, options.check_each_slide);
  res.stats.precondition_splits += precondition_pass(res, false);
  build_cut(res, find_he(rs.mesh, root, res.loops[0][1]));
  if (options.normal_form && !is_canonical_word(word_of(res)))
    internal("cut word is not canonical: " + to_string(word_of(res)));
  res.stats.seconds_cut = seconds_since(t_cut);
  res.stats.vertices_after = rs.mesh.num_vertices();
  res.stats.faces_after = rs.mesh.num_faces();
  res.stats.seconds_total = seconds_since(t_start);
  return res;
}

}  // namespace igm
