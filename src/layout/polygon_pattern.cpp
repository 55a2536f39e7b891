#include "igm/layout/polygon_pattern.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "igm/mesh/surface_point.h"

namespace igm {

namespace {

std::string str(std::int64_t x) { return std::to_string(x); }

std::uint64_t dkey(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}
std::uint64_t ukey(int a, int b) { return a < b ? dkey(a, b) : dkey(b, a); }

int use_start(const SurfaceLayout& L, const ArcUse& u) {
  const auto& vs = L.arcs[u.arc].vertices;
  return u.forward ? vs.front() : vs.back();
}
int use_end(const SurfaceLayout& L, const ArcUse& u) {
  const auto& vs = L.arcs[u.arc].vertices;
  return u.forward ? vs.back() : vs.front();
}

// A run of arc uses walked in order: its vertices (joints once) and, per edge, the arc and the
// smaller of its two positions in the arc's vertex list.
struct Walk {
  std::vector<int> vertices;
  std::vector<int> edge_arc;
  std::vector<std::size_t> edge_low;
};

Walk walk(const SurfaceLayout& L, const std::vector<ArcUse>& uses) {
  Walk w;
  for (const ArcUse& u : uses) {
    const auto& vs = L.arcs[u.arc].vertices;
    const std::size_t n = vs.size();
    if (w.vertices.empty()) w.vertices.push_back(u.forward ? vs.front() : vs.back());
    for (std::size_t i = 1; i < n; ++i) {
      w.vertices.push_back(u.forward ? vs[i] : vs[n - 1 - i]);
      w.edge_arc.push_back(u.arc);
      w.edge_low.push_back(u.forward ? i - 1 : n - 1 - i);
    }
  }
  return w;
}

double distance(const Vec3d& a, const Vec3d& b) {
  const double x = a.x - b.x, y = a.y - b.y, z = a.z - b.z;
  return std::sqrt(x * x + y * y + z * z);
}

// Per vertex of a walk, the 3D length along it from its start (doubles: only the choice of a
// middle depends on them).
std::vector<double> lengths_along(const SurfaceLayout& L, const Walk& w) {
  std::vector<double> acc(w.vertices.size(), 0.0);
  for (std::size_t i = 1; i < w.vertices.size(); ++i)
    acc[i] = acc[i - 1] + distance(L.positions[w.vertices[i - 1]], L.positions[w.vertices[i]]);
  return acc;
}

// A side's arc uses cut where a use ends at node m (not its last use): before and after m. False
// when no use ends there.
bool cut_side_at(const SurfaceLayout& L, const std::vector<ArcUse>& side, int m, std::vector<ArcUse>& before,
                 std::vector<ArcUse>& after) {
  for (std::size_t i = 0; i + 1 < side.size(); ++i)
    if (use_end(L, side[i]) == m) {
      before.assign(side.begin(), side.begin() + static_cast<std::ptrdiff_t>(i + 1));
      after.assign(side.begin() + static_cast<std::ptrdiff_t>(i + 1), side.end());
      return true;
    }
  return false;
}

// Unit-capacity max flow by breadth-first augmenting paths (Edmonds-Karp).
class UnitFlow {
 public:
  explicit UnitFlow(int n) : g_(static_cast<std::size_t>(n)) {}
  void add(int u, int v) {
    g_[u].push_back({v, 1, static_cast<int>(g_[v].size()), true});
    g_[v].push_back({u, 0, static_cast<int>(g_[u].size()) - 1, false});
  }
  // One augmenting path from s to t; false when there is none. O(nodes + edges).
  bool augment(int s, int t) {
    const std::size_t n = g_.size();
    std::vector<std::pair<int, int>> parent(n, {-1, -1});
    std::deque<int> queue{s};
    parent[s] = {s, -1};
    while (!queue.empty() && parent[t].first < 0) {
      const int u = queue.front();
      queue.pop_front();
      for (int e = 0; e < static_cast<int>(g_[u].size()); ++e) {
        const Edge& ed = g_[u][e];
        if (ed.cap > 0 && parent[ed.to].first < 0) parent[ed.to] = {u, e}, queue.push_back(ed.to);
      }
    }
    if (parent[t].first < 0) return false;
    for (int v = t; v != s;) {
      const auto [u, e] = parent[v];
      Edge& ed = g_[u][e];
      --ed.cap;
      ++g_[v][ed.rev].cap;
      v = u;
    }
    return true;
  }
  // The next node along a saturated original edge out of u, or -1.
  int flow_next(int u) const {
    for (const Edge& ed : g_[u])
      if (ed.original && ed.cap == 0) return ed.to;
    return -1;
  }
  // Every node u's saturated original edges, for following several paths out of the source.
  std::vector<int> flow_all(int u) const {
    std::vector<int> out;
    for (const Edge& ed : g_[u])
      if (ed.original && ed.cap == 0) out.push_back(ed.to);
    return out;
  }

