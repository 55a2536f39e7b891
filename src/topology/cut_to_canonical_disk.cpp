#include "igm/topology/cut_to_canonical_disk.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <numeric>
#include <optional>
#include <queue>
#include <string>
#include <system_error>
#include <thread>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "igm/core/error.h"
#include "igm/core/union_find.h"
#include "igm/core/weight_sort.h"
#include "igm/topology/ring_bound.h"
#include "igm/topology/handle_slides.h"
#include "igm/topology/tighten_loops.h"

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

// The embedding pre-conditions (embed/tutte.h, Floater 2003), made to hold by edge splits at
// midpoints on the disk that build_cut made: no interior disk edge joins two vertices of one
// polygon side (a root copy lies on its two sides). This also excludes triangles with three
// vertices on one side (such a triangle has an interior edge). Triangles with boundary vertices on
// several sides, e.g. a root wedge that is one triangle, are fixed by the strictly convex boundary
// and positive, so they need no split. A split vertex is interior to the disk, so no split creates
// a new violation: one pass. Pre: build_cut(res) done. Post: the cut must be rebuilt. Returns the
// number of splits. O(n).
int precondition_pass(CutResult& res) {
  auto& rs = res.surface;
  auto& Mm = rs.mesh;
  const int nd = static_cast<int>(res.disk_to_surface.size());
  std::vector<int> side_a(nd, -1), side_b(nd, -1);  // the (at most two) sides through a disk vertex
  for (int s = 0; s < static_cast<int>(res.sides.size()); ++s)
    for (int d : res.sides[s].disk_vertices) (side_a[d] < 0 ? side_a[d] : side_b[d]) = s;
  auto share_side = [&](int p, int q) {
    if (side_a[p] < 0 || side_a[q] < 0) return false;
    return side_a[p] == side_a[q] || side_a[p] == side_b[q] || (side_b[p] >= 0 && (side_b[p] == side_a[q] || side_b[p] == side_b[q]));
  };
  std::vector<char> is_cut(Mm.num_halfedges(), 0);
  for (const auto& L : res.loops)
    for (std::size_t j = 0; j < L.size(); ++j) {
      const int h = find_he(Mm, L[j], L[(j + 1) % L.size()]);
      is_cut[h] = is_cut[Mm.twin(h)] = 1;
    }
  auto disk_corner = [&](int h) { return res.disk_triangles[TriMesh::face(h)][h % 3]; };
  std::vector<std::pair<int, int>> todo;
  for (int h = 0; h < Mm.num_halfedges(); ++h)
    if (!is_cut[h] && h < Mm.twin(h) && share_side(disk_corner(h), disk_corner(TriMesh::next(h))))
      todo.push_back({Mm.origin(h), Mm.target(h)});
  for (auto [a, b] : todo) rs.split_edge(find_he(Mm, a, b), make_rational(1, 2));
  return static_cast<int>(todo.size());
}

// Renumbers and reorients res.loops so that the word `cur` (the loops' word up to rotation, in g
// commutator blocks) reads exactly L0 L1 L0^-1 L1^-1 L2 L3 ... Throws Internal if it is not in
// blocks. O(n).
void relabel_blocks(CutResult& res, const Word& cur) {
  const int r = commutator_rotation(cur);
  if (r < 0) internal("word is not in commutator blocks: " + to_string(cur));
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

// The greedy homotopy basis at `root` (metric: 3D edge lengths, or hop counts if `hops`, plus
// (penalty[a] + penalty[b]) / 2 per edge ab if `penalty` is given, one value per input vertex) and
// the plan of its detaching (steps 1-2 up to the owners):
// the surface with the band splits, the pruned tree, the tour and the owners. `crossings` is the
// number of edge crossings the strands will make (the dynamic programme's optimum, chord splits
// not counted). Pre: mesh valid, connected, of genus `genus` >= 1. Cost O(n log n).
struct DetachPlan {
  RefinedSurface rs;
  int root = -1;
  int root_start = -1;  // the tour starts at the root's edge to this vertex (-1: its stored half-edge)
  std::vector<int> parent, leaf_a, leaf_b, leaves, leaf_index, min_leaf, max_leaf, owner;
  std::vector<char> pruned, is_leaf;
  long long crossings = 0;
  int band_splits = 0;
  bool hops = false;  // the metric of the basis
};

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

void plan_strands(DetachPlan& P, const std::vector<std::pair<int, int>>& bands);

// The vertex count a plan's realization will have: one new vertex per crossing (chord splits and
// face vertices, usually none, come on top).
long planned_vertices(const DetachPlan& P) { return P.rs.mesh.num_vertices() + P.crossings; }

DetachPlan plan_detach(const TriMesh& mesh, const std::vector<Vec3d>& positions, int root, int genus, bool hops,
                       const std::vector<double>* penalty = nullptr) {
  auto edge_length = [&](int a, int b) {
    const double base = hops ? 1.0 : length(positions[a], positions[b]);
    return penalty ? base + 0.5 * ((*penalty)[a] + (*penalty)[b]) : base;
  };
  DetachPlan P;
  P.root = root;
  P.hops = hops;
  const int nv0 = mesh.num_vertices();
  RefinedSurface& rs = P.rs;
  rs.mesh = mesh;
  rs.num_input_vertices = nv0;
  // ---- 1. greedy homotopy basis: shortest-path tree + dual maximum spanning tree ----
  std::vector<double> dist(nv0, INFINITY);
  std::vector<int>& parent = P.parent;
  parent.assign(nv0, -1);
  {
    MinQueue pq;
    dist[root] = 0;
    pq.push({0.0, root});
    settle_all(mesh, dist, pq, [&](int v, int w, double d) {
      const double nd = d + edge_length(v, w);
      if (nd < dist[w]) dist[w] = nd, parent[w] = v, pq.push({nd, w});
    });
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
      cand.push_back({dist[a] + dist[b] + edge_length(a, b), h});
    }
    sort_by_weight_descending(cand);  // heaviest first, ties by half-edge
    UnionFind dsu(mesh.num_faces());
    for (const auto& [w, h] : cand) {
      (void)w;
      if (!dsu.unite(TriMesh::face(h), TriMesh::face(mesh.twin(h)))) bands.push_back({mesh.origin(h), mesh.target(h)});
    }
    if (static_cast<int>(bands.size()) != 2 * genus)
      internal("tree-cotree left " + std::to_string(bands.size()) + " edges, expected 2g = " + std::to_string(2 * genus));
  }
  plan_strands(P, bands);
  return P;
}

// Step 2 planned for the loops root~u, uv, v~root of `bands` on the tree P.parent (rooted at P.root;
// every band end reaches the root through it): the band splits (done on P.rs), the pruned tree, the
// tour (counter-clockwise from the root's edge to P.root_start), the owners and the word. Pre:
// P.rs, P.root, P.parent (size V) set; the tree edges at the root lie in one wedge that the tour
// start does not cut. Cost O(n + total strand length).
void plan_strands(DetachPlan& P, const std::vector<std::pair<int, int>>& bands) {
  RefinedSurface& rs = P.rs;
  const int root = P.root;
  std::vector<int>& parent = P.parent;
  const int nv_bands = rs.mesh.num_vertices();
  // ---- 2. detach: band splits, extended tree, strands as normal curves ----
  std::vector<int>& leaf_a = P.leaf_a;
  std::vector<int>& leaf_b = P.leaf_b;
  leaf_a.resize(bands.size());
  leaf_b.resize(bands.size());
  // A band end that is a leaf of the tree spanned by all band ends (not the root, the end of no
  // other band, no band end below it) is the strand's end itself; the other ends get a vertex on
  // the band edge hanging below them (at 1/3 and 2/3 of the edge, or at 1/2 if one end is a leaf).
  {
    std::vector<int> ends(nv_bands, 0);
    std::vector<char> has_below(nv_bands, 0);
    for (auto [u, v] : bands) ++ends[u], ++ends[v];
    for (auto [u, v] : bands)
      for (int x : {u, v})
        // Climbs at most once per vertex (stops at marked ones): O(V) in total.
        for (int y = parent[x]; y >= 0 && !has_below[y]; y = parent[y]) has_below[y] = 1;
    auto own_end = [&](int x) { return x != root && ends[x] == 1 && !has_below[x]; };
    for (std::size_t i = 0; i < bands.size(); ++i) {
      auto [u, v] = bands[i];
      const bool keep_u = own_end(u), keep_v = own_end(v);
      int a = u, b = v;
      if (!keep_u && !keep_v) {
        a = rs.split_edge(find_he(rs.mesh, u, v), make_rational(1, 3));
        b = rs.split_edge(find_he(rs.mesh, a, v), make_rational(1, 2));
      } else if (!keep_u) {
        a = rs.split_edge(find_he(rs.mesh, u, v), make_rational(1, 2));
      } else if (!keep_v) {
        b = rs.split_edge(find_he(rs.mesh, u, v), make_rational(1, 2));
      }
      parent.resize(rs.mesh.num_vertices(), -1);
      if (a != u) parent[a] = u, ++P.band_splits;
      if (b != v) parent[b] = v, ++P.band_splits;
      leaf_a[i] = a;
      leaf_b[i] = b;
    }
  }
  auto& M = rs.mesh;
  const int root_h0 = P.root_start >= 0 ? find_he(M, root, P.root_start) : M.vertex_halfedge(root);
  std::vector<char>& pruned = P.pruned;
  std::vector<char>& is_leaf = P.is_leaf;
  pruned.assign(M.num_vertices(), 0);
  is_leaf.assign(M.num_vertices(), 0);
  for (std::size_t i = 0; i < bands.size(); ++i) {
    is_leaf[leaf_a[i]] = is_leaf[leaf_b[i]] = 1;
    for (int x : {leaf_a[i], leaf_b[i]})
      // Climbs at most once per vertex (stops at marked ones): O(V) in total.
      for (; x >= 0 && !pruned[x]; x = parent[x]) pruned[x] = 1;
  }
  if (!pruned[root]) internal("root not on the tree");
  // Children in ccw order after the parent (root: after its stored half-edge), and for a vertex
  // other than the root the number of edges strictly between the parent edge and each child edge,
  // counted counter-clockwise (the other side holds valence - 2 - that many).
  const int nv_tree = M.num_vertices();
  auto children = [&](int x, std::vector<int>* ccw_gap) {
    std::vector<int> ch;
    const int h0 = x == root ? root_h0 : find_he(M, x, parent[x]);
    int h = h0, steps = 0;
    do {  // one turn around x: valence steps
      const int w = M.target(h);
      if (w != (x == root ? -1 : parent[x]) && pruned[w] && parent[w] == x) {
        ch.push_back(w);
        if (ccw_gap) ccw_gap->push_back(steps - 1);
      }
      h = M.next_around_origin(h);
      ++steps;
    } while (h != h0);
    return ch;
  };
  std::vector<int>&leaf_index = P.leaf_index, &max_leaf = P.max_leaf, &min_leaf = P.min_leaf;
  leaf_index.assign(nv_tree, -1);
  max_leaf.assign(nv_tree, -1);
  min_leaf.assign(nv_tree, -1);
  std::vector<int>& leaves = P.leaves;  // tour order
  std::vector<int> post;    // pruned non-leaf vertices, children before parents
  {
    // Iterative DFS; each pruned vertex pushed once: O(V + E).
    std::vector<std::pair<int, std::vector<int>>> stack;
    std::vector<std::size_t> pos;
    stack.push_back({root, children(root, nullptr)});
    pos.push_back(0);
    while (!stack.empty()) {
      auto& [x, ch] = stack.back();
      if (pos.back() < ch.size()) {
        int c = ch[pos.back()++];
        if (is_leaf[c]) {
          leaf_index[c] = static_cast<int>(leaves.size());
          min_leaf[c] = max_leaf[c] = leaf_index[c];
          leaves.push_back(c);
        } else {
          stack.push_back({c, children(c, nullptr)});
          pos.push_back(0);
        }
      } else {
        const int xv = x;
        max_leaf[xv] = max_leaf[ch.back()];
        min_leaf[xv] = min_leaf[ch.front()];
        post.push_back(xv);
        stack.pop_back();
        pos.pop_back();
      }
    }
    if (leaves.size() != 2 * bands.size()) internal("tour found " + std::to_string(leaves.size()) + " strand ends");
  }

  // Owners. Every tree vertex x but the root lies on exactly one strand, its owner o(x), the owner
  // of one of its children (so each strand owns a final part of its path, down to its leaf). The
  // other strands through x go around it: tour index < o(x) counter-clockwise (from the parent edge
  // to their child edge), > o(x) clockwise, crossing the edges in between. A strand that reaches x
  // on the other side (its owner changed at the parent) first crosses the parent edge. The owners
  // minimise the number of crossings, by dynamic programming over the tree: for each x and each
  // leaf l below it the cheapest crossings in x's subtree with o(x) = l (an empty sweep counts as
  // one, the chord split below). Cost O(sum of strand lengths + E).
  std::vector<int>& owner = P.owner;
  owner.assign(nv_tree, -1);
  {
    std::vector<std::vector<long long>> best(nv_tree);   // by leaf - min_leaf
    std::vector<long long> arr_ccw(nv_tree), arr_cw(nv_tree), arr_free(nv_tree);  // best on arrival
    std::vector<int> opt_ccw(nv_tree), opt_cw(nv_tree), opt_free(nv_tree);
    auto summarize = [&](int x) {  // the three arrival minima of a subtree with its best costs
      const auto& b = best[x];
      arr_ccw[x] = arr_cw[x] = arr_free[x] = INT64_MAX;
      for (int i = 0; i < static_cast<int>(b.size()); ++i) {
        const int l = min_leaf[x] + i;
        const long long cc = b[i] + (max_leaf[x] - l), cw = b[i] + (l - min_leaf[x]);
        if (cc < arr_ccw[x]) arr_ccw[x] = cc, opt_ccw[x] = l;
        if (cw < arr_cw[x]) arr_cw[x] = cw, opt_cw[x] = l;
        if (b[i] < arr_free[x]) arr_free[x] = b[i], opt_free[x] = l;
      }
    };
    for (int l : leaves) {
      best[l].assign(1, 0);
      summarize(l);
    }
    std::vector<int> gap;
    for (int x : post) {
      if (x == root) continue;
      gap.clear();
      const std::vector<int> ch = children(x, &gap);
      const int m = static_cast<int>(ch.size());
      const int val = M.valence(x);
      std::vector<long long> before(m + 1, 0), after(m + 1, 0);  // sums over children < i, >= i
      std::vector<long long> s_ccw(m), s_cw(m);
      for (int i = 0; i < m; ++i) {
        s_ccw[i] = std::max(gap[i], 1);
        s_cw[i] = std::max(val - 2 - gap[i], 1);
      }
      for (int i = 0; i < m; ++i) {
        const int c = ch[i];
        const long long n = max_leaf[c] - min_leaf[c] + 1;
        before[i + 1] = before[i] + n * s_ccw[i] + arr_ccw[c];
      }
      for (int i = m - 1; i >= 0; --i) {
        const int c = ch[i];
        const long long n = max_leaf[c] - min_leaf[c] + 1;
        after[i] = after[i + 1] + n * s_cw[i] + arr_cw[c];
      }
      auto& b = best[x];
      b.assign(max_leaf[x] - min_leaf[x] + 1, 0);
      for (int i = 0; i < m; ++i) {
        const int c = ch[i];
        for (int l = min_leaf[c]; l <= max_leaf[c]; ++l)
          b[l - min_leaf[x]] = best[c][l - min_leaf[c]] + before[i] + after[i + 1] + (l - min_leaf[c]) * s_ccw[i] +
                               (max_leaf[c] - l) * s_cw[i];
        std::vector<long long>().swap(best[c]);
      }
      summarize(x);
    }
    // Top down (reverse post-order visits parents first).
    for (auto it = post.rbegin(); it != post.rend(); ++it) {
      const int x = *it;
      for (int c : children(x, nullptr)) {
        if (x == root) owner[c] = opt_free[c];
        else if (owner[x] >= min_leaf[c] && owner[x] <= max_leaf[c]) owner[c] = owner[x];
        else owner[c] = owner[x] > max_leaf[c] ? opt_ccw[c] : opt_cw[c];
      }
    }
    for (int l : leaves)
      if (owner[l] != leaf_index[l]) internal("leaf not owned by its strand", {l});
    for (int c : children(root, nullptr)) P.crossings += arr_free[c];
  }
}

