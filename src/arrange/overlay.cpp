#include "igm/arrange/overlay.h"

#include <algorithm>
#include <deque>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "igm/core/error.h"

namespace igm {

namespace {

std::string seg_name(int s) { return "segment " + std::to_string(s); }

// Input checks beyond PlanarAdjacency::build: positive triangles, every vertex used, one
// boundary loop turning left (or straight) everywhere and winding once, Euler characteristic 1.
void validate_disk(const PlanarTriangulation& m, const PlanarAdjacency& adj) {
  const int nv = static_cast<int>(m.positions.size());
  const int nf = static_cast<int>(m.triangles.size());
  if (nf == 0) throw Error(ErrorKind::NoFaces, "overlay: the triangulation has no triangles");
  for (int t = 0; t < nf; ++t) {
    const auto& T = m.triangles[t];
    if (orient2d(m.positions[T[0]], m.positions[T[1]], m.positions[T[2]]) != Sign::Positive)
      throw Error(ErrorKind::InvalidArgument, "overlay: triangle " + std::to_string(t) + " is not strictly counter-clockwise",
                  {t});
  }
  for (int v = 0; v < nv; ++v)
    if (adj.star_begin[v] == adj.star_begin[v + 1])
      throw Error(ErrorKind::InvalidArgument, "overlay: vertex " + std::to_string(v) + " is used by no triangle", {v});
  std::vector<int> next(nv, -1);
  int nb = 0, first = -1, ne2 = 0;
  for (int t = 0; t < nf; ++t)
    for (int i = 0; i < 3; ++i) {
      if (adj.neighbor[t][i] >= 0) {
        ++ne2;
        continue;
      }
      const int a = m.triangles[t][i], b = m.triangles[t][(i + 1) % 3];
      if (next[a] >= 0)
        throw Error(ErrorKind::NonManifoldVertex, "overlay: vertex " + std::to_string(a) + " is on the boundary twice", {a});
      next[a] = b;
      ++nb;
      first = a;
    }
  if (nb < 3) throw Error(ErrorKind::InvalidArgument, "overlay: the triangulation has no boundary (not a disk)");
  // Follow the loop; check left turns and count how often the edge direction enters the upper
  // half-plane (exact): a convex loop winding once does it exactly once.
  auto upper = [&](int a, int b) {
    const Sign sy = sign(Rational(m.positions[b].y - m.positions[a].y));
    return sy == Sign::Positive || (sy == Sign::Zero && sign(Rational(m.positions[b].x - m.positions[a].x)) == Sign::Positive);
  };
  int count = 0, entries = 0, v = first;
  do {  // bounded by nb steps (checked)
    const int w = next[v];
    if (w < 0) throw Error(ErrorKind::NonManifoldVertex, "overlay: the boundary is not a closed loop", {v});
    const int u = next[w];
    if (u < 0) throw Error(ErrorKind::NonManifoldVertex, "overlay: the boundary is not a closed loop", {w});
    if (orient2d(m.positions[v], m.positions[w], m.positions[u]) == Sign::Negative)
      throw Error(ErrorKind::InvalidArgument, "overlay: the boundary turns right at vertex " + std::to_string(w) +
                                                  " (the region is not convex)",
                  {w});
    if (!upper(v, w) && upper(w, u)) ++entries;
    v = w;
    if (++count > nb) break;
  } while (v != first);
  if (count != nb) throw Error(ErrorKind::InvalidArgument, "overlay: the boundary has more than one loop");
  if (entries != 1) throw Error(ErrorKind::InvalidArgument, "overlay: the boundary winds more than once");
  const long long edges = nb + (ne2 / 2);
  if (static_cast<long long>(nv) - edges + nf != 1)
    throw Error(ErrorKind::InvalidArgument, "overlay: the triangulation is not a disk (Euler characteristic != 1)");
}

// Retriangulates one input triangle with extra points on its edges and inside, and segment
// pieces as constraints. Works on local vertex indices; positions are global.
class LocalTriangulation {
 public:
  LocalTriangulation(const std::vector<Point2q>& positions, const std::array<int, 3>& corners) : P_(positions) {
    for (int c : corners) g_.push_back(c);
    tris_.push_back({0, 1, 2});
  }
  int add(int global) {
    g_.push_back(global);
    local_[global] = static_cast<int>(g_.size()) - 1;
    return static_cast<int>(g_.size()) - 1;
  }
  int local_of(int global) const {
    for (int i = 0; i < 3; ++i)
      if (g_[i] == global) return i;
    auto it = local_.find(global);
    if (it == local_.end()) throw Error(ErrorKind::Internal, "overlay: a segment piece ends at a point unknown to its triangle");
    return it->second;
  }
  const Point2q& pt(int l) const { return P_[g_[l]]; }