 private:
  struct Edge {
    int to, cap, rev;
    bool original;
  };
  std::vector<std::vector<Edge>> g_;
};

class Filler {
  // The patch's triangles, boundary vertices (on its sides' arcs) and interior edges.
  struct Region {
    std::vector<int> tris;
    std::vector<int> local;                  // local id -> vertex
    std::unordered_map<int, int> id;         // vertex -> local id
    std::vector<char> boundary;              // per local id
    std::vector<std::vector<int>> adjacent;  // per local id, across interior edges (local ids)
    std::vector<std::array<int, 2>> interior_edges;  // vertex pairs, in order of first meeting
  };
 public:
  Filler(SurfaceLayout& L, std::vector<PolygonPatch>& polys, const PolygonPatternOptions& o, PolygonPatternStats& st)
      : L_(L), polys_(polys), opt_(o), st_(st),
        input_positions_(L.positions.begin(), L.positions.begin() + std::min<std::size_t>(L.positions.size(), L.num_input_vertices)) {}

  std::string fill(std::size_t index) {
    const int p = polys_[index].patch;
    const std::string name = "patch " + str(p);
    const int k = static_cast<int>(polys_[index].sides.size());
    if (k < 3 || k > 6) return name + ": " + str(k) + " sides (the pattern takes 3 to 6)";
    for (const auto& side : polys_[index].sides)
      if (side.empty()) return name + ": an empty side";
    // 1. A node in the middle of every side.
    std::vector<int> mid(k, -1);
    for (int s = 0; s < k; ++s)
      if (std::string e = middle_node(index, s, mid[s]); !e.empty()) return name + ": " + e;
    // 2. Room for k disjoint paths from a centre, refining the patch's triangles where needed.
    std::vector<std::vector<int>> paths;
    for (int round = 0;; ++round) {
      const Region R = region(polys_[index]);
      const std::string e = find_paths(R, mid, paths);
      if (e.empty()) break;
      if (round >= opt_.max_refine_rounds)
        return name + ": " + e + " after " + str(round) + " refinement rounds";
      refine(p, R);
      ++st_.refine_rounds;
    }
    // 3. The k patches.
    const PolygonPatch& poly = polys_[index];
    std::vector<std::vector<ArcUse>> first(k), second(k);
    for (int s = 0; s < k; ++s)
      if (!cut_side_at(L_, poly.sides[s], mid[s], first[s], second[s]))
        return name + ": side " + str(s) + " has no arc end at its middle node";
    std::vector<int> path_arc(k);
    for (int s = 0; s < k; ++s) {
      path_arc[s] = static_cast<int>(L_.arcs.size());
      LayoutArc a;
      a.vertices = paths[s];
      L_.arcs.push_back(std::move(a));
    }
    std::vector<int> ids(k, p);
    for (int j = 1; j < k; ++j) {
      ids[j] = static_cast<int>(L_.patches.size());
      L_.patches.emplace_back();
    }
    std::vector<int> barrier_arcs = path_arc;
    for (const auto& side : poly.sides)
      for (const ArcUse& u : side) barrier_arcs.push_back(u.arc);
    std::vector<std::array<int, 2>> seeds;
    for (int j = 0; j < k; ++j) {
      const Walk w = walk(L_, first[j]);
      seeds.push_back({w.vertices[0], w.vertices[1]});
    }
    if (std::string e = assign_parts(p, seeds, ids, barrier_arcs); !e.empty()) return name + ": " + e;
    for (int j = 0; j < k; ++j) {
      const int prev = (j + k - 1) % k;
      LayoutPatch& P = L_.patches[ids[j]];
      P.sides[0] = first[j];
      P.sides[1] = {ArcUse{path_arc[j], false}};
      P.sides[2] = {ArcUse{path_arc[prev], true}};
      P.sides[3] = second[prev];
    }
    ++st_.patterns;
    return "";
  }