// Congestion penalties (negotiated congestion, after the PathFinder router of McMurchie & Ebeling
// 1995). Strands that share a tree path are drawn side by side (step 2), and past the free vertices
// beside the path each further strand costs a crossing vertex per edge it passes. So after a plan
// every tree vertex x of the input (x < nv0, not the root) that k > 1 strands pass has its penalty
// raised by raise * (k - 1); a basis recomputed with the metric plus the penalties (per edge ab,
// (penalty[a] + penalty[b]) / 2) routes its paths around the crowded vertices, and its cotree,
// weighted by the same loop lengths, picks other bands. O(nv0).
void raise_penalties(const DetachPlan& p, int nv0, double raise, std::vector<double>& penalty) {
  for (int x = 0; x < nv0; ++x)  // input vertices only (band splits and chord splits come after them)
    if (x != p.root && p.pruned[x] && !p.is_leaf[x]) {
      const int k = p.max_leaf[x] - p.min_leaf[x] + 1;
      if (k > 1) penalty[x] += raise * (k - 1);
    }
}

// The unit of a metric on `unit` positions: the mean edge length (0 only if every edge has length
// 0; the penalties then do nothing), or one hop. O(E).
double metric_unit(const TriMesh& mesh, const std::vector<Vec3d>& unit, bool hops) {
  if (hops) return 1.0;
  double sum = 0;
  for (int h = 0; h < mesh.num_halfedges(); ++h) sum += length(unit[mesh.origin(h)], unit[mesh.target(h)]);
  return sum / mesh.num_halfedges();
}

// Throws InvalidArgument unless CutOptions::congestion_step is finite and > 0.
void check_congestion_step(double step) {
  if (!(step > 0) || !std::isfinite(step))
    throw Error(ErrorKind::InvalidArgument, "CutOptions::congestion_step must be finite and > 0, got " + std::to_string(step));
}

// The congestion reweighting of the basis (not of the normal form's rounds, whose outcomes jump
// from round to round: there it would lose, e.g. couplingdown 2141 -> 2167 vertices) stops after
// this many rounds without a new best plan: on the shared meshes and generated genus 2-12 it loses
// nothing against running all rounds (1,595 vertices added in all against 1,620) and takes 30 %
// less time.
constexpr int kCongestionPatience = 10;

// The round budget of the congestion reweighting: CutOptions::congestion_rounds, or for -1
// clamp(per_faces / F, least, 40).
int congestion_budget(const CutOptions& options, const TriMesh& mesh, long per_faces, long least) {
  if (options.congestion_rounds >= 0) return options.congestion_rounds;
  return static_cast<int>(std::clamp(per_faces / std::max(1, mesh.num_faces()), least, 40L));
}

// Step 1c: up to `rounds` rounds (and at most `patience` after the last new best) of congestion
// reweighting from the plan `best`, the penalties (raise_penalties, `raise` per extra strand)
// accumulating over the rounds, each from the last plan made. replan(penalty, plan) makes a plan
// with the penalties, or returns false (that round gives none). `best` becomes the plan with the
// fewest planned vertices (the earliest on ties), so never more than it had; kept(r) is called
// when round r's plan becomes the best, before it moves into `best`. Returns the index of the
// round kept (0: none). Deterministic. Cost: `rounds` replans and O(rounds nv0).
template <class Replan, class Kept>
int reweight_for_congestion(DetachPlan& best, int nv0, double raise, int rounds, int patience, Replan&& replan,
                            Kept&& kept) {
  std::vector<double> penalty(nv0, 0.0);
  DetachPlan current;
  const DetachPlan* last = &best;
  long best_count = planned_vertices(best);
  int best_round = 0;
  for (int r = 1; r <= rounds && r - best_round <= patience; ++r) {
    raise_penalties(*last, nv0, raise, penalty);
    DetachPlan next;
    if (!replan(penalty, next)) continue;
    const long count = planned_vertices(next);
    if (count < best_count) {
      best_count = count;
      best_round = r;
      kept(r);
      best = std::move(next);
      last = &best;
    } else {
      current = std::move(next);
      last = &current;
    }
  }
  return best_round;
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

// v's exact point without a copy: a constructed vertex's own, an input vertex's (weight 1) set in
// `scratch` (its limbs reused).
const SurfacePoint& point_of(const RefinedSurface& rs, int v, SurfacePoint& scratch) {
  if (v >= rs.num_input_vertices) return rs.constructed[v - rs.num_input_vertices];
  scratch.v = {v, -1, -1};
  scratch.w[0] = 1, scratch.w[1] = 0, scratch.w[2] = 0;
  return scratch;
}

// make(begin, end) over [0, n): in two halves, the second on a thread of its own when `parallel`
// and n is at least kPointsPerThread (below that a thread costs more than it saves); adds n to
// stats.points_on_two_threads if it ran so. For the exact points of new vertices, each made from
// points made before: no two calls write the same point. Used where the drawing of the kept plan
// has both threads to itself (the crossings); the rounds' and the crosses' chord midpoints gained
// nothing measurable on two threads (cheese: 0.057 s for all of them on one).
constexpr std::size_t kPointsPerThread = 1024;
template <class Make>
void make_in_halves(bool parallel, std::size_t n, CutStats& stats, Make&& make) {
  const std::size_t half = n / 2;
  if (run_pair(parallel && n >= kPointsPerThread, [&] { make(0, half); }, [&] { make(half, n); }))
    stats.points_on_two_threads += static_cast<long long>(n);
}

// Step 2 realized: draws the strands planned in P as pairwise disjoint normal curves around the
// pruned tree and re-triangulates the faces they cross (on P.rs; vertex ids are kept, new ones are
// appended). Returns the loops, one per band in band order, each from the root. Adds to
// stats.crossings, steiner_vertices and chord_splits. Cost O(n + total crossings).
std::vector<std::vector<int>> realize_strands(DetachPlan& P, CutStats& stats, bool parallel) {
  RefinedSurface& rs = P.rs;
  auto& M = rs.mesh;
  const int root = P.root;
  const std::vector<int>&parent = P.parent, &leaves = P.leaves, &leaf_index = P.leaf_index, &owner = P.owner;
  const std::vector<int>&leaf_a = P.leaf_a, &leaf_b = P.leaf_b;
  // The root-to-leaf paths, and which side each strand takes at each vertex it does not own.
  std::vector<std::vector<int>> paths(leaves.size());
  std::vector<int> first_owned(leaves.size());
  for (int k = 0; k < static_cast<int>(leaves.size()); ++k) {
    auto& path = paths[k];
    // The parent chain is acyclic (a shortest-path tree): at most V steps.
    for (int x = leaves[k]; x != root; x = parent[x]) path.push_back(x);
    path.push_back(root);
    std::reverse(path.begin(), path.end());
    int j0 = 1;
    while (j0 < static_cast<int>(path.size()) && owner[path[j0]] != k) ++j0;
    if (j0 == static_cast<int>(path.size())) internal("strand does not reach its leaf", {leaves[k]});
    first_owned[k] = j0;
  }
  // A strand that goes around x on the side it arrived on, with no edge between the parent edge
  // and the child edge on that side, would run along the edge parent-child ("chord"): split it.
  {
    std::vector<std::pair<int, int>> chords;
    for (int k = 0; k < static_cast<int>(leaves.size()); ++k) {
      const auto& path = paths[k];
      for (int j = 1; j < first_owned[k]; ++j) {
        const int x = path[j], p = path[j - 1], c = path[j + 1];
        const bool ccw = k < owner[x];
        const bool switched = j > 1 && (k < owner[p]) != ccw && owner[p] != owner[x];
        if (switched) continue;
        const int h_in = find_he(M, x, p), h_out = find_he(M, x, c);
        if (ccw ? M.next_around_origin(h_in) == h_out : M.next_around_origin(h_out) == h_in) chords.push_back({p, c});
      }
    }
    std::sort(chords.begin(), chords.end());
    chords.erase(std::unique(chords.begin(), chords.end()), chords.end());
    for (auto [p, c] : chords) {
      const int h = M.find_halfedge(p, c);
      if (h < 0) continue;  // split already from the other side (listed as (c, p)): never twice
      rs.split_edge(h, make_rational(1, 2));
      ++stats.chord_splits;
    }
  }
  const int nv1 = M.num_vertices();

  std::vector<Crossing> crossings;
  std::vector<FaceArc> arcs;
  std::vector<std::vector<int>> strand_points(leaves.size());  // point codes
  for (int k = 0; k < static_cast<int>(leaves.size()); ++k) {
    const auto& path = paths[k];
    const int j0 = first_owned[k];
    auto& pts = strand_points[k];
    pts.push_back(root);
    int prev_pt = root;
    int face_cur = -1;
    auto cross = [&](int g, int x) {  // crosses the edge of half-edge g near x
      crossings.push_back({std::min(g, M.twin(g)), x, k});
      const int code = -1 - static_cast<int>(crossings.size() - 1);
      arcs.push_back({face_cur, prev_pt, code});
      pts.push_back(code);
      prev_pt = code;
    };
    for (int j = 1; j < j0; ++j) {
      const int x = path[j];
      const int h_in = find_he(M, x, path[j - 1]), h_out = find_he(M, x, path[j + 1]);
      const bool ccw = k < owner[x];
      // The face on the strand's side of the parent edge: left of x->parent for ccw.
      const int side_face = ccw ? TriMesh::face(h_in) : TriMesh::face(M.twin(h_in));
      if (j == 1) {
        face_cur = side_face;
      } else if (face_cur != side_face) {
        const int other = ccw ? TriMesh::face(M.twin(h_in)) : TriMesh::face(h_in);
        if (face_cur != other) internal("strand leaves its face", {x});
        cross(h_in, x);  // change sides across the parent edge
        face_cur = side_face;
      }
      // Sweep the edges at x from the parent to the child: at most valence(x) steps.
      if (ccw) {
        for (int g = M.next_around_origin(h_in); g != h_out; g = M.next_around_origin(g)) {
          if (g == h_in) internal("sweep around a tree vertex did not meet the child", {x});
          cross(g, x);
          face_cur = TriMesh::face(g);
        }
      } else {
        // Clockwise: the half-edge before g around x is the one whose next_around_origin is g.
        int g = h_in;
        for (int guard = 0;; ++guard) {
          const int pg = TriMesh::next(M.twin(g));  // clockwise neighbour: next_around_origin(pg) == g
          if (pg == h_out) break;
          if (pg == h_in || guard > M.num_halfedges()) internal("sweep around a tree vertex did not meet the child", {x});
          face_cur = TriMesh::face(pg);
          cross(pg, x);
          g = pg;
        }
        face_cur = TriMesh::face(h_out);
      }
    }
    if (j0 > 1) arcs.push_back({face_cur, prev_pt, path[j0]});
    for (int j = j0; j < static_cast<int>(path.size()); ++j) pts.push_back(path[j]);
  }

  // Place crossings on their edges: the ones around the origin first (nearest = closest to the
  // origin's owner in tour order), then the ones around the target; parameters i/(n+1).
  int next_vertex = nv1;
  {
    std::vector<int> order(crossings.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int p, int q) {
      const Crossing &a = crossings[p], &b = crossings[q];
      if (a.edge != b.edge) return a.edge < b.edge;
      const bool a_first = a.side == M.origin(a.edge), b_first = b.side == M.origin(b.edge);
      if (a_first != b_first) return a_first;
      // Nearest to the vertex gone around: the strand closest to its owner in tour order.
      const int da = std::abs(a.strand - owner[a.side]), db = std::abs(b.strand - owner[b.side]);
      return a_first ? da < db : da > db;
    });
    // The k-th of an edge's n crossings (in order) is at k / (n + 1) from its origin: group[p] is
    // (k, n) for the p-th in order. The points are made in place, each from its edge's ends only.
    std::vector<std::pair<long, long>> group(order.size());
    for (std::size_t i = 0; i < order.size();) {
      std::size_t j = i;
      const int e = crossings[order[i]].edge;
      while (j < order.size() && crossings[order[j]].edge == e) ++j;
      for (std::size_t k = i; k < j; ++k)
        crossings[order[k]].vertex = next_vertex++, group[k] = {static_cast<long>(k - i + 1), static_cast<long>(j - i)};
      i = j;
    }
    const std::size_t made = rs.constructed.size();
    rs.constructed.resize(made + order.size());
    make_in_halves(parallel, order.size(), stats, [&](std::size_t begin, std::size_t end) {
      SurfacePoint sa, sb;
      for (std::size_t p = begin; p < end; ++p) {
        const int e = crossings[order[p]].edge;
        lerp_into(rs.constructed[made + p], point_of(rs, M.origin(e), sa), point_of(rs, M.target(e), sb),
                  make_rational(group[p].first, group[p].second + 1));
      }
    });
  }
  stats.crossings += static_cast<int>(crossings.size());
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
      ++stats.steiner_vertices;
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
  const int nloops = static_cast<int>(leaf_a.size());
  std::vector<std::vector<int>> loops(nloops);
  {
    std::vector<std::vector<int>> strand_vertices(leaves.size());
    for (std::size_t k = 0; k < leaves.size(); ++k)
      for (int c : strand_points[k]) strand_vertices[k].push_back(vid(c));
    for (int i = 0; i < nloops; ++i) {
      const auto& sa = strand_vertices[leaf_index[leaf_a[i]]];
      const auto& sb = strand_vertices[leaf_index[leaf_b[i]]];
      auto& L = loops[i];
      L = sa;
      for (std::size_t j = sb.size() - 1; j >= 1; --j) L.push_back(sb[j]);
    }
  }
  return loops;
}

// The boundary word of loops at the root whose ends, in ccw order, are `ends` (per end: loop id,
// and whether it is the loop's last edge; each loop twice): the boundary walk leaves along an
// end, comes back at its mate and leaves along the next end clockwise (build_cut's rule),
// starting with the end at position `start`. departures[k] is the position letter k leaves from.
// Returns an empty word if the walk closes before it has used every end (more than one boundary
// cycle). For ends in one wedge, start = m - 1 reads the word from the corner outside the wedge.
// O(m log m).
Word trace_word(const std::vector<Letter>& ends, int start, std::vector<int>* departures) {
  const int m = static_cast<int>(ends.size());
  std::vector<int> order(m), mate(m, -1);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return ends[a].loop != ends[b].loop ? ends[a].loop < ends[b].loop : a < b; });
  for (int k = 0; k < m; k += 2) {
    if (k + 1 == m || ends[order[k]].loop != ends[order[k + 1]].loop) internal("boundary word: a loop without two ends");
    mate[order[k]] = order[k + 1], mate[order[k + 1]] = order[k];
  }
  Word w;
  departures->clear();
  int leave = start;
  for (int k = 0; k < m; ++k) {  // m steps
    if (k > 0 && leave == start) return {};
    w.push_back(ends[leave]);
    departures->push_back(leave);
    leave = (mate[leave] + m - 1) % m;
  }
  return w;
}

