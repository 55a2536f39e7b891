#include "igm/topology/open_cut.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "igm/core/error.h"
#include "igm/core/union_find.h"
#include "topology_internal.h"

namespace igm {

namespace {

using namespace topology_internal;

[[noreturn]] void bad(const std::string& what, std::vector<std::int64_t> ids = {}) {
  throw Error(ErrorKind::InvalidArgument, "cut_open_surface: " + what, std::move(ids));
}

std::string str(long long x) { return std::to_string(x); }

// A cut path of the refined S': a loop (a cycle from the root, its last vertex joined to the
// first) or a leg (open).
struct CutPath {
  std::vector<int> v;
  bool cycle = false;
};

// The construction's state on the refined filled surface S'.
struct Work {
  RefinedSurface rs;
  int nv_s = 0;               // S's vertices (ids 0..nv_s-1); the centers h_j are nv_s + j
  int holes = 0;
  std::vector<int> hole_of;   // per vertex: the loop it lies on (a boundary vertex of S), or -1
  std::vector<char> on_cut;   // per vertex: on a loop or a leg
  std::vector<char> corner;   // per vertex: every disk copy is a corner
  std::vector<Vec3d> pos;     // per vertex: unit-scaled positions, for the legs' metric
  std::vector<CutPath> paths;
  std::vector<std::int64_t> cut_edges;  // sorted keys min * 2^32 + max of the paths' edges

  static std::int64_t key(int a, int b) {
    return (std::int64_t(std::min(a, b)) << 32) | std::int64_t(std::max(a, b));
  }
  bool is_cut_edge(int a, int b) const { return std::binary_search(cut_edges.begin(), cut_edges.end(), key(a, b)); }
  void add_path(std::vector<int> v, bool cycle) {
    const std::size_t k = v.size();
    for (std::size_t i = 0; i + 1 < k + (cycle ? 1 : 0); ++i) cut_edges.push_back(key(v[i], v[(i + 1) % k]));
    std::sort(cut_edges.begin(), cut_edges.end());
    for (int x : v) on_cut[x] = 1;
    paths.push_back({std::move(v), cycle});
  }