  // Cuts polygon `index`, which has one reflex corner, by a path from it to the middle of a side
  // (fill_polygon_patches' contract); each part becomes a four-sided patch or a new polygon.
  std::string split_reflex(std::size_t index) {
    const int p = polys_[index].patch;
    const std::string name = "patch " + str(p);
    const int k = static_cast<int>(polys_[index].sides.size());
    if (static_cast<int>(polys_[index].turns.size()) != k) return name + ": " + str(k) + " sides but " +
        str(static_cast<std::int64_t>(polys_[index].turns.size())) + " corner turns";
    int r = -1, reflex = 0;
    for (int s = 0; s < k; ++s) {
      if (polys_[index].sides[s].empty()) return name + ": an empty side";
      const int t = polys_[index].turns[s];
      if (t == 3) ++reflex, r = s;
      else if (t != 1) return name + ": a corner of " + str(t) + " quarter turns";
    }
    if (reflex != 1) return name + ": " + str(reflex) + " reflex corners (a cut takes one)";
    {
      PolygonPatch& P = polys_[index];
      std::rotate(P.sides.begin(), P.sides.begin() + r, P.sides.end());
      std::rotate(P.turns.begin(), P.turns.begin() + r, P.turns.end());
    }
    const int rv = use_start(L_, polys_[index].sides[0].front());
    // The side to cut to and which part keeps r as a corner (x = 1: the part before the side).
    int best_s = -1, best_x = 0, best_score = 0;
    double best_d = 0;
    for (int s = 2; s <= k - 2; ++s) {
      const Walk w = walk(L_, polys_[index].sides[s]);
      const std::vector<double> acc = lengths_along(L_, w);
      const double len = acc.back();
      std::size_t mid_i = 0;
      for (std::size_t i = 0; i < w.vertices.size(); ++i)
        if (std::abs(acc[i] - len / 2) < std::abs(acc[mid_i] - len / 2)) mid_i = i;
      const double d = distance(L_.positions[rv], L_.positions[w.vertices[mid_i]]);
      for (int x = 1; x <= 2; ++x) {
        const int na = s + 1 + (x == 1), nb = k - s + (x == 2);
        if (na < 3 || na > 6 || nb < 3 || nb > 6) continue;
        const int score = (na != 4) + (nb != 4);
        if (best_s < 0 || score < best_score || (score == best_score && d < best_d))
          best_s = s, best_x = x, best_score = score, best_d = d;
      }
    }
    if (best_s < 0) return name + ": no side to cut to from its reflex corner (" + str(k) + " sides)";
    const int s = best_s, x = best_x;
    int m = -1;
    if (std::string e = middle_node(index, s, m); !e.empty()) return name + ": " + e;
    std::vector<int> path;
    for (int round = 0;; ++round) {
      const Region R = region(polys_[index]);
      if (const auto it = R.id.find(rv); it == R.id.end()) return name + ": its reflex corner is off the patch";
      int met = 0;
      for (const auto& side : polys_[index].sides) {
        const Walk w = walk(L_, side);
        for (std::size_t i = 0; i + 1 < w.vertices.size(); ++i) met += w.vertices[i] == rv;
      }
      if (met != 1) return name + ": its reflex corner is met " + str(met) + " times on its boundary";
      path = interior_path(R, rv, m);
      if (!path.empty()) break;
      if (round >= opt_.max_refine_rounds)
        return name + ": no path from its reflex corner to side " + str(s) + " after " + str(round) + " refinement rounds";
      refine(p, R);
      ++st_.refine_rounds;
    }
    const PolygonPatch& P = polys_[index];
    std::vector<ArcUse> first, second;
    if (!cut_side_at(L_, P.sides[s], m, first, second))
      return name + ": side " + str(s) + " has no arc end at its middle node";
    const int pa = static_cast<int>(L_.arcs.size());
    {
      LayoutArc a;
      a.vertices = path;
      L_.arcs.push_back(std::move(a));
    }
    // The two parts as runs of arc uses, each flagged when it starts at a corner of the part.
    std::vector<std::vector<ArcUse>> runs_a, runs_b;
    std::vector<char> corner_a, corner_b;
    for (int i = 0; i < s; ++i) runs_a.push_back(P.sides[i]), corner_a.push_back(i == 0 ? x == 1 : 1);
    runs_a.push_back(first), corner_a.push_back(1);
    runs_a.push_back({ArcUse{pa, false}}), corner_a.push_back(1);
    runs_b.push_back(second), corner_b.push_back(1);
    for (int i = s + 1; i < k; ++i) runs_b.push_back(P.sides[i]), corner_b.push_back(1);
    runs_b.push_back({ArcUse{pa, true}}), corner_b.push_back(x == 2);
    const std::vector<std::vector<ArcUse>> sides_a = sides_from_runs(runs_a, corner_a), sides_b = sides_from_runs(runs_b, corner_b);
    std::vector<int> barrier_arcs{pa};
    for (const auto& side : P.sides)
      for (const ArcUse& u : side) barrier_arcs.push_back(u.arc);
    const Walk wa = walk(L_, P.sides[0]), wb = walk(L_, second);
    const int id_b = static_cast<int>(L_.patches.size());
    L_.patches.emplace_back();
    if (std::string e = assign_parts(p, {{{wa.vertices[0], wa.vertices[1]}, {wb.vertices[0], wb.vertices[1]}}}, {p, id_b},
                                     barrier_arcs);
        !e.empty())
      return name + ": " + e;
    std::vector<PolygonPatch> more;
    for (const auto& [id, sides] : {std::pair{p, sides_a}, std::pair{id_b, sides_b}}) {
      if (sides.size() == 4) {
        for (int i = 0; i < 4; ++i) L_.patches[id].sides[i] = sides[i];
      } else {
        more.push_back({id, sides, {}});
      }
    }
    ++st_.reflex_cuts;
    for (PolygonPatch& q : more) polys_.push_back(std::move(q));
    return "";
  }