// True if w is non-empty and p q p^-1 q^-1 blocks from letter 0 on (any ids and orientations).
bool blocks_from_start(const Word& w) {
  if (w.empty() || w.size() % 4 != 0) return false;
  for (std::size_t k = 0; k < w.size(); k += 4) {
    const Letter &p = w[k], &q = w[k + 1], &pi = w[k + 2], &qi = w[k + 3];
    if (p.loop == q.loop || pi.loop != p.loop || qi.loop != q.loop || pi.inverse == p.inverse || qi.inverse == q.inverse)
      return false;
  }
  return true;
}

// Depth-first tour of a tree on M from the root, counter-clockwise after the parent edge (the
// root: all of its half-edges from root_h0 on): child(h) says whether target(h) is a child of
// origin(h); visit(h) is called, in tour order, for every other half-edge out of a tree vertex
// (the parent edges excepted). Each tree vertex once: O(E).
template <class Child, class Visit>
void tour_tree(const TriMesh& M, int root_h0, Child&& child, Visit&& visit) {
  struct It { int h, stop; };
  std::vector<It> st;
  auto step = [&](int h) {
    if (child(h)) st.push_back({M.next_around_origin(M.twin(h)), M.twin(h)});
    else visit(h);
  };
  int h = root_h0;
  do {  // valence(root) steps, each followed by one subtree
    step(h);
    while (!st.empty()) {
      It& t = st.back();
      if (t.h == t.stop) {
        st.pop_back();
        continue;
      }
      const int g = t.h;
      t.h = M.next_around_origin(g);
      step(g);  // may push (t is not used after)
    }
    h = M.next_around_origin(h);
  } while (h != root_h0);
}

// The tree G of the canonical construction: parent, distance from the root along G, membership.
struct GammaTree {
  std::vector<int> pg;
  std::vector<double> dg;
  std::vector<char> on_g;
  void grow(int nv) {
    pg.resize(nv, -1);
    dg.resize(nv, INFINITY);
    on_g.resize(nv, 0);
  }
};

// The tour of G (with the bands `taken`) on M: rot = the taken ends in tour order (Letter{band,
// end at v}), gap_of[h] = the number of ends before the half-edge h out of G that is neither a tree
// edge nor a band (-1 for the others), band_of[h] = the taken band on h's edge (-1: none);
// gap_halfedges (if given) = the half-edges with gap_of[h] >= 0, ascending. O(E).
void gamma_tour(const TriMesh& M, const GammaTree& K, const std::vector<std::pair<int, int>>& taken, int root,
                int root_h0, std::vector<int>& band_of, std::vector<int>& gap_of, std::vector<Letter>& rot,
                std::vector<int>* gap_halfedges = nullptr) {
  const int nh = M.num_halfedges();
  band_of.assign(nh, -1);
  for (std::size_t i = 0; i < taken.size(); ++i) {
    const int h = find_he(M, taken[i].first, taken[i].second);
    band_of[h] = band_of[M.twin(h)] = static_cast<int>(i);
  }
  gap_of.assign(nh, -1);
  rot.clear();
  tour_tree(
      M, root_h0,
      [&](int h) {
        const int b = M.target(h);
        return band_of[h] < 0 && K.on_g[b] && b != root && K.pg[b] == M.origin(h);
      },
      [&](int h) {
        const int i = band_of[h];
        if (i >= 0) rot.push_back(Letter{i, M.origin(h) != taken[i].first});
        else gap_of[h] = static_cast<int>(rot.size());
      });
  // Each visited once; in ascending order by a scan (sorting them cost the rounds on cheese 12 %).
  if (gap_halfedges) {
    gap_halfedges->clear();
    for (int h = 0; h < nh; ++h)
      if (gap_of[h] >= 0) gap_halfedges->push_back(h);
  }
}

// Appends to p the (unit-scaled, double) positions of S's vertices from p.size() on, to guide the
// searches only (path lengths): each weight rounded to a double, then summed in doubles (not the
// exact point rounded, as evaluate() gives: a fifth of a crosses candidate's time on cheese).
// O(new vertices).
void extend_positions(const RefinedSurface& S, const std::vector<Vec3d>& unit, std::vector<Vec3d>& p) {
  while (static_cast<int>(p.size()) < S.mesh.num_vertices()) {
    const SurfacePoint& q = S.constructed[p.size() - S.num_input_vertices];
    Vec3d r{0, 0, 0};
    for (int i = 0; i < 3 && q.v[i] >= 0; ++i) {
      const double w = q.w[i].get_d();
      const Vec3d& u = unit[q.v[i]];
      r.x += w * u.x, r.y += w * u.y, r.z += w * u.z;
    }
    p.push_back(r);
  }
}

// The first child of the root in G, counter-clockwise from the root's stored half-edge (G's tour
// starts at its edge). O(valence).
int first_child_of_root(const TriMesh& M, const GammaTree& G, int root) {
  const int h0 = M.vertex_halfedge(root);
  int h = h0;
  while (!(G.on_g[M.target(h)] && G.pg[M.target(h)] == root)) {
    h = M.next_around_origin(h);
    if (h == h0) internal("normal form: G has no edge at the root");
  }
  return M.target(h);
}

// The end of both normal-form constructions: checks that the word traced from the tour of G
// (from the root's edge to root_start) with the bands `taken` is one cycle in commutator blocks
// (Internal otherwise), then plans step 2 once (all loops detached along G) without drawing it:
// the caller realizes only the candidate it keeps (realize_strands). True: res.surface has moved
// into `plan` and planned_vertices(plan) <= vertex_limit; false: the plan would pass
// vertex_limit (res.surface kept). O(n + total strand length).
bool plan_along_tree(CutResult& res, const GammaTree& G, int root_start, const std::vector<std::pair<int, int>>& taken,
                     long vertex_limit, DetachPlan& plan) {
  RefinedSurface& rs = res.surface;
  {
    std::vector<int> band_of, gap_of, dep;
    std::vector<Letter> rot;
    gamma_tour(rs.mesh, G, taken, res.root, find_he(rs.mesh, res.root, root_start), band_of, gap_of, rot);
    const Word w = trace_word(rot, 0, &dep);
    if (w.empty() || rot.size() != 2 * taken.size() || static_cast<int>(taken.size()) != 2 * res.genus ||
        commutator_rotation(w) < 0)
      internal("normal form: the final word is not in blocks: " + to_string(w));
  }
  plan = DetachPlan{};
  plan.root = res.root;
  plan.root_start = root_start;
  plan.parent = G.pg;
  plan.rs = std::move(rs);
  plan_strands(plan, taken);
  res.stats.band_splits += plan.band_splits;
  res.stats.predicted_crossings = plan.crossings;
  if (planned_vertices(plan) > vertex_limit) {
    rs = std::move(plan.rs);
    return false;
  }
  return true;
}

// The chords of M: its edges between two vertices of is_wall but for those skip(a, b, h) names (h:
// a -> b), as pairs (a, b) with a < b, sorted: made in order, each wall vertex's higher neighbours
// sorted in turn. Both constructions' copies split these. O(n + sum of valence log valence).
template <class IsWall, class Skip>
std::vector<std::pair<int, int>> sorted_chords(const TriMesh& M, IsWall&& is_wall, Skip&& skip) {
  std::vector<std::pair<int, int>> chords;
  std::vector<int> higher;
  for (int a = 0; a < M.num_vertices(); ++a) {
    if (!is_wall(a)) continue;
    higher.clear();
    const int h0 = M.vertex_halfedge(a);
    int h = h0;
    do {
      const int b = M.target(h);
      if (b > a && is_wall(b) && !skip(a, b, h)) higher.push_back(b);
      h = M.next_around_origin(h);
    } while (h != h0);
    std::sort(higher.begin(), higher.end());
    for (int b : higher) chords.push_back({a, b});
  }
  return chords;
}

// Splits chords (sorted vertex pairs (a, b), a < b, edges of the mesh M that split(k, h) splits)
// in order, the k-th (where need is null or need[k]) through split(k, h) with h its half-edge a -> b.
// Each a's half-edges are read once, when its first chord comes: a split of (a, b) (TriMesh::
// split_edge) renumbers only the half-edges of the two edges at b that its faces have off a, so
// the half-edges out of a read before it stay those of their edges (a find per chord walked a's
// fan every time). O(n + chords).
template <class Split>
void split_sorted_chords(const TriMesh& M, const std::vector<std::pair<int, int>>& chords, const std::vector<char>* need,
                         Split&& split) {
  std::vector<std::pair<int, int>> out_of_a;  // (target, half-edge)
  for (std::size_t k = 0, end = 0; k < chords.size(); k = end) {
    const int a = chords[k].first;
    bool any = false;
    for (end = k; end < chords.size() && chords[end].first == a; ++end) any = any || !need || (*need)[end];
    if (!any) continue;
    out_of_a.clear();
    const int h0 = M.vertex_halfedge(a);
    int h = h0;
    do {
      out_of_a.push_back({M.target(h), h});
      h = M.next_around_origin(h);
    } while (h != h0);
    for (std::size_t j = k; j < end; ++j) {
      if (need && !(*need)[j]) continue;
      const int b = chords[j].second;
      const auto it = std::find_if(out_of_a.begin(), out_of_a.end(), [b](const auto& e) { return e.first == b; });
      if (it == out_of_a.end()) internal("missing edge", {a, b});
      split(j, it->second);
    }
  }
}

// A copy of M with every chord (sorted vertex pairs of M) split at its midpoint: combinatorics
// and double positions only, to guide a search. mid[k] is chord k's midpoint (ids from
// M.num_vertices() on, in chord order). O(n + chords).
TriMesh split_copy(const TriMesh& M, const std::vector<Vec3d>& pos, const std::vector<std::pair<int, int>>& chords,
                   std::vector<int>& mid, std::vector<Vec3d>& pos_copy) {
  TriMesh copy;
  const int splits = static_cast<int>(chords.size());
  copy.reserve(M.num_vertices() + splits, M.num_faces() + 2 * splits);  // one copy of the arrays, no regrowth
  copy = M;
  pos_copy.reserve(pos.size() + chords.size());
  pos_copy.assign(pos.begin(), pos.end());
  mid.resize(chords.size());
  split_sorted_chords(copy, chords, nullptr, [&](std::size_t k, int h) {
    const auto [a, b] = chords[k];
    mid[k] = copy.split_edge(h);
    pos_copy.push_back({(pos[a].x + pos[b].x) / 2, (pos[a].y + pos[b].y) / 2, (pos[a].z + pos[b].z) / 2});
  });
  return copy;
}

// After a search on split_copy(rs.mesh, ..., chords, mid, ...) (copy_nv vertices): splits on rs,
// in the copy's order, the chords that the copy's edges `used` cross, and every chord of a face
// where a used edge meets two, so that those faces are triangulated as in the copy and the used
// edges exist on rs. Returns the map from the copy's vertices to rs's (-1: a midpoint not split);
// `splits` counts the splits. O(chords + used).
std::vector<int> split_like_copy(RefinedSurface& rs, const std::vector<std::pair<int, int>>& chords,
                                 const std::vector<int>& mid, int copy_nv,
                                 const std::vector<std::pair<int, int>>& used, int& splits) {
  const TriMesh& M = rs.mesh;
  const int nv = M.num_vertices();
  std::vector<char> need(chords.size(), 0);
  auto chord_index = [&](int a, int b) {
    const std::pair<int, int> k{std::min(a, b), std::max(a, b)};
    const auto it = std::lower_bound(chords.begin(), chords.end(), k);
    return it != chords.end() && *it == k ? static_cast<int>(it - chords.begin()) : -1;
  };
  std::vector<int> index_of_mid(copy_nv - nv, -1);
  for (std::size_t k = 0; k < chords.size(); ++k) index_of_mid[mid[k] - nv] = static_cast<int>(k);
  auto close_face = [&](int f) {
    int count = 0;
    for (int g : {f, TriMesh::next(f), TriMesh::prev(f)}) count += chord_index(M.origin(g), M.target(g)) >= 0;
    if (count >= 2)
      for (int g : {f, TriMesh::next(f), TriMesh::prev(f)}) {
        const int c = chord_index(M.origin(g), M.target(g));
        if (c >= 0) need[c] = 1;
      }
  };
  // An edge at a midpoint lies in one face of rs at the midpoint's chord (the face opposite its
  // other end, or the face two chords share).
  for (auto [p, q] : used) {
    if (p < nv && q < nv) continue;
    if (p < nv) std::swap(p, q);  // p is a midpoint
    const int k = index_of_mid[p - nv];
    need[k] = 1;
    const int h = find_he(M, chords[k].first, chords[k].second);
    for (int g : {h, M.twin(h)}) {
      bool in_face = false;
      if (q < nv) {
        in_face = M.target(TriMesh::next(g)) == q;
      } else {
        const int kq = index_of_mid[q - nv];
        for (int e : {TriMesh::next(g), TriMesh::prev(g)}) in_face = in_face || chord_index(M.origin(e), M.target(e)) == kq;
      }
      if (in_face) close_face(g);
    }
    if (q >= nv) need[index_of_mid[q - nv]] = 1;
  }
  std::vector<int> to_surface(copy_nv, -1);
  std::iota(to_surface.begin(), to_surface.begin() + nv, 0);
  const Rational half = make_rational(1, 2);
  split_sorted_chords(rs.mesh, chords, &need, [&](std::size_t k, int h) {
    to_surface[mid[k]] = rs.split_edge(h, half);
    ++splits;
  });
  return to_surface;
}