  // The triangle with directed edge a->b and the corner index of a, or -1. O(k).
  int find_directed(int a, int b, int* corner) const {
    for (std::size_t t = 0; t < tris_.size(); ++t)
      for (int i = 0; i < 3; ++i)
        if (tris_[t][i] == a && tris_[t][(i + 1) % 3] == b) {
          if (corner) *corner = i;
          return static_cast<int>(t);
        }
    return -1;
  }

  // A point strictly inside the input triangle: face split, or edge split if it lies on an edge.
  void insert_interior(int m) {
    for (std::size_t t = 0; t < tris_.size(); ++t) {
      const auto T = tris_[t];
      Sign o[3];
      bool out = false;
      for (int i = 0; i < 3 && !out; ++i) {
        o[i] = orient2d(pt(T[i]), pt(T[(i + 1) % 3]), pt(m));
        out = o[i] == Sign::Negative;
      }
      if (out) continue;
      int zero = -1, nzero = 0;
      for (int i = 0; i < 3; ++i)
        if (o[i] == Sign::Zero) zero = i, ++nzero;
      if (nzero == 0) {
        tris_[t] = {T[0], T[1], m};
        tris_.push_back({T[1], T[2], m});
        tris_.push_back({T[2], T[0], m});
        return;
      }
      if (nzero == 1) {
        split_edge(static_cast<int>(t), zero, m);
        return;
      }
      throw Error(ErrorKind::Internal, "overlay: an interior point coincides with a vertex");
    }
    throw Error(ErrorKind::Internal, "overlay: an interior point lies in no local triangle");
  }

  // Point `m`, strictly inside the boundary sub-edge u -> v (u, v consecutive among the inserted
  // points of an edge of the input triangle): splits the boundary triangle (u, v, o).
  void insert_boundary(int u, int v, int m) {
    int i = 0;
    const int t = find_directed(u, v, &i);
    if (t < 0) throw Error(ErrorKind::Internal, "overlay: lost a boundary edge");
    const int o = tris_[t][(i + 2) % 3];
    tris_[t] = {u, m, o};
    tris_.push_back({m, v, o});
  }

  // Makes the segment a-b an edge. Pre: a, b present; the open segment inside the triangle.
  void insert_constraint(int a, int b, int seg, std::map<std::pair<int, int>, int>& owner, std::size_t& flips) {
    const auto key = std::make_pair(std::min(g_[a], g_[b]), std::max(g_[a], g_[b]));
    if (find_directed(a, b, nullptr) >= 0 || find_directed(b, a, nullptr) >= 0) {
      claim(key, seg, owner);
      return;
    }
    const Point2q &pa = pt(a), &pb = pt(b);
    for (int w = 0; w < static_cast<int>(g_.size()); ++w) {
      if (w == a || w == b) continue;
      if (orient2d(pa, pb, pt(w)) == Sign::Zero && sign(dot(pt(w), pa, pb)) == Sign::Negative)
        throw Error(ErrorKind::InvalidArgument,
                    seg_name(seg) + " passes through the end point of another segment or overlaps it", {seg});
    }
    std::deque<std::pair<int, int>> queue;
    for (const auto& T : tris_)
      for (int i = 0; i < 3; ++i) {
        const int x = T[i], y = T[(i + 1) % 3];
        if (x > y || x == a || x == b || y == a || y == b) continue;
        if (crosses(a, b, x, y)) {
          auto it = owner.find(std::make_pair(std::min(g_[x], g_[y]), std::max(g_[x], g_[y])));
          if (it != owner.end())
            throw Error(ErrorKind::InvalidArgument, seg_name(seg) + " crosses " + seg_name(it->second), {seg, it->second});
          queue.emplace_back(x, y);
        }
      }
    // Sloan's flip loop: terminates because some crossing edge is always flippable; the bound
    // below is far above Sloan's O(k^2) and only guards against a bug.
    const std::size_t bound = 16 * (queue.size() + 4) * (queue.size() + 4) + 64;
    for (std::size_t iter = 0; !queue.empty(); ++iter) {
      if (iter > bound) throw Error(ErrorKind::Internal, "overlay: constrained edge insertion did not terminate", {seg});
      auto [x, y] = queue.front();
      queue.pop_front();
      int i1 = 0, i2 = 0;
      const int t1 = find_directed(x, y, &i1), t2 = find_directed(y, x, &i2);
      if (t1 < 0 || t2 < 0) throw Error(ErrorKind::Internal, "overlay: a crossed edge vanished");
      const int w1 = tris_[t1][(i1 + 2) % 3], w2 = tris_[t2][(i2 + 2) % 3];
      if (orient2d(pt(x), pt(w2), pt(w1)) == Sign::Positive && orient2d(pt(w2), pt(y), pt(w1)) == Sign::Positive) {
        tris_[t1] = {x, w2, w1};
        tris_[t2] = {w2, y, w1};
        ++flips;
        if (w1 != a && w1 != b && w2 != a && w2 != b && crosses(a, b, w1, w2)) queue.emplace_back(w1, w2);
      } else {
        queue.emplace_back(x, y);
      }
    }
    if (find_directed(a, b, nullptr) < 0 && find_directed(b, a, nullptr) < 0)
      throw Error(ErrorKind::Internal, "overlay: a segment piece is not an edge after flipping", {seg});
    claim(key, seg, owner);
  }