 private:
  int add_vertex(SurfacePoint p) {
    L_.positions.push_back(evaluate(p, input_positions_));
    L_.locations.push_back(std::move(p));
    ++st_.added_vertices;
    return static_cast<int>(L_.locations.size()) - 1;
  }

  void add_triangle(const std::array<int, 3>& t, int patch) {
    L_.triangles.push_back(t);
    L_.triangle_patch.push_back(patch);
  }

  // Cuts arc a in two at its vertex `at` (0 < at < size - 1); every use of a in every patch and
  // polygon becomes the two pieces in walking order.
  void split_arc(int a, std::size_t at) {
    LayoutArc b;
    b.vertices.assign(L_.arcs[a].vertices.begin() + static_cast<std::ptrdiff_t>(at), L_.arcs[a].vertices.end());
    b.patch = L_.arcs[a].patch;
    L_.arcs[a].vertices.resize(at + 1);
    const int nb = static_cast<int>(L_.arcs.size());
    L_.arcs.push_back(std::move(b));
    auto fix = [&](std::vector<ArcUse>& side) {
      std::vector<ArcUse> out;
      out.reserve(side.size() + 1);
      for (const ArcUse& u : side) {
        if (u.arc != a) {
          out.push_back(u);
        } else if (u.forward) {
          out.push_back({a, true});
          out.push_back({nb, true});
        } else {
          out.push_back({nb, false});
          out.push_back({a, false});
        }
      }
      side = std::move(out);
    };
    for (LayoutPatch& P : L_.patches)
      for (auto& side : P.sides) fix(side);
    for (PolygonPatch& poly : polys_)
      for (auto& side : poly.sides) fix(side);
    ++st_.split_arcs;
  }

  // Splits the surface edge between positions low and low + 1 of arc a at its exact midpoint, in
  // both triangles beside it; the new vertex enters the arc. Returns it.
  int split_edge(int a, std::size_t low) {
    const int x = L_.arcs[a].vertices[low], y = L_.arcs[a].vertices[low + 1];
    const int m = add_vertex(lerp(L_.locations[x], L_.locations[y], Rational(1, 2)));
    const std::size_t nt = L_.triangles.size();
    for (std::size_t t = 0; t < nt; ++t) {
      const std::array<int, 3> tri = L_.triangles[t];
      for (int c = 0; c < 3; ++c) {
        const int u = tri[c], v = tri[(c + 1) % 3], w = tri[(c + 2) % 3];
        if ((u == x && v == y) || (u == y && v == x)) {
          L_.triangles[t] = {u, m, w};
          add_triangle({m, v, w}, L_.triangle_patch[t]);
          break;
        }
      }
    }
    L_.arcs[a].vertices.insert(L_.arcs[a].vertices.begin() + static_cast<std::ptrdiff_t>(low + 1), m);
    ++st_.split_edges;
    return m;
  }