// Step 3: the canonical system built handle by handle on one growing tree, with no slides. Gamma
// = a tree G from the root (parent pg, distance dg along G) and the bands taken so far; once
// detached along G (step 2, at the end) the loops root~u, uv, v~root leave the root in the order
// of G's counter-clockwise tour, and that order traces a word in commutator blocks (checked every
// round). A gap is the stretch of the tour between two consecutive taken ends (it becomes a
// corner of the polygon); a gap between blocks can take new blocks. One round:
//  a. the tour of G: each half-edge out of a vertex of G that is neither a tree edge nor a taken
//     band gets the gap it lies in; the word of the taken ends and its gaps between blocks (round 0:
//     the whole rotation of the root);
//  b. the gap t between blocks whose free half-edges reach the largest connected set of vertices
//     off Gamma;
//  c. greedy basis of the surface cut along Gamma: Dijkstra forest T from the free half-edges of
//     gap t (a vertex x of G starts at dg[x]; metric `hops` or 3D lengths, plus the congestion
//     penalties of the input vertices if `penalty` is given: raise_penalties) over the vertices off
//     Gamma; dual maximum spanning tree on the edges off T and off Gamma, every edge at a Gamma
//     vertex (but the sources) or at a vertex T misses forced in first;
//  d. the leftover edges' ends in the tour of G + T (they lie inside gap t); linked pairs (ends
//     X Y X' Y') taken greedily by right end as long as their word read from the gap stays in
//     blocks from its first letter; the taken bands and their paths in T join G.
// Chords (edges off Gamma joining two Gamma vertices) wall T off where branches of G run side by
// side. A round with no usable pair is searched again (c, d) on a copy of the surface with every
// chord split at its midpoint; then only the chords the taken paths cross are split on the
// surface, with every chord of the faces at them, in the copy's order (so that those faces are
// triangulated as in the copy and the paths exist). If that finds nothing either, gap t is given
// up for this round. Every round adds a block: at most g rounds, at most g + 1 gaps per round.
// Then step 2 detaches all 2g loops once, along G. Returns false as soon as the mesh would have
// more than vertex_limit vertices, or more than *rival (if given: the planned vertices of the
// crosses raced against it; the rounds only add vertices, so such a run would lose). Post (true):
// res.loops holds the 2g loops, their word in commutator blocks (relabelled by the caller);
// res.stats has the counts. Cost O(g^2 n log n + crossings) in the worst case, O(g n log n +
// crossings) when no gap is given up.
bool canonical_rounds(CutResult& res, const std::vector<Vec3d>& unit, bool hops, long vertex_limit, DetachPlan& plan,
                      const std::vector<double>* penalty = nullptr, const std::atomic<long>* rival = nullptr) {
  const int root = res.root, genus = res.genus;
  RefinedSurface& rs = res.surface;
  std::vector<Vec3d> pos(unit.begin(), unit.begin() + rs.num_input_vertices);
  auto extend = [&](const RefinedSurface& S, std::vector<Vec3d>& p) { extend_positions(S, unit, p); };
  GammaTree G;
  G.grow(rs.mesh.num_vertices());
  G.on_g[root] = 1;
  G.dg[root] = 0;
  std::vector<std::pair<int, int>> taken;  // the bands taken, (u, v): the loop root~u, uv, v~root
  int root_start = -1;  // after round 0: a child of the root in G (its edge is never split)
  auto root_h0 = [&](const TriMesh& M) { return root_start >= 0 ? find_he(M, root, root_start) : M.vertex_halfedge(root); };
  auto is_g = [&](const TriMesh& M, const GammaTree& K, const std::vector<int>& band_of, int h) {
    const int a = M.origin(h), b = M.target(h);
    return band_of[h] >= 0 ||
           (K.on_g[a] && K.on_g[b] && ((b != root && K.pg[b] == a) || (a != root && K.pg[a] == b)));
  };
  // The found pairs of a search: bands and the new vertices of G with their parents and distances.
  struct Found {
    std::vector<std::pair<int, int>> bands;
    std::vector<std::tuple<int, int, double>> verts;  // (vertex, parent, distance), parents first
  };
  // Steps c-d on S (the surface or a copy) with G's marks K (sized for S) and positions P, from the
  // gaps `gaps` at once (each vertex of T belongs to the gap its tree hangs from; an edge between two
  // gaps' parts is forced into the cotree; pairs are taken within one gap). Vertices >= first_mid
  // (chord midpoints of a copy) cost kMidpointCost more to enter or leave. False if no usable linked
  // pair. O(E log E + pairs * taken log taken).
  auto search = [&](const TriMesh& M, const GammaTree& K, const std::vector<Vec3d>& P,
                    const std::vector<int>& gaps, int round, int first_mid, Found& out) {
    constexpr double kMidpointCost = 1000.0;  // unit-scaled lengths: crossing a chord is a last resort
    const int nv = M.num_vertices(), nh = M.num_halfedges();
    auto len = [&](int a, int b) {
      const double base = (hops ? 1.0 : length(P[a], P[b])) + (a >= first_mid ? kMidpointCost : 0.0) +
                          (b >= first_mid ? kMidpointCost : 0.0);
      if (!penalty) return base;
      const int n0 = static_cast<int>(penalty->size());  // input vertices; splits and midpoints: none
      return base + 0.5 * ((a < n0 ? (*penalty)[a] : 0.0) + (b < n0 ? (*penalty)[b] : 0.0));
    };
    const int want = 2 * genus - static_cast<int>(taken.size());
    std::vector<int> band_of, gap_of, gap_hes;
    std::vector<Letter> rot;
    gamma_tour(M, K, taken, root, root_h0(M), band_of, gap_of, rot, &gap_hes);
    const int m = static_cast<int>(rot.size());
    std::vector<int> label_of_gap(m + 1, -1);  // gap number -> index in gaps (m: the outer gap's end)
    for (std::size_t k = 0; k < gaps.size(); ++k) {
      label_of_gap[gaps[k]] = static_cast<int>(k);
      if (gaps[k] == 0) label_of_gap[m] = static_cast<int>(k);
    }
    auto gap_label = [&](int h) { return gap_of[h] >= 0 ? label_of_gap[gap_of[h]] : -1; };
    // c. the forest T from the gaps, the cotree.
    std::vector<double> dist(nv, INFINITY);
    std::vector<int> par(nv, -1), label(nv, -1);
    {
      MinQueue pq;
      for (int h : gap_hes) {  // gap_label(h) >= 0 only there
        const int x = M.origin(h), y = M.target(h);
        if (gap_label(h) < 0 || K.on_g[y]) continue;
        if (K.dg[x] + len(x, y) < dist[y]) dist[y] = K.dg[x] + len(x, y), par[y] = x, label[y] = gap_label(h), pq.push({dist[y], y});
      }
      settle_all(M, dist, pq, [&](int v, int w, double d) {
        if (!K.on_g[w] && d + len(v, w) < dist[w]) dist[w] = d + len(v, w), par[w] = v, label[w] = label[v], pq.push({dist[w], w});
      });
    }
    auto t_edge = [&](int a, int b) { return (!K.on_g[b] && par[b] == a) || (!K.on_g[a] && par[a] == b); };
    auto dd = [&](int v) { return K.on_g[v] ? K.dg[v] : dist[v]; };
    // The gap an edge's loop would leave from at its end h (origin(h)): -1 if none.
    auto end_label = [&](int h) { return K.on_g[M.origin(h)] ? gap_label(h) : label[M.origin(h)]; };
    std::vector<std::pair<int, int>> bands;
    std::vector<double> band_len;
    std::vector<char> band_ok;
    {
      // The forced edges go into the dual tree first, in half-edge order, as they are found (a
      // leftover among them is a band that is not ok), then the others heaviest first (ties by
      // half-edge).
      std::vector<std::pair<double, int>> weighted;
      UnionFind dsu(M.num_faces());
      auto take = [&](double w, int h) {
        if (!dsu.unite(TriMesh::face(h), TriMesh::face(M.twin(h)))) {
          bands.push_back({M.origin(h), M.target(h)});
          band_len.push_back(w);
          band_ok.push_back(w < INFINITY);
        }
      };
      for (int h = 0; h < nh; ++h) {
        if (h > M.twin(h) || is_g(M, K, band_of, h)) continue;
        const int a = M.origin(h), b = M.target(h);
        if (t_edge(a, b)) continue;
        const int la = end_label(h), lb = end_label(M.twin(h));
        const bool forced = (K.on_g[a] && K.on_g[b]) || la < 0 || la != lb || !(dd(a) < INFINITY) || !(dd(b) < INFINITY);
        if (forced) take(INFINITY, h);
        else weighted.push_back({dd(a) + dd(b) + len(a, b), h});
      }
      sort_by_weight_descending(weighted);
      for (const auto& [w, h] : weighted) take(w, h);
      // A vertex off Gamma that T does not reach (cut off by chords) adds one edge.
      int dead = 0;
      for (int v = 0; v < nv; ++v) dead += !K.on_g[v] && !(dist[v] < INFINITY);
      if (static_cast<int>(bands.size()) != want + dead)
        internal("normal form: round " + std::to_string(round) + " left " + std::to_string(bands.size()) +
                 " edges, expected " + std::to_string(want) + " + " + std::to_string(dead));
    }
    // d. the leftover edges' ends in the tour of G + T, per gap (read from the gap: in the outer
    // gap, the part after the last taken end comes first), then the linked pairs per gap.
    const int nb = static_cast<int>(bands.size());
    std::vector<std::array<int, 2>> end_pos(nb, {-1, -1});
    std::vector<int> band_gap(nb, -1);
    {
      std::vector<int> cand_of(nh, -1);
      for (int i = 0; i < nb; ++i)
        if (band_ok[i]) {
          const int h = find_he(M, bands[i].first, bands[i].second);
          cand_of[h] = cand_of[M.twin(h)] = i;
          band_gap[i] = end_label(h);
        }
      // The tour descends only into T's vertices above a leftover edge's end (climbs stop at
      // marked vertices: O(n) in all).
      std::vector<char> above(nv, 0);
      for (int i = 0; i < nb; ++i)
        if (band_ok[i])
          for (int x : {bands[i].first, bands[i].second})
            for (; !K.on_g[x] && !above[x]; x = par[x]) above[x] = 1;
      std::vector<std::pair<std::pair<int, long long>, std::pair<int, int>>> met;  // ((gap, key), (band, end))
      int old = 0;
      long long counter = 0;
      tour_tree(
          M, root_h0(M),
          [&](int h) {
            const int a = M.origin(h), b = M.target(h);
            if (band_of[h] >= 0 || cand_of[h] >= 0) return false;
            return K.on_g[b] ? (K.on_g[a] && b != root && K.pg[b] == a) : par[b] == a && above[b];
          },
          [&](int h) {
            if (band_of[h] >= 0) {
              ++old;
            } else if (cand_of[h] >= 0) {
              const int i = cand_of[h], t = gaps[band_gap[i]];
              if (!(old == t || (t == 0 && old == m))) internal("normal form: a new loop end outside its gap");
              const long long key = (t == 0 && m > 0 && old == 0 ? (1LL << 40) : 0) + counter++;
              met.push_back({{band_gap[i], key}, {i, M.origin(h) == bands[i].first ? 0 : 1}});
            }
          });
      std::sort(met.begin(), met.end());
      for (std::size_t k = 0; k < met.size(); ++k)
        end_pos[met[k].second.first][met[k].second.second] = static_cast<int>(k);  // gaps apart
    }
    struct Pair { int gap, lo, hi, i, j; double cost; };
    std::vector<Pair> pairs;
    for (int i = 0; i < nb; ++i) {
      if (!band_ok[i] || end_pos[i][0] < 0 || end_pos[i][1] < 0) continue;
      const int li = std::min(end_pos[i][0], end_pos[i][1]), hi = std::max(end_pos[i][0], end_pos[i][1]);
      for (int j = 0; j < nb; ++j) {
        if (j == i || !band_ok[j] || band_gap[j] != band_gap[i] || end_pos[j][0] < 0 || end_pos[j][1] < 0) continue;
        const int lj = std::min(end_pos[j][0], end_pos[j][1]), hj = std::max(end_pos[j][0], end_pos[j][1]);
        if (li < lj && lj < hi && hi < hj) pairs.push_back({band_gap[i], li, hj, i, j, band_len[i] + band_len[j]});
      }
    }
    if (pairs.empty()) return false;
    // Per gap, a pair is taken if the word of the pairs taken there so far, read from the gap's
    // start, stays in blocks from its first letter (so that inserted at the gap it keeps the whole
    // word in blocks): side by side, or nested where a block may hold another. Blocks inserted at
    // different gaps between blocks keep the word in blocks. O(pairs * taken log taken).
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
      if (a.gap != b.gap) return a.gap < b.gap;
      return a.hi != b.hi ? a.hi < b.hi : a.cost != b.cost ? a.cost < b.cost : a.lo > b.lo;
    });
    std::vector<int> now;  // band ids of the current gap, pairs in order
    std::vector<char> used(nb, 0);
    std::vector<int> departures, chosen;
    auto word_of_now = [&] {
      std::vector<std::pair<int, Letter>> e;
      for (int i : now)
        for (int t = 0; t < 2; ++t) e.push_back({end_pos[i][t], Letter{i, t == 1}});
      std::sort(e.begin(), e.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      std::vector<Letter> ends;
      for (const auto& x : e) ends.push_back(x.second);
      return trace_word(ends, static_cast<int>(ends.size()) - 1, &departures);
    };
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const Pair& p = pairs[k];
      if (k > 0 && p.gap != pairs[k - 1].gap) chosen.insert(chosen.end(), now.begin(), now.end()), now.clear();
      if (used[p.i] || used[p.j]) continue;
      now.push_back(p.i);
      now.push_back(p.j);
      if (blocks_from_start(word_of_now())) used[p.i] = used[p.j] = 1;
      else now.resize(now.size() - 2);
    }
    chosen.insert(chosen.end(), now.begin(), now.end());
    // The taken bands' paths in T, parents first (each vertex of T once: O(n)).
    std::vector<char> seen(nv, 0);
    for (int i : chosen) {
      for (int x : {bands[i].first, bands[i].second}) {
        std::vector<int> chain;
        for (; !K.on_g[x] && !seen[x]; x = par[x]) seen[x] = 1, chain.push_back(x);  // T leads to G
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) out.verts.push_back({*it, par[*it], dist[*it]});
      }
      out.bands.push_back(bands[i]);
    }
    return true;
  };

  // The gap numbers between blocks of the word of the taken ends in tour order `rot` (0: the outer
  // gap; all of the rotation if nothing is taken yet), after checking that the word is one cycle
  // in commutator blocks (Internal otherwise). O(m log m).
  auto gaps_between_blocks = [&](const std::vector<Letter>& rot, int round) {
    const int m = static_cast<int>(rot.size());
    if (m == 0) return std::vector<int>{0};
    std::vector<int> dep, legal;
    const Word w = trace_word(rot, 0, &dep);
    if (w.empty()) internal("normal form: the loops so far bound more than one boundary");
    const int s = commutator_rotation(w);
    if (m != 2 * static_cast<int>(taken.size()) || s < 0)
      internal("normal form: after round " + std::to_string(round) + " the word is not in blocks: " + to_string(w));
    for (int p = 0; p < m / 4; ++p) legal.push_back((dep[(s + 4 * p) % m] + 1) % m);
    return legal;
  };

  int round = 0;
  std::size_t last_k = std::numeric_limits<int>::max();  // the gaps the last round's search used
  for (; static_cast<int>(taken.size()) < 2 * genus; ++round) {
    if (round >= genus) internal("normal form: round " + std::to_string(round) + " with g = " + std::to_string(genus));
    if (rival && rs.mesh.num_vertices() > rival->load()) return false;  // it would lose the race
    const TriMesh& M = rs.mesh;
    extend(rs, pos);
    G.grow(M.num_vertices());
    const int nv = M.num_vertices(), nh = M.num_halfedges();
    // a. the tour of G; its gaps between blocks, with a check that the word is in blocks.
    std::vector<int> band_of, gap_of;
    std::vector<Letter> rot;
    gamma_tour(M, G, taken, root, root_h0(M), band_of, gap_of, rot);
    const int m = static_cast<int>(rot.size());
    std::vector<int> legal = gaps_between_blocks(rot, round);
    // b. the gaps by the size of the largest connected set of vertices off Gamma their free
    // half-edges reach (then by their number of such half-edges). O(n + E).
    {
      UnionFind comp(nv);
      for (int h = 0; h < nh; ++h)
        if (!G.on_g[M.origin(h)] && !G.on_g[M.target(h)]) comp.unite(M.origin(h), M.target(h));
      std::vector<int> size(nv, 0);
      for (int v = 0; v < nv; ++v)
        if (!G.on_g[v]) ++size[comp.find(v)];
      std::vector<int> score(m + 1, 0), spokes(m + 1, 0);  // by gap number (m: the outer gap's end)
      for (int h = 0; h < nh; ++h)
        if (gap_of[h] >= 0 && !G.on_g[M.target(h)]) {
          const int t = gap_of[h] == m ? 0 : gap_of[h];
          score[t] = std::max(score[t], size[comp.find(M.target(h))]);
          ++spokes[t];
        }
      std::stable_sort(legal.begin(), legal.end(), [&](int a, int b) {
        return score[a] != score[b] ? score[a] > score[b] : spokes[a] > spokes[b];
      });
    }
    // c-d from the best k gaps, k = min(twice the last round's, a quarter of the loops still to
    // find), then half, a quarter, ..., 1 (more gaps: shorter paths, but a handle whose loops reach
    // two gaps is not usable; few handles left are seldom inside one gap's part): first on the
    // surface, then on a copy with every chord split. At most 2 (log2 g + 2) searches.
    Found found;
    bool ok = false;
    auto try_prefixes = [&](const TriMesh& S, const GammaTree& K, const std::vector<Vec3d>& P, int first_mid) {
      const std::size_t quarter = std::max<std::size_t>(1, (2 * genus - taken.size()) / 4);
      for (std::size_t k = std::min({legal.size(), 2 * last_k, quarter});; k = (k + 1) / 2) {
        found = Found{};
        if (search(S, K, P, std::vector<int>(legal.begin(), legal.begin() + static_cast<long>(k)), round, first_mid, found)) {
          last_k = k;
          return true;
        }
        if (k == 1) return false;
      }
    };
    ok = try_prefixes(rs.mesh, G, pos, INT32_MAX);
    if (!ok) {
      // Sorted: the copy's split order. is_g reads both half-edges of an edge alike.
      const auto chords = sorted_chords(
          M, [&](int v) { return G.on_g[v] != 0; }, [&](int, int, int h) { return is_g(M, G, band_of, h); });
      if (chords.empty()) internal("normal form: round " + std::to_string(round) + " found no linked pair of loops");
      std::vector<int> mid;
      std::vector<Vec3d> pos_copy;
      const TriMesh copy = split_copy(M, pos, chords, mid, pos_copy);
      GammaTree K = G;
      K.grow(copy.num_vertices());
      ok = try_prefixes(copy, K, pos_copy, nv);
      if (!ok) internal("normal form: round " + std::to_string(round) + " found no linked pair of loops");
      // The chords the found paths and bands cross (midpoints are the copy's vertices >= nv).
      std::vector<std::pair<int, int>> used;
      for (const auto& [v, p, d] : found.verts) used.push_back({v, p});
      for (const auto& b : found.bands) used.push_back(b);
      const std::vector<int> to_surface =
          split_like_copy(rs, chords, mid, copy.num_vertices(), used, res.stats.round_chord_splits);
      auto map = [&](int v) {
        if (v < 0) return v;
        if (to_surface[v] < 0) internal("normal form: a found path uses a chord midpoint that was not split");
        return to_surface[v];
      };
      for (auto& [v, p, d] : found.verts) v = map(v), p = map(p);
      for (auto& [u, v] : found.bands) u = map(u), v = map(v);
      // The paths' edges exist on the surface (their faces are triangulated as in the copy).
      for (const auto& [v, p, d] : found.verts)
        if (rs.mesh.find_halfedge(p, v) < 0) internal("normal form: a found path edge is missing after the splits", {v});
      for (const auto& [u, v] : found.bands)
        if (rs.mesh.find_halfedge(u, v) < 0) internal("normal form: a found band is missing after the splits", {u});
      if (rs.mesh.num_vertices() > vertex_limit) return false;
    }
    // The taken bands and their paths in T join G.
    G.grow(rs.mesh.num_vertices());
    for (const auto& [v, p, d] : found.verts) G.on_g[v] = 1, G.pg[v] = p, G.dg[v] = d;
    for (const auto& b : found.bands) taken.push_back(b);
    if (root_start < 0) root_start = first_child_of_root(rs.mesh, G, root);
    ++res.stats.normal_form_rounds;
  }
  // The last round's word, checked like the others, and step 2 once: all 2g loops detached along G.
  G.grow(rs.mesh.num_vertices());
  return plan_along_tree(res, G, root_start, taken, rival ? std::min(vertex_limit, rival->load()) : vertex_limit, plan);
}