  void emit(int input_tri, std::vector<std::array<int, 3>>& out, std::vector<int>& out_input) const {
    for (const auto& T : tris_) {
      out.push_back({g_[T[0]], g_[T[1]], g_[T[2]]});
      out_input.push_back(input_tri);
    }
  }

 private:
  static void claim(const std::pair<int, int>& key, int seg, std::map<std::pair<int, int>, int>& owner) {
    auto [it, inserted] = owner.emplace(key, seg);
    if (!inserted && it->second != seg)
      throw Error(ErrorKind::InvalidArgument, seg_name(seg) + " overlaps " + seg_name(it->second), {seg, it->second});
  }
  // Do the open segments a-b and x-y cross at one interior point?
  bool crosses(int a, int b, int x, int y) const {
    const Sign s1 = orient2d(pt(a), pt(b), pt(x)), s2 = orient2d(pt(a), pt(b), pt(y));
    if (s1 == Sign::Zero || s2 == Sign::Zero || s1 == s2) return false;
    const Sign s3 = orient2d(pt(x), pt(y), pt(a)), s4 = orient2d(pt(x), pt(y), pt(b));
    return s3 != Sign::Zero && s4 != Sign::Zero && s3 != s4;
  }
  void split_edge(int t, int k, int m) {
    const auto T = tris_[t];
    const int a = T[k], b = T[(k + 1) % 3], c = T[(k + 2) % 3];
    int j = 0;
    const int u = find_directed(b, a, &j);
    if (u < 0) throw Error(ErrorKind::Internal, "overlay: an interior point lies on the input triangle's boundary");
    const int d = tris_[u][(j + 2) % 3];
    tris_[t] = {a, m, c};
    tris_.push_back({m, b, c});
    tris_[u] = {b, m, d};
    tris_.push_back({m, a, d});
  }

  const std::vector<Point2q>& P_;
  std::vector<int> g_;
  std::map<int, int> local_;
  std::vector<std::array<int, 3>> tris_;
};

// Triangulates a convex polygon whose vertices (counter-clockwise, global ids) may include
// points in the interior of its sides, with strictly positive triangles only: clips a strictly
// convex corner whose removal leaves at least three strictly convex corners. O(m^2) ints, O(m)
// orientations for m vertices.
void triangulate_convex(const std::vector<Point2q>& P, std::vector<int> poly, std::vector<std::array<int, 3>>& out) {
  std::vector<char> convex(poly.size());
  auto flag = [&](std::size_t i) {
    const std::size_t m = poly.size();
    convex[i] = orient2d(P[poly[(i + m - 1) % m]], P[poly[i]], P[poly[(i + 1) % m]]) == Sign::Positive;
  };
  for (std::size_t i = 0; i < poly.size(); ++i) flag(i);
  while (poly.size() > 3) {  // bounded: one vertex removed per iteration
    const std::size_t m = poly.size();
    std::size_t corners = 0;
    for (char c : convex) corners += c;
    std::size_t pick = m;
    for (std::size_t i = 0; i < m && pick == m; ++i)
      if (convex[i] && (corners >= 4 || !(convex[(i + m - 1) % m] && convex[(i + 1) % m]))) pick = i;
    if (pick == m) throw Error(ErrorKind::Internal, "overlay: a cell is not a convex polygon");
    out.push_back({poly[(pick + m - 1) % m], poly[pick], poly[(pick + 1) % m]});
    poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(pick));
    convex.erase(convex.begin() + static_cast<std::ptrdiff_t>(pick));
    const std::size_t n = poly.size();
    flag((pick + n - 1) % n);
    flag(pick % n);
  }
  if (orient2d(P[poly[0]], P[poly[1]], P[poly[2]]) != Sign::Positive)
    throw Error(ErrorKind::Internal, "overlay: a cell triangle is not positive");
  out.push_back({poly[0], poly[1], poly[2]});
}

struct AlongPiece {
  int edge;
  Rational t0, t1;
  int seg;
};

}  // namespace