  // Sides of a part: consecutive runs joined from each run flagged as starting at a corner.
  static std::vector<std::vector<ArcUse>> sides_from_runs(const std::vector<std::vector<ArcUse>>& runs,
                                                           const std::vector<char>& corner) {
    std::vector<std::vector<ArcUse>> sides;
    const std::size_t n = runs.size();
    std::size_t start = n;
    for (std::size_t i = 0; i < n && start == n; ++i)
      if (corner[i]) start = i;
    if (start == n) return sides;
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t i = (start + j) % n;
      if (corner[i]) sides.emplace_back();
      sides.back().insert(sides.back().end(), runs[i].begin(), runs[i].end());
    }
    return sides;
  }

  // The triangles of patch p flood-filled into parts across edges on none of `barrier_arcs`,
  // part j from the triangle left of directed edge seeds[j] and given patch ids[j]; then the
  // barrier arcs' patches on each side from the triangles along them. "" or why the parts do
  // not tile the patch.
  std::string assign_parts(int p, const std::vector<std::array<int, 2>>& seeds, const std::vector<int>& ids,
                           const std::vector<int>& barrier_arcs) {
    std::unordered_set<std::uint64_t> barrier;
    for (int a : barrier_arcs) {
      const auto& vs = L_.arcs[a].vertices;
      for (std::size_t i = 0; i + 1 < vs.size(); ++i) barrier.insert(ukey(vs[i], vs[i + 1]));
    }
    std::vector<int> tris;
    for (int t = 0; t < static_cast<int>(L_.triangles.size()); ++t)
      if (L_.triangle_patch[t] == p) tris.push_back(t);
    std::unordered_map<std::uint64_t, int> by_edge;
    for (int t : tris)
      for (int c = 0; c < 3; ++c) by_edge[dkey(L_.triangles[t][c], L_.triangles[t][(c + 1) % 3])] = t;
    std::unordered_map<int, int> part;  // triangle -> j
    for (std::size_t j = 0; j < seeds.size(); ++j) {
      const auto it = by_edge.find(dkey(seeds[j][0], seeds[j][1]));
      if (it == by_edge.end()) return "part " + str(static_cast<std::int64_t>(j)) + "'s first side has no triangle of the patch on its left";
      if (part.count(it->second)) return "the cut does not separate part " + str(static_cast<std::int64_t>(j));
      std::vector<int> stack{it->second};
      part[it->second] = static_cast<int>(j);
      while (!stack.empty()) {
        const int t = stack.back();
        stack.pop_back();
        for (int c = 0; c < 3; ++c) {
          const int u = L_.triangles[t][c], v = L_.triangles[t][(c + 1) % 3];
          if (barrier.count(ukey(u, v))) continue;
          const auto nb = by_edge.find(dkey(v, u));
          if (nb == by_edge.end()) continue;
          const auto seen = part.find(nb->second);
          if (seen == part.end()) {
            part[nb->second] = static_cast<int>(j);
            stack.push_back(nb->second);
          } else if (seen->second != static_cast<int>(j)) {
            return "the cut does not separate parts " + str(seen->second) + " and " + str(static_cast<std::int64_t>(j));
          }
        }
      }
    }
    if (part.size() != tris.size())
      return str(static_cast<std::int64_t>(tris.size() - part.size())) + " triangles in no part";
    for (int t : tris) L_.triangle_patch[t] = ids[part[t]];
    for (int a : barrier_arcs) {
      LayoutArc& A = L_.arcs[a];
      const auto f = by_edge.find(dkey(A.vertices[0], A.vertices[1]));
      if (f != by_edge.end()) A.patch[0] = L_.triangle_patch[f->second];
      const auto b = by_edge.find(dkey(A.vertices[1], A.vertices[0]));
      if (b != by_edge.end()) A.patch[1] = L_.triangle_patch[b->second];
    }
    return "";
  }