// Step 3 (crosses): g disjoint crosses, each round's hung at once from a tree P from the root. A
// cross is two loops a, b that share one tree path and cross once there (a linked pair of a
// tree–cotree basis of the surface cut along the earlier crosses and P, its stem to the seed
// dropped): the union of their two tree paths, with the two bands. Disjoint crosses are
// independent (each pair meets once, the pairs not at all), and cut along all of them the surface
// is a sphere with g holes, connected; P, a tree from the root over the vertices off the crosses
// meeting each cross at one vertex c, leaves the four ends of every cross next to each other in
// G's tour (G = P + the crosses' trees), where any cyclic rotation of X Y X' Y' reads a
// commutator block. Detached along G (step 2 once), the word is in blocks wherever P meets a
// cross, so nothing constrains where it does.
// One round: seeds spread over the vertices off the crosses and P (farthest first, from those and
// the root); a Dijkstra forest from them over those vertices; the dual maximum spanning tree with
// every edge at a cross, at P, or between two seeds' parts forced in first; the leftover edges'
// ends in each seed's tour; linked pairs by length, taken while their paths are disjoint from the
// pairs taken before; then the round's crosses are hung from P (hang_round), whose new paths are
// walls for the rounds after. Chords (edges off the crosses and P joining two of their vertices)
// can wall the forest off; a round that finds nothing from k seeds is searched from k/2, ..., 1,
// then on a copy with every chord split (a midpoint costs 1000 unit lengths), after which only
// the chords the found crosses use are split on the surface; P reaches a walled-off cross the same
// way. A round starts from k = min(twice the seeds the last round used, a quarter of the crosses
// still to find) seeds, at least 1. At most g rounds (each takes a cross), at most log2 k + 1
// searches on the surface and as many on a copy per round, and one or two hanging searches.
// Returns false as soon as the mesh has more than vertex_limit vertices, or at the start of a
// round once it has at least *rival (if given: the planned vertices of the rounds raced against
// it, which win ties; the count at a round's start only grows, and the plan has at least as many,
// so such a run would lose). Post (true): as canonical_rounds. Cost O(g log g (E log E +
// L^2 log L) + crossings), L <= 2g + k the leftover edges of a search.
bool canonical_crosses(CutResult& res, const std::vector<Vec3d>& unit, bool hops, long vertex_limit, DetachPlan& plan,
                       const std::atomic<long>* rival) {
  const int root = res.root, genus = res.genus;
  RefinedSurface& rs = res.surface;
  std::vector<Vec3d> pos(unit.begin(), unit.begin() + rs.num_input_vertices);
  auto extend = [&](const RefinedSurface& S, std::vector<Vec3d>& p) { extend_positions(S, unit, p); };
  constexpr double kMidpointCost = 1000.0;  // unit-scaled lengths: crossing a chord is a last resort
  struct Cross {
    std::vector<std::pair<int, int>> edges;  // tree edges (x, parent of x in the seed's forest)
    std::array<std::pair<int, int>, 2> bands;
  };
  std::vector<Cross> crosses;
  std::vector<int> cross_of(rs.mesh.num_vertices(), -1);
  // The crosses' edges, P's and those hanging the crosses from P, as each end's list of the other
  // ends (a wall vertex has few): never split as chords.
  std::vector<std::vector<int>> cross_nb;
  auto add_cross_edge = [&](int a, int b) {
    const std::size_t need = static_cast<std::size_t>(std::max(a, b)) + 1;
    if (cross_nb.size() < need) cross_nb.resize(need);
    cross_nb[a].push_back(b);
    cross_nb[b].push_back(a);
  };
  auto is_cross_edge = [&](int a, int b) {
    if (static_cast<std::size_t>(std::max(a, b)) >= cross_nb.size()) return false;
    if (cross_nb[a].size() > cross_nb[b].size()) std::swap(a, b);  // scan the shorter list
    return std::find(cross_nb[a].begin(), cross_nb[a].end(), b) != cross_nb[a].end();
  };
  auto lenf = [&](const std::vector<Vec3d>& P, int first_mid) {
    return [&P, first_mid, hops](int a, int b) {
      return (hops ? 1.0 : length(P[a], P[b])) + (a >= first_mid ? kMidpointCost : 0.0) +
             (b >= first_mid ? kMidpointCost : 0.0);
    };
  };
  // The search's per-vertex, per-face and per-half-edge state, kept across searches and reset
  // where the last search touched it (its reached vertices, faces and band half-edges), so that a
  // search whose seeds reach few vertices costs about what it reaches: the surface's searches in
  // the late rounds reach a few hundred of its 30k-65k vertices before the copy is needed.
  struct SearchState {
    std::vector<double> dist;
    std::vector<int> par, label, depth, face_node, cand_of;
    std::vector<char> above, mark;
    std::vector<int> reached, faces, halfedges;  // what the last search set
    void prepare(int nv, int nf, int nh) {
      for (int v : reached) dist[v] = INFINITY, par[v] = -1, label[v] = -1, depth[v] = 0, above[v] = 0, mark[v] = 0;
      for (int f : faces) face_node[f] = -1;
      for (int h : halfedges) cand_of[h] = -1;
      reached.clear(), faces.clear(), halfedges.clear();
      if (static_cast<int>(dist.size()) < nv) {
        dist.resize(nv, INFINITY), par.resize(nv, -1), label.resize(nv, -1), depth.resize(nv, 0);
        above.resize(nv, 0), mark.resize(nv, 0);
      }
      if (static_cast<int>(face_node.size()) < nf) face_node.resize(nf, -1);
      if (static_cast<int>(cand_of.size()) < nh) cand_of.resize(nh, -1);
    }
  } st;
  // One round's search on M (the surface or a copy; cof = cross_of sized for M) from `seeds`.
  // Appends the crosses found (vertex ids of M). O(R log R + L^2 log L + the paths) for R vertices
  // reached (with their edges) and L leftovers.
  auto search = [&](const TriMesh& M, const std::vector<int>& cof, const std::vector<Vec3d>& P,
                    const std::vector<int>& seeds, int first_mid, int round, std::vector<Cross>& out) {
    const int nv = M.num_vertices(), nh = M.num_halfedges();
    const auto len = lenf(P, first_mid);
    auto blocked = [&](int v) { return v == root || cof[v] != -1; };
    st.prepare(nv, M.num_faces(), nh);
    std::vector<double>& dist = st.dist;
    std::vector<int> &par = st.par, &label = st.label, &depth = st.depth, &reached = st.reached;
    {
      MinQueue pq;
      for (std::size_t k = 0; k < seeds.size(); ++k) {
        dist[seeds[k]] = 0, label[seeds[k]] = static_cast<int>(k), pq.push({0.0, seeds[k]});
        reached.push_back(seeds[k]);
      }
      settle_all(M, dist, pq, [&](int v, int w, double d) {
        if (!blocked(w) && d + len(v, w) < dist[w]) {
          if (dist[w] == INFINITY) reached.push_back(w);
          dist[w] = d + len(v, w), par[w] = v, label[w] = label[v], depth[w] = depth[v] + 1, pq.push({dist[w], w});
        }
      });
    }
    std::vector<std::pair<int, int>> bands;
    std::vector<double> band_len;
    {
      // The forced edges (at a vertex not reached, between two seeds' parts) go into the dual tree
      // first, then the others heaviest first (ties by half-edge); a leftover of the latter is a
      // band. The faces at the vertices not reached are one part of the dual forest once the
      // forced edges are in: the fan around such a vertex is joined by its edges, two such vertices
      // on an edge share its faces, and they are connected on the mesh (the root, the crosses and
      // P form one tree of edges, and every part of the free vertices the seeds do not reach
      // borders it). So that part is one node (0), every face of three reached vertices another,
      // and only the edges between reached vertices are read: the same leftovers as Kruskal over
      // all faces and edges, at the cost of what the seeds reach (the late rounds' searches on the
      // surface reach a few hundred of its 30k-65k vertices). The dual forest must end connected
      // (over all faces: E - (reached - seeds) - (F - 1) leftovers, E = V + F - 2 + 2g).
      std::vector<std::pair<double, int>> weighted;
      std::vector<int>& face_node = st.face_node;
      int nodes = 1;
      auto node = [&](int h) {
        const int f = TriMesh::face(h);
        if (face_node[f] < 0) {
          const bool inner = dist[M.origin(h)] < INFINITY && dist[M.origin(TriMesh::next(h))] < INFINITY &&
                             dist[M.origin(TriMesh::prev(h))] < INFINITY;
          face_node[f] = inner ? nodes++ : 0;
          st.faces.push_back(f);
        }
        return face_node[f];
      };
      std::vector<std::array<int, 2>> forced;
      for (int a : reached) {
        const int h0 = M.vertex_halfedge(a);
        int h = h0;
        do {  // valence(a) steps
          const int b = M.target(h), t = M.twin(h);
          if (h < t && dist[b] < INFINITY && par[b] != a && par[a] != b) {
            const int x = node(h), y = node(t);  // every node exists before the forest is sized
            if (label[a] != label[b]) forced.push_back({x, y});
            else weighted.push_back({dist[a] + dist[b] + len(a, b), h});
          }
          h = M.next_around_origin(h);
        } while (h != h0);
      }
      UnionFind dsu(static_cast<std::size_t>(nodes));
      long joined = 0;
      for (const auto& [x, y] : forced) joined += dsu.unite(x, y);
      sort_by_weight_descending(weighted);
      for (const auto& [w, h] : weighted) {
        if (dsu.unite(node(h), node(M.twin(h)))) ++joined;
        else bands.push_back({M.origin(h), M.target(h)}), band_len.push_back(w);
      }
      if (joined != nodes - 1)
        internal("normal form: cross round " + std::to_string(round) + " left the dual forest in " +
                 std::to_string(nodes - joined) + " parts");
    }
    const int nb = static_cast<int>(bands.size());
    if (nb < 2) return false;
    // The leftover ends in the tours of the seeds' trees (descending only above an end: O(n)).
    std::vector<std::array<long, 2>> end_pos(nb, {-1, -1});
    {
      std::vector<int>& cand_of = st.cand_of;
      std::vector<char>& above = st.above;
      for (int i = 0; i < nb; ++i) {
        const int h = find_he(M, bands[i].first, bands[i].second);
        cand_of[h] = cand_of[M.twin(h)] = i;
        st.halfedges.push_back(h), st.halfedges.push_back(M.twin(h));
        for (int x : {bands[i].first, bands[i].second})
          for (; x >= 0 && !above[x]; x = par[x]) above[x] = 1;
      }
      long counter = 0;
      for (int s : seeds) {
        if (!above[s]) continue;
        tour_tree(
            M, M.vertex_halfedge(s),
            [&](int h) {
              const int b = M.target(h);
              return cand_of[h] < 0 && !blocked(b) && par[b] == M.origin(h) && above[b];
            },
            [&](int h) {
              const int i = cand_of[h];
              if (i >= 0) end_pos[i][M.origin(h) == bands[i].first ? 0 : 1] = counter++;
            });
      }
    }
    // Each leftover's loop without its stem: the tree path between its ends, and its length.
    std::vector<std::vector<int>> path(nb);
    std::vector<double> cost(nb);
    for (int i = 0; i < nb; ++i) {
      int x = bands[i].first, y = bands[i].second;
      std::vector<int> up, down;
      while (x != y) {  // climbs at most depth(x) + depth(y) steps
        if (depth[x] >= depth[y]) up.push_back(x), x = par[x];
        else down.push_back(y), y = par[y];
      }
      up.push_back(x);
      cost[i] = dist[bands[i].first] + dist[bands[i].second] - 2 * dist[x] + len(bands[i].first, bands[i].second);
      path[i] = std::move(up);
      path[i].insert(path[i].end(), down.rbegin(), down.rend());
    }
    struct Pair { double cost; int i, j; };
    std::vector<Pair> pairs;
    for (int i = 0; i < nb; ++i) {
      const long li = std::min(end_pos[i][0], end_pos[i][1]), hi = std::max(end_pos[i][0], end_pos[i][1]);
      if (li < 0) continue;
      for (int j = 0; j < nb; ++j) {
        if (j == i || label[bands[j].first] != label[bands[i].first]) continue;
        const long lj = std::min(end_pos[j][0], end_pos[j][1]), hj = std::max(end_pos[j][0], end_pos[j][1]);
        if (lj >= 0 && li < lj && lj < hi && hi < hj) pairs.push_back({cost[i] + cost[j], i, j});
      }
    }
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
      return a.cost != b.cost ? a.cost < b.cost : a.i != b.i ? a.i < b.i : a.j < b.j;
    });
    std::vector<char>& mark = st.mark;
    std::vector<char> blocked_band(nb, 0);  // a band whose path meets a taken cross
    std::vector<std::size_t> free_at(nb, SIZE_MAX);       // out.size() when its path was last found free
    const std::size_t before = out.size();
    // A band's path is scanned again only after a cross was taken, and never once blocked:
    // O(pairs + nb * path length * crosses taken) after the sort.
    auto path_free = [&](int k) {
      if (blocked_band[k]) return false;
      if (free_at[k] == out.size()) return true;
      for (int x : path[k])
        if (mark[x]) return !(blocked_band[k] = 1);
      free_at[k] = out.size();
      return true;
    };
    for (const Pair& p : pairs) {
      if (static_cast<int>(crosses.size() + out.size()) >= genus) break;
      if (!path_free(p.i) || !path_free(p.j)) continue;
      Cross c;
      int top = path[p.i][0];
      std::vector<int> verts;
      for (int k : {p.i, p.j})
        for (int x : path[k])
          if (!mark[x]) mark[x] = 2, verts.push_back(x);
      for (int x : verts)
        if (depth[x] < depth[top]) top = x;
      for (int x : verts) {  // the union is one subtree below top (linked paths meet)
        if (x == top) continue;
        if (par[x] < 0 || mark[par[x]] != 2) internal("normal form: a linked pair whose paths do not meet", {x});
        c.edges.push_back({x, par[x]});
      }
      for (int x : verts) mark[x] = 1;
      c.bands = {bands[p.i], bands[p.j]};
      out.push_back(std::move(c));
    }
    return out.size() > before;
  };

  // The chords of M: edges joining two vertices of `is_wall` that are no cross's edge, sorted.
  auto chords_of = [&](const TriMesh& M, auto&& is_wall) {
    return sorted_chords(M, is_wall, [&](int a, int b, int) { return is_cross_edge(a, b); });
  };
  auto map_ids = [&](const std::vector<int>& to_surface, int& v) {
    if (to_surface[v] < 0) internal("normal form: a found path uses a chord midpoint that was not split");
    v = to_surface[v];
  };

  // Seeds on M (the surface or a copy, cof = cross_of sized for it): up to k vertices off the
  // crosses and the root, each the farthest (ties: lowest id) from those and the seeds before it.
  // At most k + 1 Dijkstra passes, each stopping where it gains nothing; O(k (n + E log E)).
  auto pick_seeds = [&](const TriMesh& M, const std::vector<int>& cof, const std::vector<Vec3d>& P, int first_mid,
                        std::size_t k) {
    const int nv = M.num_vertices();
    const auto len = lenf(P, first_mid);
    std::vector<double> d(nv, INFINITY);
    std::vector<char> source(nv, 0);
    MinQueue pq;
    auto free_v = [&](int v) { return v != root && cof[v] == -1; };
    // The first pass: every vertex off the free ones is a source at 0; only those beside a vertex
    // that `through` admits can relax anything, so only they are queued, once each, found from
    // the admitted side (late rounds: most of the surface is crosses and P, the free part small).
    auto first_pass = [&](auto&& through) {
      std::fill(d.begin(), d.end(), INFINITY);
      std::fill(source.begin(), source.end(), 0);
      for (int v = 0; v < nv; ++v)
        if (!free_v(v)) d[v] = 0, source[v] = 1;
      for (int w = 0; w < nv; ++w) {
        if (!through(w)) continue;
        const int h0 = M.vertex_halfedge(w);
        int h = h0;
        do {
          const int v = M.target(h);
          if (source[v] == 1) source[v] = 2, pq.push({0.0, v});  // 2: a source queued
          h = M.next_around_origin(h);
        } while (h != h0);
      }
      settle_all(M, d, pq, [&](int v, int w, double dv) {
        if (through(w) && dv + len(v, w) < d[w]) d[w] = dv + len(v, w), pq.push({d[w], w});
      });
    };
    // On a copy the pass first goes over the free surface vertices only, and each midpoint then
    // takes the least of d(x) + len(x, m) over its surface neighbours x. These are the distances
    // of a pass over all free vertices whenever the surface vertices end at most 2 kMidpointCost
    // away and the midpoints at most 3: a path that passes a midpoint pays kMidpointCost to enter
    // it and again to leave it, one that reaches a midpoint from another midpoint at least 3
    // times (additions round monotonically, so the bounds hold in doubles). Else the full pass.
    // The late rounds' copies are mostly midpoints, every one of which the full pass would queue:
    // O(n) instead of O(n log n) there.
    bool exact = false;
    if (first_mid < nv) {
      first_pass([&](int w) { return w < first_mid && free_v(w); });
      exact = true;
      for (int v = 0; v < first_mid && exact; ++v) exact = d[v] <= 2 * kMidpointCost;
      for (int m = first_mid; m < nv && exact; ++m) {
        const int h0 = M.vertex_halfedge(m);
        int h = h0;
        do {
          const int x = M.target(h);
          if (x < first_mid && d[x] + len(x, m) < d[m]) d[m] = d[x] + len(x, m);
          h = M.next_around_origin(h);
        } while (h != h0);
        exact = d[m] <= 3 * kMidpointCost;
      }
    }
    if (!exact) first_pass(free_v);
    auto run = [&] {
      settle_all(M, d, pq, [&](int v, int w, double dv) {
        if (free_v(w) && dv + len(v, w) < d[w]) d[w] = dv + len(v, w), pq.push({d[w], w});
      });
    };
    std::vector<int> seeds;
    while (seeds.size() < k) {
      int best = -1;
      for (int v = 0; v < nv; ++v)
        if (!source[v] && (best < 0 || d[v] > d[best])) best = v;
      if (best < 0) break;
      seeds.push_back(best);
      d[best] = 0, source[best] = 1;
      pq.push({0.0, best});
      run();
    }
    return seeds;
  };

  // P: a tree from the root, grown after every round to that round's new crosses, and a wall for
  // the rounds after it (its vertices are marked -2 in cross_of, like the root; its edges and the
  // edges to the crosses are in cross_nb, so never split as chords). hang_round hangs crosses
  // [first, end): a Dijkstra from P's vertices at their depths (pdepth, along P) over the free
  // vertices; each new cross hangs from the first of its vertices it reaches (hang[i], reached
  // from hang_from[i]), and the path to it joins P. A cross walled off by chords is reached on a
  // copy with every chord split, then only the chords its path crosses are split on the surface
  // (as in a round). Any P vertex can take a cross: P holds no band end, so every wedge at it lies
  // between blocks of G's tour. Hanging at once keeps P's paths short (cheese: their lengths sum
  // to ~6k vertices, against ~100k when P is built after the last round, through the maze the
  // crosses leave); the later rounds pay for the walls with chord splits. O(E log E + chords) per
  // round.
  cross_of[root] = -2;  // off the crosses and the seeds
  std::vector<int> ppar(rs.mesh.num_vertices(), -1), hang, hang_from;
  std::vector<double> pdepth(rs.mesh.num_vertices(), INFINITY);
  pdepth[root] = 0;
  auto hang_round = [&](std::size_t first) {
    extend(rs, pos);
    ppar.resize(rs.mesh.num_vertices(), -1);
    pdepth.resize(rs.mesh.num_vertices(), INFINITY);
    hang.resize(crosses.size(), -1);
    hang_from.resize(crosses.size(), -1);
    std::vector<double> dist;
    std::vector<int> par;
    auto run = [&](const TriMesh& M, const std::vector<int>& cof, const std::vector<Vec3d>& P, int first_mid) {
      const int nv = M.num_vertices();
      const auto len = lenf(P, first_mid);
      dist.assign(nv, INFINITY);
      par.assign(nv, -1);
      MinQueue pq;
      for (int v = 0; v < static_cast<int>(pdepth.size()); ++v)
        if (cof[v] == -2) dist[v] = pdepth[v], pq.push({dist[v], v});
      // Stops once every new cross hangs: their hang points and the paths up from them are final.
      std::size_t hung = 0;
      const std::size_t want = crosses.size() - first;
      settle_until(
          M, dist, pq,
          [&](int v, int w, double d) {
            const int c = cof[w];
            if (c >= static_cast<int>(first)) {
              if (hang[c] < 0) hang[c] = w, hang_from[c] = v, ++hung;
            } else if (c == -1 && d + len(v, w) < dist[w]) {
              dist[w] = d + len(v, w), par[w] = v, pq.push({dist[w], w});
            }
          },
          [&] { return hung == want; });
      return hung;
    };
    // The path from x (reached) up to P, as (vertex, parent) pairs.
    auto path_up = [&](int x, const std::vector<int>& cof) {
      std::vector<std::pair<int, int>> path;
      for (; cof[x] != -2; x = par[x]) path.push_back({x, par[x]});  // <= nv steps: par is a tree
      return path;
    };
    auto join_p = [&](std::size_t i, const std::vector<std::pair<int, int>>& path) {
      const auto len = lenf(pos, INT32_MAX);
      for (auto it = path.rbegin(); it != path.rend(); ++it) {  // from P down: the parent's depth first
        const auto [x, y] = *it;
        if (rs.mesh.find_halfedge(x, y) < 0) internal("normal form: a path edge to a cross is missing", {x});
        cross_of[x] = -2, ppar[x] = y, pdepth[x] = pdepth[y] + len(x, y);
        add_cross_edge(x, y);
      }
      if (rs.mesh.find_halfedge(hang_from[i], hang[i]) < 0) internal("normal form: an edge to a cross is missing", {hang[i]});
      add_cross_edge(hang_from[i], hang[i]);
    };
    const std::size_t want = crosses.size() - first;
    if (run(rs.mesh, cross_of, pos, INT32_MAX) == want) {
      for (std::size_t i = first; i < crosses.size(); ++i) join_p(i, path_up(hang_from[i], cross_of));
      return rs.mesh.num_vertices() <= vertex_limit;
    }
    // Some are walled off: all of this round's on a copy (so that their paths form one tree).
    const int nv = rs.mesh.num_vertices();
    const auto chords = chords_of(rs.mesh, [&](int v) { return cross_of[v] != -1; });
    std::vector<int> mid;
    std::vector<Vec3d> pos_copy;
    const TriMesh copy = split_copy(rs.mesh, pos, chords, mid, pos_copy);
    std::vector<int> cof = cross_of;
    cof.resize(copy.num_vertices(), -1);
    std::fill(hang.begin() + static_cast<long>(first), hang.end(), -1);
    if (run(copy, cof, pos_copy, nv) != want) internal("normal form: a cross is not reachable from the tree P");
    std::vector<std::vector<std::pair<int, int>>> paths;
    std::vector<std::pair<int, int>> used;
    for (std::size_t i = first; i < crosses.size(); ++i) {
      paths.push_back(path_up(hang_from[i], cof));
      used.insert(used.end(), paths.back().begin(), paths.back().end());
      used.push_back({hang_from[i], hang[i]});
    }
    const std::vector<int> to_surface =
        split_like_copy(rs, chords, mid, copy.num_vertices(), used, res.stats.round_chord_splits);
    extend(rs, pos);
    cross_of.resize(rs.mesh.num_vertices(), -1);
    ppar.resize(rs.mesh.num_vertices(), -1);
    pdepth.resize(rs.mesh.num_vertices(), INFINITY);
    for (std::size_t i = first; i < crosses.size(); ++i) {
      auto& path = paths[i - first];
      for (auto& [x, y] : path) map_ids(to_surface, x), map_ids(to_surface, y);
      map_ids(to_surface, hang_from[i]);
      join_p(i, path);
    }
    return rs.mesh.num_vertices() <= vertex_limit;
  };

  int round = 0;
  std::size_t last_k = std::numeric_limits<int>::max();
  while (static_cast<int>(crosses.size()) < genus) {
    if (round >= genus) internal("normal form: cross round " + std::to_string(round) + " with g = " + std::to_string(genus));
    if (rival && rs.mesh.num_vertices() >= rival->load()) return false;  // it would lose the race
    extend(rs, pos);
    const int nv = rs.mesh.num_vertices();
    cross_of.resize(nv, -1);
    const std::size_t remaining = genus - crosses.size();
    const std::size_t want_seeds = std::min(2 * last_k, std::max<std::size_t>(1, remaining / 4));
    std::vector<Cross> found;
    auto try_prefixes = [&](const TriMesh& M, const std::vector<int>& cof, const std::vector<Vec3d>& P, int first_mid) {
      const std::vector<int> seeds = pick_seeds(M, cof, P, first_mid, want_seeds);
      if (seeds.empty()) return false;  // every vertex is on a cross or the root
      for (std::size_t k = seeds.size();; k = (k + 1) / 2) {
        found.clear();
        if (search(M, cof, P, std::vector<int>(seeds.begin(), seeds.begin() + static_cast<long>(k)), first_mid, round, found)) {
          last_k = k;
          return true;
        }
        if (k == 1) return false;
      }
    };
    if (!try_prefixes(rs.mesh, cross_of, pos, INT32_MAX)) {
      const auto chords = chords_of(rs.mesh, [&](int v) { return v == root || cross_of[v] != -1; });
      if (chords.empty()) internal("normal form: cross round " + std::to_string(round) + " found no linked pair");
      std::vector<int> mid;
      std::vector<Vec3d> pos_copy;
      const TriMesh copy = split_copy(rs.mesh, pos, chords, mid, pos_copy);
      std::vector<int> cof = cross_of;
      cof.resize(copy.num_vertices(), -1);
      if (!try_prefixes(copy, cof, pos_copy, nv))
        internal("normal form: cross round " + std::to_string(round) + " found no linked pair");
      std::vector<std::pair<int, int>> used;
      for (const Cross& c : found) {
        used.insert(used.end(), c.edges.begin(), c.edges.end());
        used.insert(used.end(), c.bands.begin(), c.bands.end());
      }
      const std::vector<int> to_surface =
          split_like_copy(rs, chords, mid, copy.num_vertices(), used, res.stats.round_chord_splits);
      for (Cross& c : found) {
        for (auto& [x, y] : c.edges) map_ids(to_surface, x), map_ids(to_surface, y);
        for (auto& [x, y] : c.bands) map_ids(to_surface, x), map_ids(to_surface, y);
      }
      // The split diagonals inside input faces that the crosses' tree paths merely pass go again
      // (straighten_paths): measured on cheese, 371k -> 148k vertices in all.
      {
        std::vector<std::pair<int, int>> tree_edges;
        std::vector<int> band_ends;
        for (const Cross& c : found) {
          tree_edges.insert(tree_edges.end(), c.edges.begin(), c.edges.end());
          for (const auto& [x, y] : c.bands) band_ends.push_back(x), band_ends.push_back(y);
        }
        StraightenedPaths st = straighten_paths(std::move(rs), tree_edges, band_ends, nv);
        rs = std::move(st.surface);
        res.stats.straightened += st.removed;
        for (Cross& c : found) {
          std::vector<std::pair<int, int>> edges;
          for (const auto& [x, y] : c.edges)
            if (st.to[x] != st.to[y]) edges.push_back({st.to[x], st.to[y]});
          c.edges = std::move(edges);
          for (auto& [x, y] : c.bands) x = st.to[x], y = st.to[y];
        }
      }
      if (rs.mesh.num_vertices() > vertex_limit) return false;
    }
    cross_of.resize(rs.mesh.num_vertices(), -1);
    for (Cross& c : found) {
      const int id = static_cast<int>(crosses.size());
      for (const auto& e : c.edges) {
        if (rs.mesh.find_halfedge(e.first, e.second) < 0) internal("normal form: a cross edge is missing after the splits", {e.first});
        cross_of[e.first] = cross_of[e.second] = id;
        add_cross_edge(e.first, e.second);
      }
      for (const auto& e : c.bands) {
        if (rs.mesh.find_halfedge(e.first, e.second) < 0) internal("normal form: a band is missing after the splits", {e.first});
        add_cross_edge(e.first, e.second);
      }
      crosses.push_back(std::move(c));
    }
    if (!hang_round(crosses.size() - found.size())) return false;
    ++round;
    ++res.stats.normal_form_rounds;
  }

  // G: P, and every cross's tree hung from its vertex hang[i] (depth-first over its edges).
  GammaTree G;
  G.grow(rs.mesh.num_vertices());
  G.on_g[root] = 1;
  for (int v = 0; v < static_cast<int>(ppar.size()); ++v)
    if (ppar[v] >= 0) G.on_g[v] = 1, G.pg[v] = ppar[v];
  std::vector<std::pair<int, int>> taken;
  for (std::size_t i = 0; i < crosses.size(); ++i) {
    std::unordered_map<int, std::vector<int>> adj;
    for (auto [x, y] : crosses[i].edges) adj[x].push_back(y), adj[y].push_back(x);
    const int c = hang[i];
    G.on_g[c] = 1, G.pg[c] = hang_from[i];
    std::vector<int> stack{c};
    while (!stack.empty()) {  // each vertex of the cross once
      const int x = stack.back();
      stack.pop_back();
      for (int y : adj[x])
        if (!G.on_g[y]) G.on_g[y] = 1, G.pg[y] = x, stack.push_back(y);
    }
    taken.push_back(crosses[i].bands[0]);
    taken.push_back(crosses[i].bands[1]);
  }
  return plan_along_tree(res, G, first_child_of_root(rs.mesh, G, root), taken,
                         rival ? std::min(vertex_limit, rival->load() - 1) : vertex_limit, plan);
}