OverlayResult overlay_segments(const PlanarTriangulation& mesh, const std::vector<Segment2>& segments,
                               const OverlayOptions& options) {
  const int nv = static_cast<int>(mesh.positions.size());
  const int nf = static_cast<int>(mesh.triangles.size());
  const auto& tris = mesh.triangles;
  const PlanarAdjacency adj = PlanarAdjacency::build(nv, tris);
  if (options.validate_input) validate_disk(mesh, adj);
  if (nf == 0) throw Error(ErrorKind::NoFaces, "overlay: the triangulation has no triangles");

  // Undirected edge ids; canonical direction lo -> hi (vertex ids).
  std::vector<std::array<int, 3>> edge_id(nf, {-1, -1, -1});
  std::vector<std::array<int, 2>> edge_ends;
  for (int t = 0; t < nf; ++t)
    for (int i = 0; i < 3; ++i) {
      if (edge_id[t][i] >= 0) continue;
      const int a = tris[t][i], b = tris[t][(i + 1) % 3];
      edge_id[t][i] = static_cast<int>(edge_ends.size());
      if (adj.neighbor[t][i] >= 0) edge_id[adj.neighbor[t][i]][adj.neighbor_edge[t][i]] = edge_id[t][i];
      edge_ends.push_back({std::min(a, b), std::max(a, b)});
    }
  const int ne = static_cast<int>(edge_ends.size());

  OverlayResult res;
  std::vector<Point2q>& P = res.mesh.positions;
  P = mesh.positions;
  res.origin.resize(nv);
  for (int v = 0; v < nv; ++v) res.origin[v].input_vertex = v;
  std::vector<std::vector<std::pair<Rational, int>>> edge_points(ne);
  std::vector<std::vector<int>> interior_points(nf);
  struct Piece {
    int a, b, seg;
  };
  std::vector<std::vector<Piece>> pieces(nf);
  std::vector<AlongPiece> along;
  std::vector<Rational> tau;      // per new vertex on an input edge: its parameter (lo -> hi)
  std::vector<int> tau_edge;      // per new vertex: its input edge or -1

  auto new_vertex = [&](const Point2q& x, int tri, std::array<Rational, 3> bary, int edge, const Rational& t) {
    P.push_back(x);
    VertexOrigin o;
    o.input_triangle = tri;
    o.barycentric = std::move(bary);
    res.origin.push_back(std::move(o));
    tau.push_back(t);
    tau_edge.push_back(edge);
    return static_cast<int>(P.size()) - 1;
  };
  // A new vertex at parameter t on edge i of triangle tri.
  auto edge_vertex = [&](int tri, int i, const Rational& t) {
    const int e = edge_id[tri][i];
    const int lo = edge_ends[e][0], hi = edge_ends[e][1];
    Point2q x{P[lo].x + t * (P[hi].x - P[lo].x), P[lo].y + t * (P[hi].y - P[lo].y)};
    std::array<Rational, 3> bary{0, 0, 0};
    const bool fwd = tris[tri][i] == lo;
    bary[i] = fwd ? Rational(1 - t) : t;
    bary[(i + 1) % 3] = fwd ? t : Rational(1 - t);
    const int id = new_vertex(x, tri, bary, e, t);
    edge_points[e].emplace_back(t, id);
    return id;
  };
  auto param_of_vertex = [&](int v, int e) { return Rational(v == edge_ends[e][0] ? 0 : 1); };

  // 1. Locate the distinct endpoints.
  std::map<Point2q, std::pair<int, PlanarLocation>, Point2qLess> endpoints;
  int from = tris[0][0];
  for (std::size_t s = 0; s < segments.size(); ++s) {
    if (same_point(segments[s].a, segments[s].b))
      throw Error(ErrorKind::InvalidArgument, seg_name(static_cast<int>(s)) + " has zero length", {static_cast<int>(s)});
    for (const Point2q* p : {&segments[s].a, &segments[s].b}) {
      if (endpoints.count(*p)) continue;
      PlanarLocation loc;
      try {
        loc = locate_point(P, tris, adj, from, *p);
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::InvalidArgument) throw;
        throw Error(ErrorKind::InvalidArgument, "an end point of " + seg_name(static_cast<int>(s)) + " lies outside the polygon",
                    {static_cast<int>(s)});
      }
      int id = -1;
      const auto& T = tris[loc.triangle];
      if (loc.kind == PlanarLocation::Kind::Vertex) {
        id = T[loc.index];
      } else if (loc.kind == PlanarLocation::Kind::Edge) {
        const int e = edge_id[loc.triangle][loc.index];
        const Point2q &lo = P[edge_ends[e][0]], &hi = P[edge_ends[e][1]];
        Rational t = dot(lo, *p, hi) / dot(lo, hi, hi);
        id = edge_vertex(loc.triangle, loc.index, t);
        ++res.stats.endpoint_vertices;
      } else {
        const Point2q &A = P[T[0]], &B = P[T[1]], &C = P[T[2]];
        const Rational area = cross(A, B, C);
        std::array<Rational, 3> bary{cross(*p, B, C) / area, cross(A, *p, C) / area, cross(A, B, *p) / area};
        id = new_vertex(*p, loc.triangle, bary, -1, Rational(0));
        interior_points[loc.triangle].push_back(id);
        ++res.stats.endpoint_vertices;
      }
      endpoints.emplace(*p, std::make_pair(id, loc));
      from = T[0];
    }
  }

  // The cap (OverlayOptions::max_triangles): each new point adds at least one output triangle (an
  // interior point two, a boundary point one, by Euler's formula for a triangulated polygon).
  auto check_cap = [&](std::size_t triangles_at_least, const char* when) {
    if (options.max_triangles > 0 && triangles_at_least > options.max_triangles)
      throw Error(ErrorKind::Unsupported, "overlay: the arrangement would have " + std::string(when) +
                                              std::to_string(triangles_at_least) + " triangles, more than max_triangles = " +
                                              std::to_string(options.max_triangles));
  };
  auto new_points = [&] { return tris.size() + res.stats.endpoint_vertices + res.stats.crossings; };
  check_cap(new_points(), "at least ");

  // 2. Walk every segment through the (unchanged) input triangulation.
  res.chains.resize(segments.size());
  std::vector<WalkStep> steps;
  for (std::size_t si = 0; si < segments.size(); ++si) {
    const int s = static_cast<int>(si);
    const auto& [ida, loca] = endpoints.at(segments[s].a);
    const int idb = endpoints.at(segments[s].b).first;
    steps.clear();
    walk_segment(P, tris, adj, loca, segments[s].a, segments[s].b, &steps);
    auto& chain = res.chains[s];
    chain.push_back(ida);
    const Point2q d{segments[s].b.x - segments[s].a.x, segments[s].b.y - segments[s].a.y};
    for (const WalkStep& st : steps) {
      int nxt = -1;
      if (st.next == WalkStep::Next::Vertex) {
        nxt = st.vertex;
      } else if (st.next == WalkStep::Next::End) {
        nxt = idb;
      } else {
        const int e = edge_id[st.cross_triangle][st.cross_edge];
        const Point2q &lo = P[edge_ends[e][0]], &hi = P[edge_ends[e][1]];
        // lo + t (hi - lo) on the line a + u d:  t = d x (a - lo) / d x (hi - lo)
        Rational num = d.x * (segments[s].a.y - lo.y);
        num -= d.y * (segments[s].a.x - lo.x);
        Rational den = d.x * (hi.y - lo.y);
        den -= d.y * (hi.x - lo.x);
        nxt = edge_vertex(st.cross_triangle, st.cross_edge, Rational(num / den));
        ++res.stats.crossings;
        check_cap(new_points(), "at least ");
      }
      const int cur = chain.back();
      if (st.medium == WalkStep::Medium::Face) {
        pieces[st.triangle].push_back({cur, nxt, s});
      } else {
        const int e = edge_id[st.triangle][st.edge];
        auto param = [&](int v) { return v < nv ? param_of_vertex(v, e) : tau[v - nv]; };
        if (cur >= nv && tau_edge[cur - nv] != e) throw Error(ErrorKind::Internal, "overlay: along-edge piece off its edge");
        if (nxt >= nv && tau_edge[nxt - nv] != e) throw Error(ErrorKind::Internal, "overlay: along-edge piece off its edge");
        along.push_back({e, param(cur), param(nxt), s});
      }
      chain.push_back(nxt);
    }
    if (chain.back() != idb) throw Error(ErrorKind::Internal, "overlay: a walk did not end at its segment's end point", {s});
  }

  {  // A segment may pass through an input vertex only if no other segment meets that vertex.
    std::map<int, int> passes;
    std::set<int> ends;
    for (const auto& [pt, v] : endpoints) ends.insert(v.first);
    for (std::size_t s = 0; s < res.chains.size(); ++s)
      for (std::size_t k = 1; k + 1 < res.chains[s].size(); ++k) {
        const int v = res.chains[s][k];
        if (v >= nv) continue;
        auto [it, fresh] = passes.emplace(v, static_cast<int>(s));
        if (!fresh || ends.count(v))
          throw Error(ErrorKind::InvalidArgument,
                      seg_name(static_cast<int>(s)) + " meets another segment at vertex " + std::to_string(v) +
                          ", which is not an end point of both",
                      {static_cast<int>(s), v});
      }
  }

  // 3. Order the points of every input edge; equal parameters mean two segments meet off
  // their end points on that edge.
  auto point_segment = [&](int id) {
    for (std::size_t s = 0; s < res.chains.size(); ++s)
      if (std::find(res.chains[s].begin(), res.chains[s].end(), id) != res.chains[s].end()) return static_cast<int>(s);
    return -1;
  };
  for (int e = 0; e < ne; ++e) {
    auto& L = edge_points[e];
    if (L.size() < 2) continue;
    std::sort(L.begin(), L.end(), [](const auto& x, const auto& y) { return cmp(x.first, y.first) < 0; });
    for (std::size_t k = 1; k < L.size(); ++k)
      if (L[k].first == L[k - 1].first) {
        const int s1 = point_segment(L[k - 1].second), s2 = point_segment(L[k].second);
        throw Error(ErrorKind::InvalidArgument,
                    seg_name(s1) + " and " + seg_name(s2) + " meet at a point that is not an end point of both", {s1, s2});
      }
  }
  {  // Pieces along input edges: no other point strictly inside, no two overlapping.
    std::sort(along.begin(), along.end(), [](const AlongPiece& x, const AlongPiece& y) {
      if (x.edge != y.edge) return x.edge < y.edge;
      return cmp(std::min(x.t0, x.t1), std::min(y.t0, y.t1)) < 0;
    });
    for (std::size_t k = 0; k < along.size(); ++k) {
      const AlongPiece& A = along[k];
      const Rational lo = std::min(A.t0, A.t1), hi = std::max(A.t0, A.t1);
      const auto& L = edge_points[A.edge];
      auto it = std::upper_bound(L.begin(), L.end(), lo, [](const Rational& v, const auto& x) { return cmp(v, x.first) < 0; });
      if (it != L.end() && cmp(it->first, hi) < 0) {
        const int other = point_segment(it->second);
        throw Error(ErrorKind::InvalidArgument, seg_name(A.seg) + " meets " + seg_name(other) + " off their end points",
                    {A.seg, other});
      }
      if (k + 1 < along.size() && along[k + 1].edge == A.edge &&
          cmp(std::min(along[k + 1].t0, along[k + 1].t1), hi) < 0)
        throw Error(ErrorKind::InvalidArgument, seg_name(A.seg) + " overlaps " + seg_name(along[k + 1].seg),
                    {A.seg, along[k + 1].seg});
    }
  }

  // 4. Retriangulate every input triangle that received points or pieces.
  auto& out = res.mesh.triangles;
  out.reserve(tris.size() + 4 * res.stats.crossings);
  res.input_triangle.reserve(out.capacity());
  std::map<std::pair<int, int>, int> owner;  // global edge -> segment, inside the current triangle
  for (int t = 0; t < nf; ++t) {
    const auto& T = tris[t];
    bool touched = !interior_points[t].empty() || !pieces[t].empty();
    for (int i = 0; i < 3 && !touched; ++i) touched = !edge_points[edge_id[t][i]].empty();
    if (!touched) {
      out.push_back(T);
      res.input_triangle.push_back(t);
      continue;
    }
    ++res.stats.split_triangles;
    std::size_t k = interior_points[t].size();
    for (int i = 0; i < 3; ++i) k += edge_points[edge_id[t][i]].size();
    res.stats.max_local_points = std::max(res.stats.max_local_points, k);
    res.stats.max_local_pieces = std::max(res.stats.max_local_pieces, pieces[t].size());
    if (interior_points[t].empty()) {
      // Only chords between boundary points: they cut T into convex cells. Split the boundary
      // polygon along each chord (the unique cell holding both ends), then triangulate cells.
      std::vector<std::vector<int>> cells(1);
      for (int i = 0; i < 3; ++i) {
        cells[0].push_back(T[i]);
        const int e = edge_id[t][i];
        const auto& L = edge_points[e];
        const int n = static_cast<int>(L.size());
        for (int r = 0; r < n; ++r) cells[0].push_back(L[T[i] == edge_ends[e][0] ? r : n - 1 - r].second);
      }
      for (const Piece& pc : pieces[t]) {
        std::size_t found = cells.size(), ia = 0, ib = 0;
        for (std::size_t c = 0; c < cells.size() && found == cells.size(); ++c) {
          const auto& C = cells[c];
          auto pa = std::find(C.begin(), C.end(), pc.a);
          if (pa == C.end()) continue;
          auto pb = std::find(C.begin(), C.end(), pc.b);
          if (pb == C.end()) continue;
          found = c, ia = static_cast<std::size_t>(pa - C.begin()), ib = static_cast<std::size_t>(pb - C.begin());
        }
        if (found == cells.size()) {
          // The chord's ends lie in no common cell: it crosses an earlier chord.
          const int other = pieces[t].front().seg == pc.seg ? pieces[t].back().seg : pieces[t].front().seg;
          throw Error(ErrorKind::InvalidArgument, seg_name(pc.seg) + " crosses another segment (e.g. " + seg_name(other) + ")",
                      {pc.seg, other});
        }
        std::vector<int> C = std::move(cells[found]);
        const std::size_t m = C.size();
        if ((ia + 1) % m == ib || (ib + 1) % m == ia)
          throw Error(ErrorKind::InvalidArgument, seg_name(pc.seg) + " overlaps another segment", {pc.seg});
        std::vector<int> c1, c2;
        for (std::size_t j = ia;; j = (j + 1) % m) {  // bounded by m steps
          c1.push_back(C[j]);
          if (j == ib) break;
        }
        for (std::size_t j = ib;; j = (j + 1) % m) {
          c2.push_back(C[j]);
          if (j == ia) break;
        }
        cells[found] = std::move(c1);
        cells.push_back(std::move(c2));
      }
      const std::size_t before = out.size();
      for (const auto& C : cells) triangulate_convex(P, C, out);
      res.input_triangle.resize(out.size(), t);
      (void)before;
      continue;
    }
    LocalTriangulation lt(P, T);
    for (int id : interior_points[t]) lt.insert_interior(lt.add(id));
    // Edge points, most-used piece end points first: a point that many pieces leave (the
    // template centre on an input edge) is then joined to the later points by the splits
    // themselves, so its pieces need no flips. Each edge keeps its inserted points ordered.
    std::map<int, int> degree;
    for (const Piece& pc : pieces[t]) ++degree[pc.a], ++degree[pc.b];
    struct Pending {
      int deg, edge, rank, id;
    };
    std::vector<Pending> pending;
    std::array<std::vector<int>, 3> ordered;  // per edge of T: local ids in order from corner i
    for (int i = 0; i < 3; ++i) {
      const int e = edge_id[t][i];
      const auto& L = edge_points[e];
      const int n = static_cast<int>(L.size());
      for (int r = 0; r < n; ++r) {
        const int id = L[T[i] == edge_ends[e][0] ? r : n - 1 - r].second;
        ordered[i].push_back(lt.add(id));
        auto it = degree.find(id);
        pending.push_back({it == degree.end() ? 0 : it->second, i, r, id});
      }
    }
    std::stable_sort(pending.begin(), pending.end(), [](const Pending& x, const Pending& y) { return x.deg > y.deg; });
    std::array<std::set<int>, 3> done;  // inserted ranks per edge
    for (const Pending& pd : pending) {
      auto& D = done[pd.edge];
      auto hi = D.upper_bound(pd.rank);
      const int v = hi == D.end() ? (pd.edge + 1) % 3 : ordered[pd.edge][*hi];
      const int u = hi == D.begin() ? pd.edge : ordered[pd.edge][*std::prev(hi)];
      lt.insert_boundary(u, v, ordered[pd.edge][pd.rank]);
      D.insert(pd.rank);
    }
    owner.clear();
    for (const Piece& pc : pieces[t]) lt.insert_constraint(lt.local_of(pc.a), lt.local_of(pc.b), pc.seg, owner, res.stats.local_flips);
    lt.emit(t, out, res.input_triangle);
  }
  check_cap(out.size(), "");
  for (const Point2q& x : P) res.stats.max_coordinate_bits = std::max({res.stats.max_coordinate_bits, bit_size(x.x), bit_size(x.y)});
  return res;
}