  // A shortest path (hops) from boundary vertex `from` to boundary vertex `to` across the region's
  // interior edges through interior vertices only; empty if none. O(region).
  static std::vector<int> interior_path(const Region& R, int from, int to) {
    const auto fi = R.id.find(from), ti = R.id.find(to);
    if (fi == R.id.end() || ti == R.id.end()) return {};
    const int s = fi->second, t = ti->second;
    std::vector<int> parent(R.local.size(), -1);
    std::deque<int> queue{s};
    parent[s] = s;
    while (!queue.empty() && parent[t] < 0) {
      const int u = queue.front();
      queue.pop_front();
      for (int v : R.adjacent[u])
        if (parent[v] < 0 && (v == t || !R.boundary[v])) parent[v] = u, queue.push_back(v);
    }
    if (parent[t] < 0) return {};
    std::vector<int> path;
    for (int v = t; v != s; v = parent[v]) path.push_back(R.local[v]);
    path.push_back(R.local[s]);
    std::reverse(path.begin(), path.end());
    return path;
  }

  // Makes a node near the middle of side s of polygon `index`; sets m.
  std::string middle_node(std::size_t index, int s, int& m) {
    const int p = polys_[index].patch;
    std::unordered_map<int, int> count;  // how often each vertex is met walking the boundary
    for (const auto& side : polys_[index].sides) {
      const Walk w = walk(L_, side);
      for (std::size_t i = 0; i + 1 < w.vertices.size(); ++i) ++count[w.vertices[i]];
    }
    const Walk w = walk(L_, polys_[index].sides[s]);
    const std::size_t n = w.vertices.size();
    const std::vector<double> acc = lengths_along(L_, w);
    const double half = acc[n - 1] / 2;
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i + 1 < n; ++i)
      if (count[w.vertices[i]] == 1 && std::abs(acc[i] - half) < best_d) best_d = std::abs(acc[i] - half), best = i;
    int arc = -1;
    std::size_t at = 0;
    if (best == 0) {
      // No such vertex: split the edge whose midpoint is nearest the middle (not a slit: the patch
      // on one side only).
      std::size_t e_best = n;
      for (std::size_t e = 0; e + 1 < n; ++e) {
        const LayoutArc& A = L_.arcs[w.edge_arc[e]];
        if (A.patch[0] == p && A.patch[1] == p) continue;
        const double d = std::abs((acc[e] + acc[e + 1]) / 2 - half);
        if (e_best == n || d < best_d) best_d = d, e_best = e;
      }
      if (e_best == n) return "side " + str(s) + " runs along slits only";
      arc = w.edge_arc[e_best];
      split_edge(arc, w.edge_low[e_best]);
      at = w.edge_low[e_best] + 1;
      m = L_.arcs[arc].vertices[at];
    } else {
      m = w.vertices[best];
      // The arc through it: the one of the edge before it, unless m ends that arc.
      arc = w.edge_arc[best - 1];
      const auto& vs = L_.arcs[arc].vertices;
      if (vs.front() == m || vs.back() == m) return "";  // already a node
      at = static_cast<std::size_t>(std::find(vs.begin() + 1, vs.end() - 1, m) - vs.begin());
    }
    split_arc(arc, at);
    return "";
  }

  Region region(const PolygonPatch& poly) const {
    Region R;
    std::unordered_set<std::uint64_t> arc_edges;
    std::unordered_set<int> on_boundary;
    for (const auto& side : poly.sides)
      for (const ArcUse& u : side) {
        const auto& vs = L_.arcs[u.arc].vertices;
        for (std::size_t i = 0; i < vs.size(); ++i) {
          on_boundary.insert(vs[i]);
          if (i + 1 < vs.size()) arc_edges.insert(ukey(vs[i], vs[i + 1]));
        }
      }
    for (int t = 0; t < static_cast<int>(L_.triangles.size()); ++t) {
      if (L_.triangle_patch[t] != poly.patch) continue;
      R.tris.push_back(t);
      for (int v : L_.triangles[t])
        if (R.id.emplace(v, static_cast<int>(R.local.size())).second) {
          R.local.push_back(v);
          R.boundary.push_back(on_boundary.count(v) ? 1 : 0);
        }
    }
    R.adjacent.resize(R.local.size());
    std::unordered_set<std::uint64_t> seen;
    for (int t : R.tris)
      for (int c = 0; c < 3; ++c) {
        const int u = L_.triangles[t][c], v = L_.triangles[t][(c + 1) % 3];
        const std::uint64_t key = ukey(u, v);
        if (arc_edges.count(key) || !seen.insert(key).second) continue;
        R.interior_edges.push_back({u, v});
        R.adjacent[R.id[u]].push_back(R.id[v]);
        R.adjacent[R.id[v]].push_back(R.id[u]);
      }
    return R;
  }