// How many root candidates the normal form tries (root = -1, CutOptions::normal_form_roots = -1):
// clamp(min(2e5 / F, 4e6 / (F g)), 1, 12). A candidate's construction costs about its output,
// which grows with g as well as F (the crosses on cheese, g133 on 17.8k faces: 1.7-3.5 s each, 31 s
// for the 11 roots that 2e5 / F alone gives, 148.4k vertices; one root: 160.8k, 2-3.5 s, since
// stop 24 1.6-1.9 s). Up to g = 20 it is 2e5 / F as before.
long normal_form_root_count(const TriMesh& mesh, int genus) {
  const long long f = std::max(1, mesh.num_faces());
  return std::clamp<long>(static_cast<long>(std::min(200000LL / f, 4000000LL / (f * std::max(genus, 1)))), 1L, 12L);
}

// Root candidates: the vertex of maximum valence (lowest id among ties), then vertices i * V / k
// for i = 1..k-1 (without repeats). O(V).
std::vector<int> root_candidates(const TriMesh& mesh, long k) {
  const int nv = mesh.num_vertices();
  int first = 0, best_valence = -1;
  for (int v = 0; v < nv; ++v)
    if (mesh.valence(v) > best_valence) best_valence = mesh.valence(v), first = v;
  std::vector<int> roots{first};
  for (long i = 1; i < k; ++i) {
    const int v = static_cast<int>(i * nv / k);
    if (std::find(roots.begin(), roots.end(), v) == roots.end()) roots.push_back(v);
  }
  return roots;
}