InputPoint to_input(const PlanarTriangulation& input, const OverlayResult& r, int t, const std::array<Rational, 3>& b) {
  if (t < 0 || t >= static_cast<int>(r.mesh.triangles.size()))
    throw Error(ErrorKind::InvalidArgument, "to_input: no output triangle " + std::to_string(t), {t});
  const auto& T = r.mesh.triangles[t];
  Point2q x{0, 0};
  for (int i = 0; i < 3; ++i) {
    x.x += b[i] * r.mesh.positions[T[i]].x;
    x.y += b[i] * r.mesh.positions[T[i]].y;
  }
  InputPoint out;
  out.input_triangle = r.input_triangle[t];
  const auto& I = input.triangles[out.input_triangle];
  const Point2q &A = input.positions[I[0]], &B = input.positions[I[1]], &C = input.positions[I[2]];
  const Rational area = cross(A, B, C);
  out.barycentric = {cross(x, B, C) / area, cross(A, x, C) / area, cross(A, B, x) / area};
  return out;
}

std::string check_overlay(const PlanarTriangulation& input, const std::vector<Segment2>& segments,
                          const OverlayResult& r) {
  const auto& P = r.mesh.positions;
  const auto& F = r.mesh.triangles;
  const int nv = static_cast<int>(P.size()), nf = static_cast<int>(F.size());
  const int nv_in = static_cast<int>(input.positions.size());
  if (nv < nv_in) return "fewer output than input vertices";
  for (int v = 0; v < nv_in; ++v)
    if (!same_point(P[v], input.positions[v])) return "input vertex " + std::to_string(v) + " moved";
  if (static_cast<int>(r.input_triangle.size()) != nf || static_cast<int>(r.origin.size()) != nv) return "array sizes";
  PlanarAdjacency adj;
  try {
    adj = PlanarAdjacency::build(nv, F);
  } catch (const Error& e) {
    return std::string("output not manifold: ") + e.what();
  }
  Rational area_out = 0, area_in = 0;
  for (int t = 0; t < nf; ++t) {
    const auto& T = F[t];
    const Rational a = cross(P[T[0]], P[T[1]], P[T[2]]);
    if (sign(a) != Sign::Positive) return "output triangle " + std::to_string(t) + " is not strictly positive";
    area_out += a;
    const int it = r.input_triangle[t];
    if (it < 0 || it >= static_cast<int>(input.triangles.size())) return "bad input triangle id";
    const auto& I = input.triangles[it];
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < 3; ++i)
        if (orient2d(input.positions[I[i]], input.positions[I[(i + 1) % 3]], P[T[c]]) == Sign::Negative)
          return "output triangle " + std::to_string(t) + " leaves its input triangle " + std::to_string(it);
  }
  for (const auto& I : input.triangles) area_in += cross(input.positions[I[0]], input.positions[I[1]], input.positions[I[2]]);
  if (area_in != area_out) return "total area changed";
  int used = 0, boundary = 0, interior2 = 0;
  for (int v = 0; v < nv; ++v) used += adj.star_begin[v] != adj.star_begin[v + 1];
  for (int t = 0; t < nf; ++t)
    for (int i = 0; i < 3; ++i) (adj.neighbor[t][i] < 0 ? boundary : interior2) += 1;
  if (used != nv) return "an output vertex is used by no triangle";
  if (nv - (boundary + interior2 / 2) + nf != 1) return "Euler characteristic is not 1";
  for (int v = 0; v < nv; ++v) {
    const VertexOrigin& o = r.origin[v];
    if (v < nv_in) {
      if (o.input_vertex != v) return "input vertex " + std::to_string(v) + " has a wrong origin";
      continue;
    }
    if (o.input_vertex >= 0 || o.input_triangle < 0 || o.input_triangle >= static_cast<int>(input.triangles.size()))
      return "vertex " + std::to_string(v) + " has no origin";
    const auto& I = input.triangles[o.input_triangle];
    Rational x = 0, y = 0, s = 0;
    for (int i = 0; i < 3; ++i) {
      if (sign(o.barycentric[i]) == Sign::Negative) return "vertex " + std::to_string(v) + " has a negative barycentric";
      x += o.barycentric[i] * input.positions[I[i]].x;
      y += o.barycentric[i] * input.positions[I[i]].y;
      s += o.barycentric[i];
    }
    if (s != 1 || x != P[v].x || y != P[v].y) return "origin of vertex " + std::to_string(v) + " does not give its position";
  }
  if (r.chains.size() != segments.size()) return "one chain per segment expected";
  std::set<std::pair<int, int>> edges;
  for (const auto& T : F)
    for (int i = 0; i < 3; ++i) edges.emplace(std::min(T[i], T[(i + 1) % 3]), std::max(T[i], T[(i + 1) % 3]));
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const auto& c = r.chains[s];
    const std::string name = "chain of segment " + std::to_string(s);
    if (c.size() < 2 || !same_point(P[c.front()], segments[s].a) || !same_point(P[c.back()], segments[s].b))
      return name + " does not join the segment's end points";
    for (std::size_t k = 0; k + 1 < c.size(); ++k) {
      if (!edges.count({std::min(c[k], c[k + 1]), std::max(c[k], c[k + 1])})) return name + " uses a non-edge";
      if (orient2d(segments[s].a, segments[s].b, P[c[k + 1]]) != Sign::Zero) return name + " leaves the segment";
      if (sign(dot(P[c[k]], P[c[k + 1]], segments[s].b)) != Sign::Positive)
        return name + " is not monotone";
    }
  }
  return {};
}

}  // namespace igm