  int nv() const { return rs.mesh.num_vertices(); }
  bool is_center(int v) const { return v >= nv_s && v < nv_s + holes; }
  // On a boundary loop of S or a center: no loop may use it.
  bool in_hole(int v) const { return hole_of[v] >= 0 || is_center(v); }
  bool fan_face(int f) const {
    const auto c = rs.mesh.face_vertices(f);
    return is_center(c[0]) || is_center(c[1]) || is_center(c[2]);
  }
  void grow() {
    const std::size_t n = static_cast<std::size_t>(nv());
    hole_of.resize(n, -1);
    on_cut.resize(n, 0);
    corner.resize(n, 0);
  }
  // Splits the edge a-b at its midpoint (exactly); the new vertex is off every hole and cut.
  int split(int a, int b) {
    const int m = rs.split_edge(find_he(rs.mesh, a, b), make_rational(1, 2));
    grow();
    if (!pos.empty()) {
      const Vec3d &p = pos[a], &q = pos[b];
      pos.push_back({(p.x + q.x) / 2, (p.y + q.y) / 2, (p.z + q.z) / 2});
    }
    return m;
  }
  // Per half-edge: on a cut path (both half-edges of the edge). O(n).
  std::vector<char> cut_halfedges() const {
    std::vector<char> cut(rs.mesh.num_halfedges(), 0);
    for (const CutPath& p : paths) {
      const std::size_t k = p.v.size();
      for (std::size_t i = 0; i + 1 < k + (p.cycle ? 1 : 0); ++i) {
        const int h = find_he(rs.mesh, p.v[i], p.v[(i + 1) % k]);
        cut[h] = cut[rs.mesh.twin(h)] = 1;
      }
    }
    return cut;
  }
};

// The positions scaled by one power of two so that the largest |coordinate| is in [1, 2) (lengths
// then finite at any magnitude; only a search metric). Throws NonFinite for a NaN or infinity.
std::vector<Vec3d> unit_scaled(const std::vector<Vec3d>& p) {
  double m = 0;
  for (std::size_t v = 0; v < p.size(); ++v) {
    if (!std::isfinite(p[v].x) || !std::isfinite(p[v].y) || !std::isfinite(p[v].z))
      throw Error(ErrorKind::NonFinite, "cut_open_surface: vertex " + str(static_cast<long long>(v)) +
                                            " has a non-finite coordinate", {static_cast<std::int64_t>(v)});
    m = std::max({m, std::fabs(p[v].x), std::fabs(p[v].y), std::fabs(p[v].z)});
  }
  if (m == 0) return p;
  const int e = std::ilogb(m);
  std::vector<Vec3d> out(p.size());
  for (std::size_t v = 0; v < p.size(); ++v)
    out[v] = {std::ldexp(p[v].x, -e), std::ldexp(p[v].y, -e), std::ldexp(p[v].z, -e)};
  return out;
}

// The number of half-edges leaving each vertex. O(n).
std::vector<int> out_degrees(const TriMesh& m) {
  std::vector<int> degree(m.num_vertices(), 0);
  for (int h = 0; h < m.num_halfedges(); ++h) ++degree[m.origin(h)];
  return degree;
}

// Step 1: the input checked, S' built (fans to the centers at the loops' centroids). Returns the
// genus. O(F log F).
int fill(const SurfaceComponent& s, Work& w) {
  const int n = static_cast<int>(s.positions.size());
  const int nf = static_cast<int>(s.triangles.size());
  const int b = static_cast<int>(s.boundary_loops.size());
  if (n == 0) throw Error(ErrorKind::Empty, "cut_open_surface: no vertices");
  if (nf == 0) throw Error(ErrorKind::NoFaces, "cut_open_surface: no triangles");
  for (int v = 0; v < n; ++v) {
    const Vec3d& p = s.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(ErrorKind::NonFinite, "cut_open_surface: vertex " + str(v) + " has a non-finite coordinate", {v});
  }
  if (b == 0)
    throw Error(ErrorKind::Unsupported,
                "cut_open_surface: the surface is closed (use cut_to_canonical_disk or cut_sphere)");
  std::vector<char> used(n, 0);
  // Per half-edge a -> c: (min * n + max) * 2 + (a > c), sorted: an edge's half-edges side by side.
  std::vector<std::int64_t> directed;
  directed.reserve(3 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    const auto& t = s.triangles[f];
    for (int i = 0; i < 3; ++i) {
      if (t[i] < 0 || t[i] >= n)
        throw Error(ErrorKind::IndexOutOfRange, "cut_open_surface: triangle " + str(f) + " uses vertex " + str(t[i]),
                    {f});
      used[t[i]] = 1;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      throw Error(ErrorKind::RepeatedVertex, "cut_open_surface: triangle " + str(f) + " repeats a vertex", {f});
    for (int i = 0; i < 3; ++i) {
      const int a = t[i], c = t[(i + 1) % 3];
      directed.push_back((std::int64_t(std::min(a, c)) * n + std::max(a, c)) * 2 + (a > c));
    }
  }
  for (int v = 0; v < n; ++v)
    if (!used[v]) bad("vertex " + str(v) + " is used by no triangle", {v});
  std::sort(directed.begin(), directed.end());
  auto origin_of = [&](std::int64_t d) { return d % 2 ? (d / 2) % n : (d / 2) / n; };
  auto target_of = [&](std::int64_t d) { return d % 2 ? (d / 2) / n : (d / 2) % n; };
  std::vector<std::int64_t> open;  // a * n + c per half-edge a -> c without a twin, sorted
  for (std::size_t i = 0; i < directed.size();) {
    std::size_t j = i;
    while (j < directed.size() && directed[j] / 2 == directed[i] / 2) ++j;
    if (j - i > 2 || (j - i == 2 && directed[i] == directed[i + 1]))
      throw Error(ErrorKind::NonManifoldEdge, "cut_open_surface: edge " + str(origin_of(directed[i])) + " - " +
                                                  str(target_of(directed[i])) + " has two triangles on one side",
                  {origin_of(directed[i]), target_of(directed[i])});
    if (j - i == 1) open.push_back(origin_of(directed[i]) * n + target_of(directed[i]));
    i = j;
  }
  std::sort(open.begin(), open.end());
  const long long open_halfedges = static_cast<long long>(open.size());
  auto is_open = [&](int a, int c) { return std::binary_search(open.begin(), open.end(), std::int64_t(a) * n + c); };
  w.hole_of.assign(n, -1);
  long long loop_length = 0;
  for (int j = 0; j < b; ++j) {
    const auto& L = s.boundary_loops[j];
    if (L.size() < 3) bad("boundary loop " + str(j) + " has fewer than 3 vertices", {j});
    for (std::size_t i = 0; i < L.size(); ++i) {
      const int a = L[i], c = L[(i + 1) % L.size()];
      if (a < 0 || a >= n) bad("boundary loop " + str(j) + " has vertex " + str(a) + " out of range", {j});
      if (w.hole_of[a] >= 0) bad("vertex " + str(a) + " is on two boundary loops or twice on one", {a});
      w.hole_of[a] = j;
      if (c < 0 || c >= n || !is_open(a, c))
        bad("boundary loop " + str(j) + ": " + str(a) + " -> " + str(c) + " is not a boundary half-edge", {a, c});
    }
    loop_length += static_cast<long long>(L.size());
  }
  if (loop_length != open_halfedges)
    bad("the loops hold " + str(loop_length) + " of the " + str(open_halfedges) + " boundary half-edges");
  const long long edges = (3LL * nf + open_halfedges) / 2;
  const long long twice_genus = 2 - (n - edges + nf) - b;
  if (twice_genus < 0 || twice_genus % 2 != 0 || twice_genus / 2 != s.genus)
    bad("genus " + str(s.genus) + " does not match the Euler characteristic " + str(n - edges + nf) + " with " +
        str(b) + " loops");
  std::vector<std::array<int, 3>> tris = s.triangles;
  std::vector<Vec3d> positions = s.positions;
  for (int j = 0; j < b; ++j) {
    const auto& L = s.boundary_loops[j];
    Vec3d c{0, 0, 0};
    for (int v : L) c.x += s.positions[v].x, c.y += s.positions[v].y, c.z += s.positions[v].z;
    const double k = static_cast<double>(L.size());
    c = {c.x / k, c.y / k, c.z / k};
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) c = s.positions[L[0]];  // overflow
    positions.push_back(c);
    for (std::size_t i = 0; i < L.size(); ++i) tris.push_back({L[(i + 1) % L.size()], L[i], n + j});
  }
  w.rs.mesh = TriMesh::from_triangles(n + b, tris);
  {  // each vertex one fan: the walk around it meets all of its half-edges
    const TriMesh& m = w.rs.mesh;
    const std::vector<int> degree = out_degrees(m);
    for (int v = 0; v < n + b; ++v) {
      int steps = 0;
      for (int h = m.next_around_origin(m.vertex_halfedge(v)); steps <= degree[v]; h = m.next_around_origin(h)) {
        ++steps;
        if (h == m.vertex_halfedge(v)) break;
      }
      if (steps != degree[v])
        throw Error(ErrorKind::NonManifoldVertex, "cut_open_surface: the faces around vertex " + str(v) +
                                                      " form more than one fan", {v});
    }
  }
  w.rs.num_input_vertices = n + b;
  w.rs.input_positions = std::move(positions);
  w.nv_s = n;
  w.holes = b;
  w.grow();
  return static_cast<int>(twice_genus / 2);
}

// The loop j of the refined surface: from `start`, along the half-edges with an S face on their
// left and a fan on their right. O(loop length x valence).
std::vector<int> refined_loop(const Work& w, int start) {
  const TriMesh& m = w.rs.mesh;
  std::vector<int> loop;
  int x = start;
  do {  // each step a new loop vertex: at most nv steps
    if (static_cast<int>(loop.size()) > w.nv()) internal("open cut: a boundary loop does not close", {start});
    loop.push_back(x);
    const int h0 = m.vertex_halfedge(x);
    int h = h0, next = -1;
    do {  // valence steps
      if (!w.fan_face(TriMesh::face(h)) && w.fan_face(TriMesh::face(m.twin(h)))) next = m.target(h);
      h = m.next_around_origin(h);
    } while (h != h0);
    if (next < 0) internal("open cut: a loop vertex has no boundary half-edge", {x});
    x = next;
  } while (x != start);
  return loop;
}

// Step 2: every S edge (two S faces) joining two boundary vertices split at its midpoint. O(n).
int split_chords(Work& w) {
  const TriMesh& m = w.rs.mesh;
  std::vector<std::pair<int, int>> todo;
  for (int h = 0; h < m.num_halfedges(); ++h)
    if (h < m.twin(h) && !w.fan_face(TriMesh::face(h)) && !w.fan_face(TriMesh::face(m.twin(h))) &&
        w.hole_of[m.origin(h)] >= 0 && w.hole_of[m.target(h)] >= 0)
      todo.push_back({m.origin(h), m.target(h)});
  for (auto [a, b] : todo) w.split(a, b);
  return static_cast<int>(todo.size());
}

// p with the ids of `pre`'s vertices (a refinement of S') replaced by their points: a point of S'.
// Pre: p's support lies in one face of pre (so the result's lies in one input face). O(1) GMP.
SurfacePoint compose(const SurfacePoint& p, const RefinedSurface& pre) {
  SurfacePoint acc;
  Rational wsum = 0;
  for (int i = 0; i < 3 && p.v[i] >= 0; ++i) {
    const SurfacePoint term = pre.point(p.v[i]);
    if (i == 0) {
      acc = term;
      wsum = p.w[0];
      continue;
    }
    const Rational total = wsum + p.w[i];
    acc = combine(acc, Rational(wsum / total), term, Rational(p.w[i] / total));
    wsum = total;
  }
  return acc;
}

// Step 3 (g >= 1): the loops through the root, in the interior of S. Fills w.paths, the root and
// the stats. Cost: the closed cut's, plus O(n) GMP compositions.
int loops_step(Work& w, int genus, const OpenCutOptions& options, OpenCutStats& stats) {
  const int n0 = w.nv(), nin = w.rs.num_input_vertices;
  std::vector<Vec3d> real(n0);
  for (int v = 0; v < n0; ++v) real[v] = w.rs.position(v);
  std::vector<Vec3d> fake = unit_scaled(real);
  const TriMesh& m = w.rs.mesh;
  double interior_length = 0;  // of the edges of I (both ends off the holes)
  for (int h = 0; h < m.num_halfedges(); ++h)
    if (h < m.twin(h) && !w.in_hole(m.origin(h)) && !w.in_hole(m.target(h)))
      interior_length += length(fake[m.origin(h)], fake[m.target(h)]);
  // Every vertex in a hole at least `far` from every other vertex: |coordinates| of I are <= 2.
  const double far = 4 * interior_length + 8;
  long k = 0;
  for (int v = 0; v < n0; ++v) {
    if (w.hole_of[v] >= 0) fake[v] = {far * static_cast<double>(k + 2), 0, 0}, ++k;
    else if (w.is_center(v)) fake[v] = {0, far * static_cast<double>(v - w.nv_s + 2), 0};
  }
  int root = options.root;
  if (root >= 0) {
    if (root >= w.nv_s) bad("root " + str(root) + " out of range [0, " + str(w.nv_s) + ")", {root});
    if (w.hole_of[root] >= 0) bad("root " + str(root) + " lies on boundary loop " + str(w.hole_of[root]), {root});
  } else {
    int best = -1;
    const std::vector<int> valence = out_degrees(m);
    for (int pass = 0; pass < 2 && root < 0; ++pass)  // S's vertices, then the chord midpoints
      for (int v = pass == 0 ? 0 : nin; v < (pass == 0 ? w.nv_s : n0); ++v)
        if (!w.in_hole(v) && valence[v] > best) best = valence[v], root = v;
    if (root < 0) internal("open cut: no interior vertex after the chord splits");
  }
  CutOptions co;
  co.root = root;
  co.normal_form = false;  // its constructions search with their own metrics: not kept off the holes
  co.tighten = false;      // tightened below, with the holes barred
  co.congestion_rounds = 0;  // its penalties, in units of the mean edge length, would beat `far`
  co.parallel = options.parallel;
  CutResult cr = cut_to_canonical_disk(m, fake, co);
  stats.closed = cr.stats;
  if (cr.genus != genus) internal("open cut: the filled surface has genus " + str(cr.genus));
  RefinedSurface surf = std::move(cr.surface);
  std::vector<std::vector<int>> loops = std::move(cr.loops);
  if (options.tighten) {
    std::vector<char> barred(n0, 0);
    for (int v = 0; v < n0; ++v) barred[v] = w.in_hole(v);
    TightenedLoops t = tighten_loops(std::move(surf), std::move(loops), cr.root, false, barred);
    surf = std::move(t.surface);
    loops = std::move(t.loops);
    stats.tightening = t.stats;
  }
  // Every loop vertex interior to S: off the holes, and a constructed one not on a boundary edge
  // (some vertex of its support off the holes) nor in a fan (no center in its support).
  for (const auto& L : loops)
    for (int v : L) {
      bool ok = v < n0 ? !w.in_hole(v) : false;
      if (v >= n0) {
        const SurfacePoint& p = surf.constructed[v - n0];
        bool center = false;
        for (int i = 0; i < 3 && p.v[i] >= 0; ++i) {
          center = center || w.is_center(p.v[i]);
          ok = ok || !w.in_hole(p.v[i]);
        }
        ok = ok && !center;
      }
      if (!ok) internal("open cut: a loop of the closed cut touches a hole", {v});
    }
  // The closed cut's points, on S' with the chord midpoints as input vertices, composed onto S'.
  std::vector<SurfacePoint> constructed = w.rs.constructed;  // the chord midpoints: ids nin..n0-1
  constructed.reserve(constructed.size() + surf.constructed.size());
  for (const SurfacePoint& p : surf.constructed) {
    bool plain = true;
    for (int i = 0; i < 3 && p.v[i] >= 0; ++i) plain = plain && p.v[i] < nin;
    constructed.push_back(plain ? p : compose(p, w.rs));
  }
  w.rs.mesh = std::move(surf.mesh);
  w.rs.constructed = std::move(constructed);
  w.grow();
  for (auto& L : loops) w.add_path(std::move(L), true);
  return cr.root;
}

// The legs' search graph (step 4): the vertices, and the chords (edges between two S faces, on no
// cut, joining two blocked vertices: on a hole or a cut) as nodes nv + h (h the edge's smaller
// half-edge), crossed at their midpoints, which a leg that uses one splits off. A leg may enter
// passable vertices (off the holes and the cuts), chords, and its target. Every interior edge of
// the region has a passable end or is a chord, and the nodes of one face are pairwise neighbours,
// so the nodes of the faces along any dual path form a path: every hole is reachable from every
// corner, whatever the cuts box in.
struct LegGraph {
  const Work& w;
  const TriMesh& m;
  int nv;
  double penalty;  // added per chord crossed (a vertex the leg adds): mean_edge_length(work)
  LegGraph(const Work& work, double mean_edge) : w(work), m(work.rs.mesh), nv(work.nv()), penalty(mean_edge) {}
  int size() const { return nv + m.num_halfedges(); }
  bool blocked(int v) const { return w.hole_of[v] >= 0 || w.on_cut[v]; }
  bool passable(int v) const { return !w.in_hole(v) && !w.on_cut[v]; }
  bool chord(int h) const {
    const int a = m.origin(h), c = m.target(h);
    return blocked(a) && blocked(c) && !w.fan_face(TriMesh::face(h)) && !w.fan_face(TriMesh::face(m.twin(h))) &&
           !w.is_cut_edge(a, c);
  }
  int node(int h) const { return nv + std::min(h, m.twin(h)); }
  Vec3d position(int x) const {
    if (x < nv) return w.pos[x];
    const Vec3d &p = w.pos[m.origin(x - nv)], &q = w.pos[m.target(x - nv)];
    return {(p.x + q.x) / 2, (p.y + q.y) / 2, (p.z + q.z) / 2};
  }
  // f(y) for every node y next to node x: for a vertex, its neighbours and the chords at it or
  // opposite it; for a chord, its ends, its faces' apexes and their other chords. O(valence).
  template <class F>
  void around(int x, F&& f) const {
    if (x < nv) {
      const int h0 = m.vertex_halfedge(x);
      int h = h0;
      do {  // valence(x) steps
        f(m.target(h));
        if (chord(h)) f(node(h));
        if (!w.fan_face(TriMesh::face(h)) && chord(TriMesh::next(h))) f(node(TriMesh::next(h)));
        h = m.next_around_origin(h);
      } while (h != h0);
      return;
    }
    const int h = x - nv;
    for (int g : {h, m.twin(h)}) {
      f(m.origin(g));
      f(m.target(TriMesh::next(g)));
      for (int k : {TriMesh::next(g), TriMesh::prev(g)})
        if (chord(k)) f(node(k));
    }
  }
};

// The mean edge length on w.pos. O(n).
double mean_edge_length(const Work& w) {
  const TriMesh& m = w.rs.mesh;
  double sum = 0;
  for (int h = 0; h < m.num_halfedges(); ++h) sum += length(w.pos[m.origin(h)], w.pos[m.target(h)]);
  return sum / std::max(1, m.num_halfedges());
}

// The order of the legs (step 4): a spanning tree of the holes and the root (g >= 1; for g = 0
// hole 0 is the root node), the minimum one over the connections of one multi-source search from
// every hole vertex and the root (Voronoi regions: two regions touching across nodes x, y give
// the connection dist(x) + |xy| + dist(y); Kruskal), listed depth-first from the root node as
// (parent node, hole) pairs, a parent before its children. Each leg then runs from its parent's
// corner to its hole: a short, local search. Node b is the root. O(n log n).
std::vector<std::pair<int, int>> leg_order(const Work& w, int genus, int root, double mean_edge) {
  const LegGraph g(w, mean_edge);
  const int b = w.holes, n = g.size();
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  std::vector<int> label(n, -1);
  MinQueue pq;
  for (int v = 0; v < g.nv; ++v)
    if (w.hole_of[v] >= 0) dist[v] = 0, label[v] = w.hole_of[v], pq.push({0.0, v});
  if (genus >= 1) dist[root] = 0, label[root] = b, pq.push({0.0, root});
  auto enterable = [&](int y) { return y >= g.nv || g.passable(y); };
  // Links are seen when the later of their two nodes settles (the earlier's distance is final).
  struct Link { double len; int a, b; };
  std::vector<Link> links;
  std::vector<char> settled(n, 0);
  while (!pq.empty()) {  // each node settled once
    // Plain locals, not a structured binding: the lambda below captures them (C++20 allows
    // capturing bindings, clang 14 does not).
    const double d = pq.top().first;
    const int x = pq.top().second;
    pq.pop();
    if (d > dist[x] || settled[x]) continue;
    settled[x] = 1;
    g.around(x, [&](int y) {
      if (!enterable(y) && !(settled[y] && enterable(x))) return;
      const double step = length(g.position(x), g.position(y));
      if (settled[y]) {
        if (label[y] != label[x])
          links.push_back({d + step + dist[y], std::min(label[x], label[y]), std::max(label[x], label[y])});
        return;
      }
      const double nd = d + step + (y >= g.nv ? g.penalty : 0);
      if (nd < dist[y]) dist[y] = nd, label[y] = label[x], pq.push({nd, y});
    });
  }
  std::sort(links.begin(), links.end(), [](const Link& x, const Link& y) {
    return x.len < y.len || (x.len == y.len && (x.a < y.a || (x.a == y.a && x.b < y.b)));
  });
  UnionFind uf(static_cast<std::size_t>(b) + 1);
  std::vector<std::vector<int>> adj(b + 1);
  for (const Link& l : links)
    if (uf.unite(l.a, l.b)) adj[l.a].push_back(l.b), adj[l.b].push_back(l.a);
  std::vector<std::pair<int, int>> order;
  std::vector<char> seen(b + 1, 0);
  std::vector<int> stack{genus >= 1 ? b : 0};
  seen[stack[0]] = 1;
  while (!stack.empty()) {  // each node once
    const int p = stack.back();
    stack.pop_back();
    for (auto it = adj[p].rbegin(); it != adj[p].rend(); ++it)
      if (!seen[*it]) seen[*it] = 1, order.push_back({p, *it}), stack.push_back(*it);
  }
  return order;
}

// Step 4: the legs. O(n log n) for the order, plus each leg's search (its settled nodes x log),
// plus the splits.
void legs_step(Work& w, int genus, int root, OpenCutStats& stats) {
  const int b = w.holes;
  {
    std::vector<Vec3d> real(w.nv());
    for (int v = 0; v < w.nv(); ++v) real[v] = w.rs.position(v);
    w.pos = unit_scaled(real);
  }
  const double mean_edge = mean_edge_length(w);
  std::vector<char> joined(b, 0);
  std::vector<int> corners;  // surface vertices whose copies are corners
  std::vector<std::vector<int>> hole_corners(b);
  if (genus >= 1) corners.push_back(root);
  if (genus == 0) joined[0] = 1;
  std::vector<double> dist;
  std::vector<int> parent;
  std::vector<char> source;
  std::vector<int> touched;
  // One search from `from` (surface vertices) to the nearest vertex of hole `to` (-1: of any hole
  // not joined) through passable vertices and chords (at least one node between). Returns the
  // path's nodes from a source to the target (LegGraph ids), or empty.
  auto search = [&](const std::vector<int>& from, int to) {
    const LegGraph g(w, mean_edge);
    auto target = [&](int x) {
      if (x >= g.nv) return false;
      const int j = w.hole_of[x];
      return j >= 0 && !joined[j] && (to < 0 || j == to);
    };
    const std::size_t n = static_cast<std::size_t>(g.size());
    dist.resize(n, std::numeric_limits<double>::infinity());
    parent.resize(n, -1);
    source.resize(n, 0);
    MinQueue pq;
    for (int x : from) {
      dist[x] = 0, source[x] = 1;
      touched.push_back(x);
      pq.push({0.0, x});
    }
    int found = -1;
    while (!pq.empty()) {  // each node settled once
      const double d = pq.top().first;  // plain locals: captured below (clang 14)
      const int x = pq.top().second;
      pq.pop();
      if (d > dist[x]) continue;
      if (target(x)) {
        found = x;
        break;
      }
      g.around(x, [&](int y) {
        if (!(y >= g.nv || g.passable(y) || (target(y) && !source[x]))) return;
        const double nd = d + length(g.position(x), g.position(y)) + (y >= g.nv ? g.penalty : 0);
        if (nd < dist[y]) {
          if (dist[y] == std::numeric_limits<double>::infinity()) touched.push_back(y);
          dist[y] = nd, parent[y] = x;
          pq.push({nd, y});
        }
      });
    }
    std::vector<int> path;
    for (int x = found, guard = 0; x >= 0; x = parent[x], ++guard) {  // the tree has <= n nodes
      if (guard > g.size()) internal("open cut: a leg's parents form a cycle", {found});
      path.push_back(x);
    }
    std::reverse(path.begin(), path.end());
    for (int x : touched) dist[x] = std::numeric_limits<double>::infinity(), parent[x] = -1, source[x] = 0;
    touched.clear();
    // Chords as their ends, split below (the half-edge ids change with the splits).
    std::vector<std::pair<int, int>> nodes;
    for (int x : path)
      nodes.push_back(x < g.nv ? std::pair{x, -1} : std::pair{g.m.origin(x - g.nv), g.m.target(x - g.nv)});
    return nodes;
  };
  // The sources of a leg from node p: the root; a hole's corners, or for hole 0 of a genus-0
  // surface before its first leg every vertex of it.
  auto node_sources = [&](int p) {
    if (p == b) return std::vector<int>{root};
    if (!hole_corners[p].empty()) return hole_corners[p];
    std::vector<int> all;
    for (int v = 0; v < w.nv(); ++v)
      if (w.hole_of[v] == p) all.push_back(v);
    return all;
  };
  // Cuts a leg found by `search`: its chords split at their midpoints (consecutive nodes stay
  // adjacent: a chord's midpoint is joined to its ends, to its faces' apexes and to the midpoints
  // of their other chords split after it), its ends made corners.
  auto cut_leg = [&](const std::vector<std::pair<int, int>>& nodes) {
    std::vector<int> path;
    for (auto [a, c] : nodes) {
      if (c < 0) {
        path.push_back(a);
        continue;
      }
      path.push_back(w.split(a, c));
      ++stats.leg_chord_splits;
    }
    const int s = path.front(), t = path.back();
    joined[w.hole_of[t]] = 1;
    for (int x : {s, t})
      if (!w.corner[x]) {
        w.corner[x] = 1, corners.push_back(x);
        if (w.hole_of[x] >= 0) hole_corners[w.hole_of[x]].push_back(x);
      }
    stats.leg_edges += static_cast<int>(path.size()) - 1;
    ++stats.legs;
    w.add_path(std::move(path), false);
  };
  // The tree's legs, each from its parent's corner to its hole; where that finds no way (the
  // parent not joined: an earlier fallback took another hole), or for a hole the tree missed,
  // from every corner to the nearest hole not joined, which always exists (LegGraph). Each round
  // joins one hole: at most b rounds of at most two searches.
  const std::vector<std::pair<int, int>> order = leg_order(w, genus, root, mean_edge);
  std::size_t next = 0;
  for (int round = 0; round < b && std::count(joined.begin(), joined.end(), 1) < b; ++round) {
    while (next < order.size() && joined[order[next].second]) ++next;
    std::vector<std::pair<int, int>> nodes;
    if (next < order.size()) {
      const auto [p, j] = order[next];
      if (p == b || joined[p]) nodes = search(node_sources(p), j);
    }
    if (nodes.empty()) nodes = search(corners.empty() ? node_sources(0) : corners, -1);
    if (nodes.empty()) internal("open cut: no leg to the holes left");
    cut_leg(nodes);
  }
}

// The disk of the S faces of w cut along w.paths, its sides from corner to corner (every copy of
// a w.corner vertex). O(n).
struct Disk {
  std::vector<int> wedge;     // per half-edge in an S face: the disk copy of its origin; else -1
  std::vector<int> d2s;       // disk vertex -> surface vertex
  std::vector<int> bh;        // the boundary's half-edges (S faces on their left), in walk order
  std::vector<char> cut, sep; // per half-edge: on a cut path; a cut or next to a fan
  std::vector<OpenSide> sides;
  std::vector<int> side_start;  // per side: its first position in bh
};

Disk build_disk(const Work& w) {
  const TriMesh& m = w.rs.mesh;
  const int nh = m.num_halfedges();
  Disk d;
  d.cut = w.cut_halfedges();
  std::vector<char> fan(m.num_faces());
  for (int f = 0; f < m.num_faces(); ++f) fan[f] = w.fan_face(f);
  d.sep.assign(nh, 0);
  for (int h = 0; h < nh; ++h) d.sep[h] = d.cut[h] || fan[TriMesh::face(h)] || fan[TriMesh::face(m.twin(h))];
  d.wedge.assign(nh, -1);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const int h0 = m.vertex_halfedge(v);
    int start = h0;
    for (int h = m.next_around_origin(h0);; h = m.next_around_origin(h)) {  // <= valence steps
      if (d.sep[h]) { start = h; break; }
      if (h == h0) break;
    }
    int copy = -1, h = start;
    do {  // one turn around v: valence steps
      if (d.sep[h]) copy = -1;
      if (!fan[TriMesh::face(h)]) {
        if (copy < 0) copy = static_cast<int>(d.d2s.size()), d.d2s.push_back(v);
        d.wedge[h] = copy;
      }
      h = m.next_around_origin(h);
    } while (h != start);
  }
  // The boundary: half-edges of S faces that are separators, chained through the fans of their
  // targets (clockwise), as in cut_to_canonical_disk's cut.
  std::vector<char> on_boundary(nh, 0);
  int count = 0, first = -1;
  for (int h = 0; h < nh; ++h)
    if (!fan[TriMesh::face(h)] && d.sep[h]) {
      on_boundary[h] = 1, ++count;
      if (first < 0 && w.corner[m.origin(h)]) first = h;
    }
  if (first < 0) internal("open cut: no corner on the disk boundary");
  int h = first;
  do {
    d.bh.push_back(h);
    if (static_cast<int>(d.bh.size()) > count) internal("open cut: the disk boundary does not close");
    int g = TriMesh::next(h);
    for (int guard = 0; !on_boundary[g]; ++guard) {
      if (guard > nh) internal("open cut: the boundary walk is lost");
      g = TriMesh::next(m.twin(g));
    }
    h = g;
  } while (h != first);
  if (static_cast<int>(d.bh.size()) != count) internal("open cut: the cut has more than one boundary cycle");
  const int nb = static_cast<int>(d.bh.size());
  for (int i = 0; i < nb; ++i)
    if (w.corner[m.origin(d.bh[i])]) d.side_start.push_back(i);
  const int ns = static_cast<int>(d.side_start.size());
  d.sides.resize(ns);
  std::vector<int> side_of_last(nh, -1);  // the side whose last half-edge this is
  for (int s = 0; s < ns; ++s) {
    const int i0 = d.side_start[s], i1 = s + 1 < ns ? d.side_start[s + 1] : nb;
    OpenSide& side = d.sides[s];
    const bool glued = d.cut[d.bh[i0]];
    for (int i = i0; i < i1; ++i) {
      side.disk_vertices.push_back(d.wedge[d.bh[i]]);
      if (static_cast<bool>(d.cut[d.bh[i]]) != glued) internal("open cut: a side is partly glued", {m.origin(d.bh[i])});
    }
    side.disk_vertices.push_back(d.wedge[d.bh[i1 % nb]]);
    side_of_last[d.bh[i1 - 1]] = s;
    if (!glued) side.loop = w.hole_of[m.target(d.bh[i0])];
  }
  for (int s = 0; s < ns; ++s) {
    OpenSide& side = d.sides[s];
    if (side.loop >= 0) continue;
    side.mate = side_of_last[m.twin(d.bh[d.side_start[s]])];
    if (side.mate < 0 || d.sides[side.mate].disk_vertices.size() != side.disk_vertices.size())
      internal("open cut: a glued side has no mate", {s});
  }
  return d;
}

// The sides' arc lengths (3D, doubles: a choice only) between their disk vertices.
double side_length(const Work& w, const Disk& d, const OpenSide& s) {
  double sum = 0;
  for (std::size_t i = 0; i + 1 < s.disk_vertices.size(); ++i)
    sum += length(w.pos[d.d2s[s.disk_vertices[i]]], w.pos[d.d2s[s.disk_vertices[i + 1]]]);
  return sum;
}

// The index in `cum` (increasing arc lengths, cum[0] = 0) in [lo, hi] nearest `target`; by index
// (lo + hi) / 2 where every length is 0. O(hi - lo).
int nearest_index(const std::vector<double>& cum, int lo, int hi, double target) {
  if (cum.back() == 0) return std::clamp(static_cast<int>(std::lround(target)), lo, hi);
  int best = lo;
  for (int i = lo; i <= hi; ++i)
    if (std::fabs(cum[i] - target) < std::fabs(cum[best] - target)) best = i;
  return best;
}

// Step 6: every interior disk edge joining two vertices of one side split at its midpoint. O(n).
int precondition_pass(Work& w, const Disk& d) {
  const TriMesh& m = w.rs.mesh;
  const int nd = static_cast<int>(d.d2s.size());
  std::vector<int> side_a(nd, -1), side_b(nd, -1);
  for (int s = 0; s < static_cast<int>(d.sides.size()); ++s)
    for (int x : d.sides[s].disk_vertices) (side_a[x] < 0 ? side_a[x] : side_b[x]) = s;
  auto share = [&](int p, int q) {
    if (side_a[p] < 0 || side_a[q] < 0) return false;
    return side_a[p] == side_a[q] || side_a[p] == side_b[q] || (side_b[p] >= 0 && (side_b[p] == side_a[q] || side_b[p] == side_b[q]));
  };
  std::vector<std::pair<int, int>> todo;
  for (int h = 0; h < m.num_halfedges(); ++h)
    if (h < m.twin(h) && !d.sep[h] && share(d.wedge[h], d.wedge[TriMesh::next(h)]))
      todo.push_back({m.origin(h), m.target(h)});
  for (auto [a, b] : todo) w.split(a, b);
  return static_cast<int>(todo.size());
}

// Faces renumbered: S's first (in their order), then the fans'. Returns the S face count. O(F).
int s_faces_first(Work& w) {
  const TriMesh& m = w.rs.mesh;
  const int nf = m.num_faces();
  std::vector<int> new_face(nf);
  int next = 0;
  for (int f = 0; f < nf; ++f)
    if (!w.fan_face(f)) new_face[f] = next++;
  const int s_faces = next;
  for (int f = 0; f < nf; ++f)
    if (w.fan_face(f)) new_face[f] = next++;
  std::vector<int> origin(3 * static_cast<std::size_t>(nf)), twin(3 * static_cast<std::size_t>(nf));
  for (int h = 0; h < 3 * nf; ++h) {
    const int g = 3 * new_face[TriMesh::face(h)] + h % 3, t = m.twin(h);
    origin[g] = m.origin(h);
    twin[g] = 3 * new_face[TriMesh::face(t)] + t % 3;
  }
  w.rs.mesh = TriMesh::from_halfedges(m.num_vertices(), std::move(origin), std::move(twin));
  return s_faces;
}

}  // namespace