// Root candidates for the basis without the normal form: the vertex of maximum valence, then of a
// spread sample (root_candidates, min(V, 50 k) of them) the k - 1 others with the least ring
// deficit, the sample's order breaking ties. The
// deficit of r: the sum of max(0, 4g - |ring_j|) over the hop rings ring_1, ring_2, ... around r
// before the first with at least 4g vertices, each such level a place where the 4g strands leaving
// r must share vertices (ring_bound.h's floor without its disk test, which the ring search would
// cost too much for). Each ring search stops after 20,000 vertices: O(50 k min(V, 20000) + V).
// Measured: on the shared meshes of genus <= 9 and generated genus 2-12 (16 meshes) the cut adds
// 1,204 vertices in all instead of 1,595 with the spread candidates (couplingdown 134 -> 106); with
// the normal form it does not help (couplingdown 300 -> 393), so the normal form keeps the spread.
std::vector<int> root_candidates_by_ring_deficit(const TriMesh& mesh, long k, int genus) {
  const int nv = mesh.num_vertices();
  const std::vector<int> sample = root_candidates(mesh, std::min<long>(nv, 50 * k));
  HopRings rings(mesh);
  std::vector<std::pair<long, int>> score;  // (deficit, position in the sample)
  for (int i = 0; i < static_cast<int>(sample.size()); ++i) {
    long deficit = 0, visited = 1;
    rings.start(sample[i]);
    while (visited < 20000 && rings.next()) {  // each ring is new: at most 20,000 vertices in all
      const long size = static_cast<long>(rings.ring().size());
      visited += size;
      if (size >= 4L * genus) break;
      deficit += 4L * genus - size;
    }
    score.push_back({deficit, i});
  }
  // The vertex of maximum valence (the sample's first) stays a candidate, the others by deficit.
  std::stable_sort(score.begin() + 1, score.end());
  std::vector<int> roots;
  for (long i = 0; i < k && i < static_cast<long>(score.size()); ++i) roots.push_back(sample[score[i].second]);
  return roots;
}

}  // namespace

std::string CutResult::word() const { return to_string(word_of(*this)); }

