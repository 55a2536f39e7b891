#include "normal_form.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "igm/core/union_find.h"
#include "igm/core/weight_sort.h"
#include "igm/topology/tighten_loops.h"

namespace igm::topology_internal {

bool canonical_crosses(CutResult& res, const std::vector<Vec3d>& unit, bool hops, long vertex_limit, DetachPlan& plan,
                       const std::atomic<long>* rival) {
  const int root = res.root, genus = res.genus;
  RefinedSurface& rs = res.surface;
  std::vector<Vec3d> pos(unit.begin(), unit.begin() + rs.num_input_vertices);
  auto extend = [&](const RefinedSurface& S, std::vector<Vec3d>& p) { extend_positions(S, unit, p); };
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
    return [&P, first_mid, hops](int a, int b) { return search_length(P, first_mid, hops, a, b); };
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

}  // namespace igm::topology_internal