OpenCut cut_open_surface(const SurfaceComponent& surface, const OpenCutOptions& options) {
  const auto t_start = Clock::now();
  Work w;
  const int genus = fill(surface, w);
  const int b = w.holes;
  OpenCut out;
  OpenCutStats& st = out.stats;
  st.genus = out.genus = genus;
  st.boundary_loops = out.boundary_loops = b;
  st.vertices_before = w.nv_s;
  st.faces_before = static_cast<int>(surface.triangles.size());
  if (genus == 0 && b == 1) {  // a disk: its loop needs 4 vertices for 4 corners
    for (int k = static_cast<int>(surface.boundary_loops[0].size()); k < 4; ++k) {  // at most one split
      const std::vector<int> loop = refined_loop(w, surface.boundary_loops[0][0]);
      const int m = w.split(loop[0], loop[1]);
      w.hole_of[m] = 0;
      ++st.boundary_splits;
    }
  }
  st.chord_splits = split_chords(w);
  const auto t_loops = Clock::now();
  if (genus >= 1) {
    out.root = loops_step(w, genus, options, st);
    w.corner[out.root] = 1;
  }
  st.seconds_loops = seconds_since(t_loops);
  const auto t_legs = Clock::now();
  if (b >= 2 || genus >= 1) {
    legs_step(w, genus, out.root, st);
  } else {
    std::vector<Vec3d> real(w.nv());
    for (int v = 0; v < w.nv(); ++v) real[v] = w.rs.position(v);
    w.pos = unit_scaled(real);
    // Step 5, a disk: four corners at about the quarters of the loop's length.
    const std::vector<int> loop = refined_loop(w, surface.boundary_loops[0][0]);
    const int n = static_cast<int>(loop.size());
    std::vector<double> cum(n + 1, 0.0);
    for (int i = 0; i < n; ++i) cum[i + 1] = cum[i] + length(w.pos[loop[i]], w.pos[loop[(i + 1) % n]]);
    int at = 0;
    w.corner[loop[0]] = 1;
    for (int q = 1; q < 4; ++q) {
      const double goal = cum.back() == 0 ? q * n / 4.0 : cum.back() * q / 4;
      at = nearest_index(cum, at + 1, n - 4 + q, goal);
      w.corner[loop[at]] = 1;
    }
  }
  st.seconds_legs = seconds_since(t_legs);
  // Step 5: an even number of sides (the count is >= 4 here: 4g + 3b with g >= 1, 3b - 2 with
  // b >= 2, or the disk's 4).
  Disk d = build_disk(w);
  if (d.sides.size() % 2 != 0) {
    int longest = -1;
    double best = -1;
    for (int s = 0; s < static_cast<int>(d.sides.size()); ++s)
      if (d.sides[s].loop >= 0 && d.sides[s].disk_vertices.size() >= 3) {
        const double len = side_length(w, d, d.sides[s]);
        if (len > best) best = len, longest = s;
      }
    if (longest < 0) internal("open cut: an odd side count and no free side to split");
    const OpenSide& side = d.sides[longest];
    const int k = static_cast<int>(side.disk_vertices.size());
    std::vector<double> cum(k, 0.0);
    for (int i = 1; i < k; ++i)
      cum[i] = cum[i - 1] + length(w.pos[d.d2s[side.disk_vertices[i - 1]]], w.pos[d.d2s[side.disk_vertices[i]]]);
    const int mid = nearest_index(cum, 1, k - 2, cum.back() == 0 ? (k - 1) / 2.0 : cum.back() / 2);
    w.corner[d.d2s[side.disk_vertices[mid]]] = 1;
    ++st.extra_corners;
    // The side in two at the new corner (a vertex on one free side only: one copy).
    OpenSide second{{side.disk_vertices.begin() + mid, side.disk_vertices.end()}, -1, side.loop};
    d.sides[longest].disk_vertices.resize(mid + 1);
    d.sides.insert(d.sides.begin() + longest + 1, std::move(second));
    for (OpenSide& o : d.sides)
      if (o.mate > longest) ++o.mate;
  }
  st.precondition_splits = precondition_pass(w, d);
  out.num_surface_faces = s_faces_first(w);
  d = build_disk(w);
  if (d.sides.size() < 4 || d.sides.size() % 2 != 0) internal("open cut: " + str(d.sides.size()) + " sides");
  // The result, the boundary rotated to start at sides[0]'s corner (bh[0] is a corner already).
  const TriMesh& m = w.rs.mesh;
  out.disk_triangles.resize(out.num_surface_faces);
  for (int f = 0; f < out.num_surface_faces; ++f)
    out.disk_triangles[f] = {d.wedge[3 * f], d.wedge[3 * f + 1], d.wedge[3 * f + 2]};
  out.disk_to_surface = d.d2s;
  for (int h : d.bh) out.boundary.push_back(d.wedge[h]);
  out.sides = std::move(d.sides);
  for (int j = 0; j < b; ++j) out.refined_loops.push_back(refined_loop(w, surface.boundary_loops[j][0]));
  st.vertices_after = m.num_vertices();
  st.faces_after = m.num_faces();
  st.disk_vertices = static_cast<int>(out.disk_to_surface.size());
  st.disk_faces = out.num_surface_faces;
  out.surface = std::move(w.rs);
  st.seconds_total = seconds_since(t_start);
  return out;
}

}  // namespace igm