  // k disjoint paths from a centre to the middle nodes, through interior vertices; "" or why not.
  std::string find_paths(const Region& R, const std::vector<int>& mid, std::vector<std::vector<int>>& paths) const {
    const int k = static_cast<int>(mid.size());
    const int n = static_cast<int>(R.local.size());
    std::vector<int> sink_of(n, -1), mid_local(k);
    for (int s = 0; s < k; ++s) {
      const auto it = R.id.find(mid[s]);
      if (it == R.id.end()) return "side " + str(s) + "'s middle node is off the patch";
      mid_local[s] = it->second;
      sink_of[it->second] = s;
    }
    // Hop distances from every middle node through interior vertices.
    constexpr int kFar = std::numeric_limits<int>::max();
    std::vector<std::vector<int>> dist(k, std::vector<int>(n, kFar));
    for (int s = 0; s < k; ++s) {
      std::deque<int> queue;
      dist[s][mid_local[s]] = 0;
      queue.push_back(mid_local[s]);
      while (!queue.empty()) {
        const int u = queue.front();
        queue.pop_front();
        for (int v : R.adjacent[u])
          if (!R.boundary[v] && dist[s][v] == kFar) dist[s][v] = dist[s][u] + 1, queue.push_back(v);
      }
    }
    int centre = -1;
    std::int64_t best_max = 0, best_sum = 0;
    for (int v = 0; v < n; ++v) {
      if (R.boundary[v]) continue;
      std::int64_t mx = 0, sum = 0;
      bool all = true;
      for (int s = 0; s < k && all; ++s) {
        if (dist[s][v] == kFar) all = false;
        else mx = std::max<std::int64_t>(mx, dist[s][v]), sum += dist[s][v];
      }
      if (!all) continue;
      if (centre < 0 || mx < best_max || (mx == best_max && (sum < best_sum || (sum == best_sum && R.local[v] < R.local[centre]))))
        centre = v, best_max = mx, best_sum = sum;
    }
    if (centre < 0) return "no interior vertex reaches every side's middle";
    // Nodes: interior vertex v -> in 2v, out 2v + 1; middle node s -> 2n + s; sink 2n + k.
    UnitFlow flow(2 * n + k + 1);
    const int sink = 2 * n + k;
    for (int v = 0; v < n; ++v)
      if (!R.boundary[v] && v != centre) flow.add(2 * v, 2 * v + 1);
    for (const auto& [a, b] : R.interior_edges) {
      const int u = R.id.at(a), v = R.id.at(b);
      for (const auto& [x, y] : {std::pair<int, int>{u, v}, std::pair<int, int>{v, u}}) {
        if (R.boundary[x]) continue;
        if (!R.boundary[y]) {
          if (y != centre) flow.add(2 * x + 1, 2 * y);
        } else if (sink_of[y] >= 0) {
          flow.add(2 * x + 1, 2 * n + sink_of[y]);
        }
      }
    }
    for (int s = 0; s < k; ++s) flow.add(2 * n + s, sink);
    int found = 0;
    while (found < k && flow.augment(2 * centre + 1, sink)) ++found;
    if (found < k) return "room for " + str(found) + " of " + str(k) + " disjoint paths";
    paths.assign(k, {});
    for (int first : flow.flow_all(2 * centre + 1)) {
      std::vector<int> path{R.local[centre]};
      int x = first;
      for (int guard = 0; guard <= 2 * n + k && x < 2 * n; ++guard) {
        path.push_back(R.local[x / 2]);
        x = flow.flow_next(2 * (x / 2) + 1);
        if (x < 0) return "a path of the flow breaks off";
      }
      if (x < 2 * n || x >= 2 * n + k) return "a path of the flow does not end at a middle node";
      const int s = x - 2 * n;
      path.push_back(mid[s]);
      paths[s] = std::move(path);
    }
    for (int s = 0; s < k; ++s)
      if (paths[s].empty()) return "no path to side " + str(s);
    return "";
  }