namespace {

// Steps 1-5 on the mesh as numbered (cut_to_canonical_disk below may renumber it first). Pre: the
// input and the options checked there, `genus` >= 1 the mesh's.
CutResult cut_in_given_order(const TriMesh& mesh, const std::vector<Vec3d>& positions, const CutOptions& options,
                             int genus) {
  const auto t_start = Clock::now();
  const int nv0 = mesh.num_vertices();
  CutResult res;
  const std::vector<Vec3d> unit = unit_scaled(positions);  // edge lengths finite at any magnitude
  res.genus = genus;
  res.stats.genus = genus;
  res.stats.vertices_before = nv0;
  res.stats.faces_before = mesh.num_faces();
  RefinedSurface& rs = res.surface;
  bool tightened = false;  // the loops were drawn and tightened while the root was chosen
  if (options.normal_form) {
    // Root and metric: the given root with 3D lengths, or among K deterministic candidates
    // (root_candidates, K = normal_form_root_count) with 3D lengths and hop counts (one root: hop
    // counts only), the pair whose planned detaching ends with the fewest vertices
    // (planned_vertices; only that one is drawn); a candidate stops once it has more than the best
    // so far. Per candidate (Best): the rounds, bounded by max_rounds_growth; if they pass it, the
    // crosses (a lone candidate: both at once, see run_candidate). After two candidates whose
    // rounds passed it, only the crosses.
    const long limit = nv0 + static_cast<long>(options.max_normal_form_growth * nv0);
    const long rounds_limit = std::min(limit, nv0 + static_cast<long>(options.max_rounds_growth * nv0));
    std::vector<std::pair<int, bool>> candidates;
    if (options.root >= 0) {
      candidates.push_back({options.root, false});
    } else {
      const long k = options.normal_form_roots > 0 ? std::min<long>(options.normal_form_roots, nv0)
                                                    : normal_form_root_count(mesh, genus);
      // One root: hop counts, which count the vertices the normal form pays for (cheese's root 2:
      // 161.9k planned vertices, against 257k with 3D lengths; the 1M-face g20: 536.6k, 538.6k).
      for (int c : root_candidates(mesh, k))
        for (bool hops : {false, true})
          if (hops || k > 1) candidates.push_back({c, hops});
    }
    using C = CutOptions::Construction;
    // Each candidate is only planned (its detaching counted, not drawn); the kept one is realized
    // once at the end. Candidates go in chunks of two, in order: the two of a chunk are bounded by
    // the best of the chunks before it and run concurrently (options.parallel), then are merged in
    // order (a candidate is kept if it plans strictly fewer vertices), so that the result does not
    // depend on the threads.
    struct Outcome {
      bool ok = false, rounds_passed = false, crosses = false, hops = false;
      bool reweighted = false;  // a rounds plan already reweighted (in a race)
      CutStats stats;
      DetachPlan plan;
    };
    // A construction's starting point: the input surface, unrefined, at `root`.
    auto new_trial = [&](int root) {
      CutResult trial;
      trial.root = root;
      trial.genus = genus;
      trial.surface.mesh = mesh;
      trial.surface.num_input_vertices = nv0;
      trial.surface.input_positions = positions;
      return trial;
    };
    // One construction at candidate (c, hops), into out if it succeeds within `bound` (and within
    // *rival: canonical_rounds, canonical_crosses).
    auto attempt = [&](int c, bool hops, bool crosses, long bound, Outcome& out,
                       const std::atomic<long>* rival = nullptr) {
      CutResult trial = new_trial(c);
      DetachPlan plan;
      const bool ok = crosses ? canonical_crosses(trial, unit, hops, bound, plan, rival)
                              : canonical_rounds(trial, unit, hops, bound, plan, nullptr, rival);
      if (ok) out.ok = true, out.crosses = crosses, out.hops = hops, out.stats = trial.stats, out.plan = std::move(plan);
      return ok;
    };
    // One candidate: the rounds, bounded by max_rounds_growth; where they pass it (their own bound
    // binding, not only the best so far; Best) the crosses, whose outcome (or error) then counts.
    // race (a lone candidate where the rounds tend to pass their bound: kRaceFacesPerHandle): both
    // run, side by side on two threads (CutOptions::parallel), the rounds followed by their
    // congestion reweighting (reweight), and the fewer planned vertices win, the rounds on ties
    // (their plan after the reweighting, which can only lower it: couplingdown at root 100 gets
    // 2,266 vertices from the reweighted rounds, 2,587 from the crosses, whose plan is below the
    // rounds' first). Each run is bounded by the other's best plan so far: the crosses by the
    // rounds' (from their first plan on), the rounds by the crosses' where no reweighting follows.
    // The rounds' count only grows, the crosses' grows from round to round, and a plan has at least
    // the vertices of its surface, so a run that passes the other's plan would lose anyway: the
    // outcome does not depend on the threads (an error of the rounds wins; one of the crosses
    // counts where the rounds failed; an Internal error that only a losing run would reach may go
    // unseen), and the time is about that of the longer of the two, or less where the winner stops
    // the other.
    const int reweight_rounds = congestion_budget(options, mesh, 200000L, 0L);
    if (reweight_rounds > 0) check_congestion_step(options.congestion_step);
    // The congestion reweighting of a rounds plan at (root, hops) (step 3a with the penalties of
    // step 1c, accumulated from each round's plan), all rounds of the budget (their outcomes are
    // erratic); the plan with the fewest planned vertices is kept, with its stats. Not for the
    // crosses (a candidate costs seconds where they are needed). Each round is bounded by the
    // rounds' own limit only: a round past the kept plan still gives the next penalties. Each new
    // best's count goes to *publish (if given). None past 2e5 faces: there a round costs as much
    // as the construction (the 1M-face g20: 7.5 s).
    auto reweight = [&](int root, bool hops, DetachPlan& plan, CutStats& stats, std::atomic<long>* publish) {
      CutStats latest;  // the stats of the last round's construction
      long latest_count = 0;
      const int kept_round = reweight_for_congestion(
          plan, nv0, options.congestion_step * metric_unit(mesh, unit, hops), reweight_rounds, reweight_rounds,
          [&](const std::vector<double>& penalty, DetachPlan& next) {
            CutResult trial = new_trial(root);
            const bool ok = canonical_rounds(trial, unit, hops, rounds_limit, next, &penalty);
            latest = trial.stats;
            latest_count = ok ? planned_vertices(next) : 0;
            return ok;
          },
          [&](int) {
            stats = latest;
            if (publish) *publish = latest_count;
          });
      stats.congestion_best_round = kept_round;
      stats.congestion_rounds = reweight_rounds;
    };
    bool raced = false;
    auto run_candidate = [&](int c, bool hops, bool crosses_only, long best, Outcome& out, bool race) {
      if (crosses_only) {
        attempt(c, hops, true, best, out);
        return;
      }
      const bool crosses_may_count = options.construction == C::Best && rounds_limit <= best;
      if (!race || !crosses_may_count) {
        if (attempt(c, hops, false, std::min(best, rounds_limit), out) || !crosses_may_count) return;
        attempt(c, hops, true, best, out);
        out.rounds_passed = true;
        return;
      }
      raced = true;
      Outcome crossed;
      std::atomic<long> rounds_planned{std::numeric_limits<long>::max()};
      std::atomic<long> crosses_planned{std::numeric_limits<long>::max()};
      std::exception_ptr crosses_error;
      auto rounds = [&] {
        try {
          if (attempt(c, hops, false, std::min(best, rounds_limit), out, reweight_rounds == 0 ? &crosses_planned : nullptr)) {
            rounds_planned = planned_vertices(out.plan);
            if (reweight_rounds > 0) reweight(c, hops, out.plan, out.stats, &rounds_planned), out.reweighted = true;
          }
        } catch (...) {
          rounds_planned = -1;  // the error wins: the crosses stop at their next round
          throw;
        }
      };
      auto crosses = [&] {
        try {
          if (attempt(c, hops, true, best, crossed, &rounds_planned)) crosses_planned = planned_vertices(crossed.plan);
        } catch (...) {
          crosses_error = std::current_exception();
        }
      };
      run_pair(options.parallel, rounds, crosses);
      if (out.ok && (!crossed.ok || planned_vertices(out.plan) <= planned_vertices(crossed.plan))) return;
      if (!out.ok && crosses_error) std::rethrow_exception(crosses_error);
      if (!crossed.ok) return;  // neither
      out = std::move(crossed);
      out.rounds_passed = true;
    };
    // The rounds pass max_rounds_growth on coarse meshes of high genus (cheese: 134 faces per
    // handle, a generated genus 200 on 30k faces: 150) and stay well within it on fine ones
    // (couplingdown: 413, the 1M-face genus 20: 49.5k): a lone candidate races the two below
    // kRaceFacesPerHandle. Not on fine meshes below kCrossesGenus: there the rounds plan about as
    // many vertices in half the time (the 1M-face genus 20: 546.8k in 4.3 s against 536.0k in
    // 8.1 s; genus 10 on 200k faces: 109.4k in 0.6 s against 111.1k in 1.0 s).
    // From kCrossesGenus on every candidate runs the crosses alone (Best): on every mesh of that
    // genus measured the crosses planned at most the rounds' vertices, where the rounds
    // succeeded at all (cheese; 50 generated meshes of genus 50-200 on 2k-1M faces, e.g. genus 50
    // on 500k faces 424k vertices for the rounds alone against 345k, genus 60 on 600k 843k
    // against 403k; 13 of genus 30-45, e.g. one root: genus 30 on 400k faces 303k against 230k,
    // genus 40 on 1M 735k against 576k; 4-6 roots: genus 35 on 40k faces 45.0k for Best against
    // 35.5k for the crosses alone, genus 30 on 36k 34.0k against 28.3k), and the rounds often
    // failed only after the crosses had finished (genus 200 on 400k faces: 31.7 s against
    // 12.3 s). With several candidates the first two no longer try the rounds before the crosses
    // (genus 50-133, 16 meshes with 1-24 candidates: the same cuts, 10-45 % faster).
    constexpr long kRaceFacesPerHandle = 2000;
    constexpr int kCrossesGenus = 30;
    const bool race = mesh.num_faces() < kRaceFacesPerHandle * static_cast<long>(genus);
    const bool crosses_by_genus = options.construction == C::Best && genus >= kCrossesGenus;
    bool found = false, kept_hops = false, kept_reweighted = false;
    int tried = 0, rounds_passed = 0;
    DetachPlan kept;
    for (std::size_t i = 0; i < candidates.size(); i += 2) {  // chunks of two
      const std::size_t n = std::min<std::size_t>(2, candidates.size() - i);
      const long best = found ? planned_vertices(kept) - 1 : limit;
      const bool crosses_only = options.construction == C::Crosses || crosses_by_genus ||
                                (options.construction == C::Best && rounds_passed >= 2);
      Outcome out[2];
      auto run = [&](std::size_t j) {
        return [&, j] {
          run_candidate(candidates[i + j].first, candidates[i + j].second, crosses_only, best, out[j], false);
        };
      };
      if (n == 2) run_pair(options.parallel, run(0), run(1));
      else run_candidate(candidates[i].first, candidates[i].second, crosses_only, best, out[0], race);
      for (std::size_t j = 0; j < n; ++j) {
        ++tried;
        rounds_passed += out[j].rounds_passed;
        if (out[j].ok && (!found || planned_vertices(out[j].plan) < planned_vertices(kept))) {
          res.root = candidates[i + j].first;
          res.stats = out[j].stats;
          res.stats.crosses = out[j].crosses;
          kept = std::move(out[j].plan);
          kept_hops = out[j].hops;
          kept_reweighted = out[j].reweighted;
          found = true;
        }
      }
    }
    // The kept rounds plan's congestion reweighting (in a race it came before the comparison).
    if (found && !res.stats.crosses && !kept_reweighted && reweight_rounds > 0)
      reweight(res.root, kept_hops, kept, res.stats, nullptr);
    res.stats.raced = raced;
    if (found) {
      res.stats.planned_vertices = planned_vertices(kept);
      res.loops = realize_strands(kept, res.stats, options.parallel);
      rs = std::move(kept.rs);
      found = rs.mesh.num_vertices() <= limit;  // chord splits and face vertices come on top of the plan
    }
    if (!found && options.construction == C::Rounds)
      throw Error(ErrorKind::Unsupported,
                  "normal form: the rounds would grow the mesh past " + std::to_string(rounds_limit) +
                      " vertices (CutOptions::max_rounds_growth x " + std::to_string(nv0) +
                      " input vertices); use the crosses construction, or run without the normal form");
    if (!found)
      throw Error(ErrorKind::Unsupported,
                  "normal form: the canonical loops would grow the mesh past " + std::to_string(limit) +
                      " vertices (CutOptions::max_normal_form_growth x " + std::to_string(nv0) +
                      " input vertices); run without the normal form");
    res.stats.genus = genus;
    res.stats.vertices_before = nv0;
    res.stats.faces_before = mesh.num_faces();
    res.stats.roots_tried = tried;
    res.stats.seconds_detach = seconds_since(t_start);
  } else {
    // Root and metric: the given root with 3D edge lengths, or among K deterministic root
    // candidates (root_candidates_by_ring_deficit, K = clamp(1e6 / F, 1, 24): the extra cost is
    // bounded by one basis computation on a 1M-face mesh), each with 3D lengths and with hop
    // counts as the basis metric, ranked by the crossings their detaching will make (predicted by plan_detach, without
    // building anything; the earlier wins ties). The best CutOptions::congestion_candidates of them
    // are reweighted (step 1c, two at a time on two threads) and the plan with the fewest planned
    // vertices is kept (the better ranked on ties), so the result does not depend on the threads.
    std::vector<DetachPlan> top;  // the best ranked plans, best first
    const int rounds = congestion_budget(options, mesh, 1000000L, 1L);
    const std::size_t keep = rounds > 0 ? static_cast<std::size_t>(options.congestion_candidates) : 1;
    if (options.root >= 0) {
      top.push_back(plan_detach(mesh, unit, options.root, genus, false));
    } else {
      const long k = std::clamp(1000000L / std::max(1, mesh.num_faces()), 1L, 24L);
      for (int c : root_candidates_by_ring_deficit(mesh, k, genus)) {
        DetachPlan q[2];  // 3D lengths, hop counts: planned side by side, ranked in that order
        run_pair(options.parallel, [&] { q[0] = plan_detach(mesh, unit, c, genus, false); },
                 [&] { q[1] = plan_detach(mesh, unit, c, genus, true); });
        for (DetachPlan& p : q) {
          ++res.stats.roots_tried;
          // Insert after every kept plan with at most as many crossings (stable), drop the last.
          std::size_t at = top.size();
          while (at > 0 && p.crossings < top[at - 1].crossings) --at;
          if (at < keep) {
            top.insert(top.begin() + static_cast<std::ptrdiff_t>(at), std::move(p));
            if (top.size() > keep) top.pop_back();
          }
        }
      }
    }
    // Congestion reweighting at each kept root and metric (reweight_for_congestion).
    DetachPlan P;
    std::optional<TightenedLoops> drawn_win;  // the drawn comparison's winner, drawn and tightened
    CutStats drawn_stats;                     // its drawing's counts
    if (rounds > 0) {
      check_congestion_step(options.congestion_step);
      std::vector<int> best_round(top.size(), 0);
      for (std::size_t i = 0; i < top.size(); i += 2) {
        auto one = [&](std::size_t j) {
          return [&, j] {
            if (j >= top.size()) return;
            const bool hops = top[j].hops;
            const int root = top[j].root;
            best_round[j] = reweight_for_congestion(
                top[j], nv0, options.congestion_step * metric_unit(mesh, unit, hops), rounds, kCongestionPatience,
                [&](const std::vector<double>& penalty, DetachPlan& plan) {
                  plan = plan_detach(mesh, unit, root, genus, hops, &penalty);
                  return true;
                },
                [](int) {});
          };
        };
        run_pair(options.parallel && i + 1 < top.size(), one(i), one(i + 1));
      }
      std::size_t win = 0;
      for (std::size_t j = 1; j < top.size(); ++j)
        if (planned_vertices(top[j]) < planned_vertices(top[win])) win = j;
      // On meshes of at most 2e5 faces the reweighted candidates are drawn and tightened on copies,
      // and the fewest vertices win instead (the better ranked on ties): the plan does not see
      // what the tightening will remove. Tightened here even with CutOptions::tighten off, so that
      // the option does not change the loops chosen; with it on, the winner's copy is the result
      // (not drawn a second time). O(C (n + crossings)).
      if (top.size() > 1 && mesh.num_faces() <= 200000) {
        long fewest = -1;
        for (std::size_t j = 0; j < top.size(); ++j) {
          DetachPlan copy = top[j];
          CutStats scratch;
          copy.rs.input_positions = positions;
          std::vector<std::vector<int>> loops = realize_strands(copy, scratch, options.parallel);
          TightenedLoops t = tighten_loops(std::move(copy.rs), std::move(loops), copy.root);
          const long drawn = t.surface.mesh.num_vertices();
          if (fewest < 0 || drawn < fewest) {
            fewest = drawn, win = j;
            if (options.tighten) drawn_win = std::move(t), drawn_stats = scratch;
          }
        }
      }
      P = std::move(top[win]);
      res.stats.congestion_rounds = rounds;
      res.stats.congestion_best_round = best_round[win];
      res.stats.congestion_candidates = static_cast<int>(top.size());
    } else {
      P = std::move(top[0]);
    }
    res.root = P.root;
    res.stats.band_splits = P.band_splits;
    res.stats.predicted_crossings = P.crossings;
    res.stats.planned_vertices = planned_vertices(P);
    res.stats.seconds_basis = seconds_since(t_start);
    const auto t_detach = Clock::now();
    if (drawn_win) {
      res.stats.crossings = drawn_stats.crossings;
      res.stats.steiner_vertices = drawn_stats.steiner_vertices;
      res.stats.chord_splits = drawn_stats.chord_splits;
      res.stats.collapsed = drawn_win->stats.collapsed;
      rs = std::move(drawn_win->surface);
      res.loops = std::move(drawn_win->loops);
      tightened = true;
    } else {
      P.rs.input_positions = positions;
      res.loops = realize_strands(P, res.stats, options.parallel);
      rs = std::move(P.rs);
    }
    res.stats.seconds_detach = seconds_since(t_detach);
  }
  if (options.tighten && !tightened) {
    const auto t_tighten = Clock::now();
    TightenedLoops t = tighten_loops(std::move(rs), std::move(res.loops), res.root);
    rs = std::move(t.surface);
    res.loops = std::move(t.loops);
    res.stats.collapsed = t.stats.collapsed;
    res.stats.seconds_detach += seconds_since(t_tighten);
  }
  const auto t_cut = Clock::now();

  // ---- 4. the cut (with the normal form: loops renumbered so that the word is L0 L1 L0^-1 ...) ----
  build_cut(res, -1);
  if (options.normal_form) relabel_blocks(res, word_of(res));
  res.stats.precondition_splits += precondition_pass(res);
  build_cut(res, find_he(rs.mesh, res.root, res.loops[0][1]));
  if (options.normal_form && !is_canonical_word(word_of(res)))
    internal("cut word is not canonical: " + to_string(word_of(res)));
  res.stats.seconds_cut = seconds_since(t_cut);
  res.stats.vertices_after = rs.mesh.num_vertices();
  res.stats.faces_after = rs.mesh.num_faces();
  res.stats.seconds_total = seconds_since(t_start);
  return res;
}

// Step 0: the locality order. Vertices renumbered breadth-first from vertex 0 (a vertex's
// unnumbered neighbours in its rotation order from its vertex half-edge; a vertex no search reached
// starts a new one), faces in the order in which the vertices, in the new order, first meet them
// (around each in rotation order), every face's corners in their given rotation. O(V + F).
struct LocalityOrder {
  std::vector<int> old_of_new;  // vertex
  TriMesh mesh;                 // the renumbered mesh
};
LocalityOrder locality_order(const TriMesh& mesh) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  LocalityOrder out;
  std::vector<int> new_of_old(nv, -1), new_face(nf, -1);
  out.old_of_new.reserve(nv);
  int placed = 0;
  for (int s = 0; s < nv; ++s) {
    if (new_of_old[s] >= 0) continue;
    new_of_old[s] = static_cast<int>(out.old_of_new.size());
    out.old_of_new.push_back(s);
    // The queue is old_of_new itself: vertices are taken in their new order, so the faces are met
    // in the order stated above, in the same walk around each.
    for (std::size_t i = static_cast<std::size_t>(new_of_old[s]); i < out.old_of_new.size(); ++i) {  // each vertex once
      const int v = out.old_of_new[i];
      const int h0 = mesh.vertex_halfedge(v);
      int h = h0;
      do {  // valence(v) steps
        const int w = mesh.target(h);
        if (new_of_old[w] < 0) new_of_old[w] = static_cast<int>(out.old_of_new.size()), out.old_of_new.push_back(w);
        if (new_face[TriMesh::face(h)] < 0) new_face[TriMesh::face(h)] = placed++;
        h = mesh.next_around_origin(h);
      } while (h != h0);
    }
  }
  std::vector<int> origin(3 * static_cast<std::size_t>(nf)), twin(3 * static_cast<std::size_t>(nf));
  for (int h = 0; h < 3 * nf; ++h) {
    const int g = 3 * new_face[TriMesh::face(h)] + h % 3, t = mesh.twin(h);
    origin[g] = new_of_old[mesh.origin(h)];
    twin[g] = 3 * new_face[TriMesh::face(t)] + t % 3;
  }
  out.mesh = TriMesh::from_halfedges(nv, std::move(origin), std::move(twin));
  return out;
}

// A result on the renumbered mesh in the caller's numbering: input vertices get their ids back
// (constructed ones keep theirs, and their points' slots are sorted again), faces and disk
// vertices stay as they are. O(V + F).
void restore_order(CutResult& res, const std::vector<int>& old_of_new, const std::vector<Vec3d>& positions) {
  RefinedSurface& rs = res.surface;
  const int nin = rs.num_input_vertices;
  auto old_id = [&](int v) { return v < nin ? old_of_new[v] : v; };
  std::vector<int> origin = rs.mesh.origins();
  for (int& v : origin) v = old_id(v);
  std::vector<int> twin = rs.mesh.twins();
  rs.mesh = TriMesh::from_halfedges(rs.mesh.num_vertices(), std::move(origin), std::move(twin));
  for (SurfacePoint& p : rs.constructed) {
    for (int i = 0; i < 3 && p.v[i] >= 0; ++i) p.v[i] = old_of_new[p.v[i]];
    for (int i = 1; i < 3 && p.v[i] >= 0; ++i)  // insertion sort of the used slots
      for (int j = i; j > 0 && p.v[j - 1] > p.v[j]; --j) {
        std::swap(p.v[j - 1], p.v[j]);
        mpq_swap(p.w[j - 1].get_mpq_t(), p.w[j].get_mpq_t());
      }
  }
  rs.input_positions = positions;
  res.root = old_id(res.root);
  for (auto& loop : res.loops)
    for (int& v : loop) v = old_id(v);
  for (int& v : res.disk_to_surface) v = old_id(v);
}

}  // namespace

CutResult cut_to_canonical_disk(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                const CutOptions& options) {
  const auto t_start = Clock::now();
  const int nv = mesh.num_vertices();
  // The input and the options, checked once, before step 0: errors name the caller's ids.
  if (static_cast<int>(positions.size()) != nv)
    throw Error(ErrorKind::InvalidArgument, "positions (" + std::to_string(positions.size()) +
                                                ") do not match the mesh vertices (" + std::to_string(nv) + ")");
  if (nv == 0) throw Error(ErrorKind::Empty, "mesh has no vertices");
  for (int v = 0; v < nv; ++v)
    if (mesh.vertex_halfedge(v) < 0)
      throw Error(ErrorKind::InvalidArgument, "vertex " + std::to_string(v) + " is used by no face", {v});
  const int chi = mesh.num_vertices() - mesh.num_edges() + mesh.num_faces();
  if (chi > 2 || chi % 2 != 0) throw Error(ErrorKind::InvalidArgument, "Euler characteristic " + std::to_string(chi));
  const int genus = (2 - chi) / 2;
  if (genus == 0) throw Error(ErrorKind::Unsupported, "genus 0 surface: the topology stage needs genus >= 1");
  if (options.root < -1 || options.root >= nv)
    throw Error(ErrorKind::InvalidArgument, "root vertex " + std::to_string(options.root) + " out of range [0, " +
                                                std::to_string(nv) + ")", {options.root});
  if (options.congestion_candidates < 1)
    throw Error(ErrorKind::InvalidArgument, "CutOptions::congestion_candidates must be >= 1, got " +
                                                std::to_string(options.congestion_candidates));
  if (options.normal_form_roots == 0 || options.normal_form_roots < -1)
    throw Error(ErrorKind::InvalidArgument, "CutOptions::normal_form_roots must be >= 1 or -1 (automatic), got " +
                                                std::to_string(options.normal_form_roots));
  if (options.congestion_rounds < -1)
    throw Error(ErrorKind::InvalidArgument,
                "CutOptions::congestion_rounds must be >= -1 (-1: automatic), got " + std::to_string(options.congestion_rounds));
  if (options.locality_order_min_vertices < -1)
    throw Error(ErrorKind::InvalidArgument, "CutOptions::locality_order_min_vertices must be >= -1 (-1: never), got " +
                                                std::to_string(options.locality_order_min_vertices));
  if (options.locality_order_min_vertices < 0 || nv < options.locality_order_min_vertices)
    return cut_in_given_order(mesh, positions, options, genus);
  const LocalityOrder order = locality_order(mesh);
  std::vector<Vec3d> renumbered(nv);
  for (int v = 0; v < nv; ++v) renumbered[v] = positions[order.old_of_new[v]];
  CutOptions o = options;
  if (o.root >= 0) o.root = static_cast<int>(std::find(order.old_of_new.begin(), order.old_of_new.end(), o.root) - order.old_of_new.begin());
  CutResult res = cut_in_given_order(order.mesh, renumbered, o, genus);
  restore_order(res, order.old_of_new, positions);
  res.stats.locality_ordered = true;
  res.stats.seconds_total = seconds_since(t_start);
  return res;
}

}  // namespace igm