namespace igm {

std::string check_open_cut(const SurfaceComponent& surface, const OpenCut& cut) {
  const RefinedSurface& rs = cut.surface;
  const TriMesh& m = rs.mesh;
  const int n = static_cast<int>(surface.positions.size());
  const int b = static_cast<int>(surface.boundary_loops.size());
  const int nin = n + b, nv = m.num_vertices(), nf = m.num_faces(), nsf = cut.num_surface_faces;
  auto is_center = [&](int v) { return v >= n && v < nin; };
  // The refined S'.
  if (rs.num_input_vertices != nin) return "the surface has " + str(rs.num_input_vertices) + " input vertices";
  if (static_cast<int>(rs.input_positions.size()) != nin) return "input positions: wrong count";
  for (int v = 0; v < n; ++v) {
    const Vec3d &p = rs.input_positions[v], &q = surface.positions[v];
    if (p.x != q.x || p.y != q.y || p.z != q.z) return "input vertex " + str(v) + " moved";
  }
  if (static_cast<int>(rs.constructed.size()) != nv - nin) return "constructed points out of step with the mesh";
  if (const std::string inv = m.check_invariants(); !inv.empty()) return "surface: " + inv;
  if (nv - m.num_edges() + nf != 2 - 2 * cut.genus) return "the filled surface's Euler characteristic is wrong";
  if (cut.genus != surface.genus || cut.boundary_loops != b) return "genus or loop count differs from the input";
  // Input faces of S': S's triangles, then the fans.
  std::vector<std::array<int, 3>> in_tris = surface.triangles;
  for (int j = 0; j < b; ++j) {
    const auto& L = surface.boundary_loops[j];
    for (std::size_t i = 0; i < L.size(); ++i) in_tris.push_back({L[(i + 1) % L.size()], L[i], n + j});
  }
  const int s_tris = static_cast<int>(surface.triangles.size());
  std::vector<std::pair<std::array<int, 3>, int>> by_corners;
  std::vector<std::pair<int, int>> in_edges;
  for (int f = 0; f < static_cast<int>(in_tris.size()); ++f) {
    std::array<int, 3> c = in_tris[f];
    for (int i = 0; i < 3; ++i) in_edges.push_back(std::minmax(c[i], c[(i + 1) % 3]));
    std::sort(c.begin(), c.end());
    by_corners.push_back({c, f});
  }
  std::sort(by_corners.begin(), by_corners.end());
  std::sort(in_edges.begin(), in_edges.end());
  for (int v = nin; v < nv; ++v) {
    const SurfacePoint& p = rs.constructed[v - nin];
    int k = 0;
    Rational sum = 0;
    for (; k < 3 && p.v[k] >= 0; ++k) {
      if (p.v[k] >= nin || sgn(p.w[k]) <= 0 || (k > 0 && p.v[k] <= p.v[k - 1]))
        return "vertex " + str(v) + ": support not ascending in-range ids with positive weights";
      sum += p.w[k];
    }
    for (int i = k; i < 3; ++i)
      if (p.v[i] != -1) return "vertex " + str(v) + ": a used slot after an unused one";
    if (sum != 1) return "vertex " + str(v) + ": weights do not sum to 1";
    if (k == 1) return "vertex " + str(v) + " lies on input vertex " + str(p.v[0]);
    if (k == 2 && !std::binary_search(in_edges.begin(), in_edges.end(), std::pair{p.v[0], p.v[1]}))
      return "vertex " + str(v) + ": support is not an input edge";
  }
  // Every face in one input face, positively oriented there, and the faces tiling each input face
  // exactly (the determinants of their barycentric coordinates sum to 1); S's faces first.
  std::vector<Rational> area(in_tris.size());
  auto weight = [](const SurfacePoint& p, int u) -> Rational {
    for (int i = 0; i < 3; ++i)
      if (p.v[i] == u) return p.w[i];
    return 0;
  };
  for (int f = 0; f < nf; ++f) {
    const auto c = m.face_vertices(f);
    std::array<SurfacePoint, 3> pt{rs.point(c[0]), rs.point(c[1]), rs.point(c[2])};
    std::array<int, 3> u{-1, -1, -1};
    int k = 0;
    for (const SurfacePoint& p : pt)
      for (int i = 0; i < 3 && p.v[i] >= 0; ++i)
        if (std::find(u.begin(), u.begin() + k, p.v[i]) == u.begin() + k) {
          if (k == 3) return "face " + str(f) + " spans more than one input face";
          u[k++] = p.v[i];
        }
    if (k != 3) return "face " + str(f) + " is flat (its corners lie on one input edge)";
    std::sort(u.begin(), u.end());
    const auto it = std::lower_bound(by_corners.begin(), by_corners.end(), std::pair{u, -1});
    if (it == by_corners.end() || it->first != u) return "face " + str(f) + " lies in no input face";
    const int F = it->second;
    if ((f < nsf) != (F < s_tris)) return "face " + str(f) + (f < nsf ? " is S's but lies in a fan" : " lies in S");
    Rational a[3][3];
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col < 3; ++col) a[r][col] = weight(pt[r], in_tris[F][col]);
    const Rational det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                         a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    if (sgn(det) <= 0) return "face " + str(f) + " is not positively oriented in its input face";
    area[F] += det;
  }
  for (std::size_t F = 0; F < area.size(); ++F)
    if (area[F] != 1) return "input face " + str(static_cast<long long>(F)) + " is not tiled exactly";
  // The disk.
  const int nd = static_cast<int>(cut.disk_to_surface.size());
  if (static_cast<int>(cut.disk_triangles.size()) != nsf) return "disk triangles: not one per S face";
  for (int x = 0; x < nd; ++x) {
    const int v = cut.disk_to_surface[x];
    if (v < 0 || v >= nv) return "disk vertex " + str(x) + " maps out of range";
    if (is_center(v)) return "disk vertex " + str(x) + " is a filled hole's center";
  }
  std::vector<char> used(nd, 0);
  std::vector<std::int64_t> directed;
  std::vector<std::array<int, 3>> corner;  // (disk vertex, next, previous) per corner
  for (int f = 0; f < nsf; ++f) {
    const auto& t = cut.disk_triangles[f];
    const auto c = m.face_vertices(f);
    for (int i = 0; i < 3; ++i) {
      if (t[i] < 0 || t[i] >= nd) return "disk triangle " + str(f) + " has a vertex out of range";
      if (cut.disk_to_surface[t[i]] != c[i]) return "disk triangle " + str(f) + " is not surface face " + str(f);
      used[t[i]] = 1;
      directed.push_back(std::int64_t(t[i]) * nd + t[(i + 1) % 3]);
      corner.push_back({t[i], t[(i + 1) % 3], t[(i + 2) % 3]});
    }
  }
  for (int x = 0; x < nd; ++x)
    if (!used[x]) return "disk vertex " + str(x) + " is in no triangle";
  std::sort(directed.begin(), directed.end());
  if (std::adjacent_find(directed.begin(), directed.end()) != directed.end()) return "a disk edge has two triangles on one side";
  auto has = [&](int p, int q) { return std::binary_search(directed.begin(), directed.end(), std::int64_t(p) * nd + q); };
  std::vector<std::int64_t> open;
  long long edges = 0;
  for (std::int64_t e : directed) {
    const int p = static_cast<int>(e / nd), q = static_cast<int>(e % nd);
    if (!has(q, p)) open.push_back(e), ++edges;
    else if (p < q) ++edges;
  }
  if (nd - edges + nsf != 1) return "the disk's Euler characteristic is " + str(nd - edges + nsf);
  const int nb = static_cast<int>(cut.boundary.size());
  std::vector<std::int64_t> cycle;
  std::vector<char> on_boundary(nd, 0);
  for (int i = 0; i < nb; ++i) {
    const int p = cut.boundary[i], q = cut.boundary[(i + 1) % nb];
    if (p < 0 || p >= nd || q < 0 || q >= nd) return "boundary vertex out of range";
    if (on_boundary[p]) return "the boundary passes disk vertex " + str(p) + " twice";
    on_boundary[p] = 1;
    cycle.push_back(std::int64_t(p) * nd + q);
  }
  std::sort(cycle.begin(), cycle.end());
  if (cycle != open) return "the disk's boundary edges are not the cycle `boundary`";
  // Each disk vertex one fan (a chain at a boundary vertex, a cycle inside); one component.
  std::sort(corner.begin(), corner.end());
  std::vector<int> comp(nd);
  for (int x = 0; x < nd; ++x) comp[x] = x;
  auto find = [&](int x) {
    while (comp[x] != x) x = comp[x] = comp[comp[x]];
    return x;
  };
  for (std::size_t i = 0; i < corner.size();) {
    std::size_t j = i;
    while (j < corner.size() && corner[j][0] == corner[i][0]) ++j;
    const int x = corner[i][0];
    auto succ = [&](int a) {  // the corner at x whose next is a: its previous, or -1
      for (std::size_t k = i; k < j; ++k)
        if (corner[k][1] == a) return corner[k][2];
      return -1;
    };
    int start = corner[i][1];
    if (on_boundary[x]) {
      start = -1;
      for (std::size_t k = i; k < j && start < 0; ++k) {
        bool is_target = false;
        for (std::size_t l = i; l < j; ++l) is_target = is_target || corner[l][2] == corner[k][1];
        if (!is_target) start = corner[k][1];
      }
      if (start < 0) return "boundary disk vertex " + str(x) + " has a closed fan";
    }
    std::size_t steps = 0;
    for (int a = start; steps <= j - i;) {
      const int c = succ(a);
      if (c < 0) break;
      ++steps;
      a = c;
      if (a == start) break;
    }
    if (steps != j - i) return "disk vertex " + str(x) + " has more than one fan";
    for (std::size_t k = i; k < j; ++k) comp[find(corner[k][1])] = find(x), comp[find(corner[k][2])] = find(x);
    i = j;
  }
  for (int x = 0; x < nd; ++x)
    if (find(x) != find(0)) return "the disk is not connected";
  // Sides: consecutive along the boundary, covering it; >= 4, even.
  const int ns = static_cast<int>(cut.sides.size());
  if (ns < 4 || ns % 2 != 0) return str(ns) + " sides: not even and >= 4";
  int at = 0;
  for (int s = 0; s < ns; ++s) {
    const auto& dv = cut.sides[s].disk_vertices;
    if (dv.size() < 2) return "side " + str(s) + " has fewer than 2 vertices";
    for (std::size_t i = 0; i < dv.size(); ++i)
      if (dv[i] != cut.boundary[(at + static_cast<int>(i)) % nb]) return "side " + str(s) + " does not follow the boundary";
    at += static_cast<int>(dv.size()) - 1;
  }
  if (at != nb) return "the sides do not cover the boundary once";
  // Glued sides: mates, the same surface vertices reversed, along S's interior edges. Free sides:
  // along S's boundary half-edges of their loop; together every such half-edge once.
  auto surface_he = [&](int p, int q) { return m.find_halfedge(cut.disk_to_surface[p], cut.disk_to_surface[q]); };
  std::vector<char> covered(m.num_halfedges(), 0);
  for (int s = 0; s < ns; ++s) {
    const OpenSide& side = cut.sides[s];
    const auto& dv = side.disk_vertices;
    if (side.mate >= 0) {
      if (side.loop != -1) return "glued side " + str(s) + " names a loop";
      if (side.mate >= ns || side.mate == s || cut.sides[side.mate].mate != s) return "side " + str(s) + ": bad mate";
      const auto& other = cut.sides[side.mate].disk_vertices;
      if (other.size() != dv.size()) return "side " + str(s) + " and its mate differ in length";
      for (std::size_t i = 0; i < dv.size(); ++i)
        if (cut.disk_to_surface[dv[i]] != cut.disk_to_surface[other[dv.size() - 1 - i]])
          return "side " + str(s) + " and its mate differ";
    } else if (side.loop < 0 || side.loop >= b) {
      return "free side " + str(s) + " names no loop";
    }
    for (std::size_t i = 0; i + 1 < dv.size(); ++i) {
      const int h = surface_he(dv[i], dv[i + 1]);
      if (h < 0) return "side " + str(s) + " steps along no surface edge";
      const int fl = TriMesh::face(h), fr = TriMesh::face(m.twin(h));
      if (side.mate >= 0 && (fl >= nsf || fr >= nsf)) return "glued side " + str(s) + " runs along a boundary";
      if (side.mate < 0) {
        const auto c = m.face_vertices(fr);
        if (fl >= nsf || fr < nsf || std::find(c.begin(), c.end(), n + side.loop) == c.end())
          return "free side " + str(s) + " leaves its loop";
        if (covered[h]) return "free side " + str(s) + " repeats a boundary edge";
        covered[h] = 1;
      }
    }
  }
  for (int h = 0; h < m.num_halfedges(); ++h)
    if (TriMesh::face(h) < nsf && TriMesh::face(m.twin(h)) >= nsf && !covered[h])
      return "boundary half-edge " + str(h) + " is on no free side";
  // Tutte's pre-conditions: no interior edge, and no triangle, within one side.
  std::vector<int> side_a(nd, -1), side_b(nd, -1);
  for (int s = 0; s < ns; ++s)
    for (int x : cut.sides[s].disk_vertices) {
      if (side_a[x] < 0 || side_a[x] == s) side_a[x] = s;
      else if (side_b[x] < 0 || side_b[x] == s) side_b[x] = s;
      else return "disk vertex " + str(x) + " lies on three sides";
    }
  auto on = [&](int x, int s) { return s >= 0 && (side_a[x] == s || side_b[x] == s); };
  for (std::int64_t e : directed) {
    const int p = static_cast<int>(e / nd), q = static_cast<int>(e % nd);
    if (p < q && has(q, p) && (on(q, side_a[p]) || on(q, side_b[p])))
      return "interior disk edge " + str(p) + "-" + str(q) + " joins two vertices of one side";
  }
  for (int f = 0; f < nsf; ++f) {
    const auto& t = cut.disk_triangles[f];
    for (int s : {side_a[t[0]], side_b[t[0]]})
      if (s >= 0 && on(t[1], s) && on(t[2], s)) return "disk triangle " + str(f) + " has three vertices on side " + str(s);
  }
  return "";
}

}  // namespace igm