  // One refinement round of patch p's triangles (R: its region, as region() gives it): centroid splits where it has no interior
  // vertex, else the exact midpoint of every interior edge (red-green: 2, 3 or 4 triangles per
  // triangle with 1, 2 or 3 split edges). Only the patch's triangles change.
  void refine(int p, const Region& R) {
    const bool any_interior = std::find(R.boundary.begin(), R.boundary.end(), 0) != R.boundary.end();
    if (!any_interior || R.interior_edges.empty()) {
      for (int t : R.tris) {
        const std::array<int, 3> tri = L_.triangles[t];
        const Rational third(1, 3);
        const int g = add_vertex(barycentric_point(L_.locations[tri[0]], L_.locations[tri[1]], L_.locations[tri[2]],
                                                   {third, third, third}));
        L_.triangles[t] = {tri[0], tri[1], g};
        add_triangle({tri[1], tri[2], g}, p);
        add_triangle({tri[2], tri[0], g}, p);
      }
      return;
    }
    std::unordered_map<std::uint64_t, int> midpoint;
    for (const auto& [a, b] : R.interior_edges)
      midpoint[ukey(a, b)] = add_vertex(lerp(L_.locations[a], L_.locations[b], Rational(1, 2)));
    for (int t : R.tris) {
      const std::array<int, 3> v = L_.triangles[t];
      std::array<int, 3> m{-1, -1, -1};  // m[i] on edge v[i] v[i+1]
      int splits = 0;
      for (int i = 0; i < 3; ++i) {
        const auto it = midpoint.find(ukey(v[i], v[(i + 1) % 3]));
        if (it != midpoint.end()) m[i] = it->second, ++splits;
      }
      if (splits == 1) {
        const int i = m[0] >= 0 ? 0 : (m[1] >= 0 ? 1 : 2);
        L_.triangles[t] = {v[i], m[i], v[(i + 2) % 3]};
        add_triangle({m[i], v[(i + 1) % 3], v[(i + 2) % 3]}, p);
      } else if (splits == 2) {
        const int i = m[0] < 0 ? 0 : (m[1] < 0 ? 1 : 2);  // the edge left whole
        const int a = v[(i + 1) % 3], b = v[(i + 2) % 3], c = v[i];
        const int m1 = m[(i + 1) % 3], m2 = m[(i + 2) % 3];  // on a-b and b-c
        L_.triangles[t] = {m1, b, m2};
        add_triangle({a, m1, m2}, p);
        add_triangle({a, m2, c}, p);
      } else if (splits == 3) {
        L_.triangles[t] = {v[0], m[0], m[2]};
        add_triangle({m[0], v[1], m[1]}, p);
        add_triangle({m[2], m[1], v[2]}, p);
        add_triangle({m[0], m[1], m[2]}, p);
      }
    }
  }

  SurfaceLayout& L_;
  std::vector<PolygonPatch>& polys_;
  const PolygonPatternOptions& opt_;
  PolygonPatternStats& st_;
  std::vector<Vec3d> input_positions_;
};

}  // namespace

std::string fill_polygon_patches(SurfaceLayout& layout, const std::vector<PolygonPatch>& polygons,
                                 const PolygonPatternOptions& options, PolygonPatternStats* stats) {
  PolygonPatternStats local;
  PolygonPatternStats& st = stats ? *stats : local;
  if (layout.positions.size() != layout.locations.size() ||
      layout.triangle_patch.size() != layout.triangles.size())
    return "the layout's positions or triangle patches do not match its sizes";
  std::vector<PolygonPatch> polys = polygons;
  for (const PolygonPatch& poly : polys)
    if (poly.patch < 0 || poly.patch >= static_cast<int>(layout.patches.size()))
      return "polygon patch " + str(poly.patch) + " is not a patch of the layout";
  Filler filler(layout, polys, options, st);
  // A cut polygon may append its parts (without reflex corners): at most twice the input's count.
  for (std::size_t i = 0; i < polys.size(); ++i) {
    const bool reflex = std::find(polys[i].turns.begin(), polys[i].turns.end(), 3) != polys[i].turns.end();
    if (std::string e = reflex ? filler.split_reflex(i) : filler.fill(i); !e.empty()) return e;
  }
  if (std::string e = check_surface_layout(layout); !e.empty()) return "the pattern broke the layout: " + e;
  return "";
}

}  // namespace igm
