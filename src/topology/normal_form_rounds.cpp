#include "normal_form.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "igm/core/union_find.h"
#include "igm/core/weight_sort.h"

namespace igm::topology_internal {

bool canonical_rounds(CutResult& res, const std::vector<Vec3d>& unit, bool hops, long vertex_limit, DetachPlan& plan,
                      const std::vector<double>* penalty, const std::atomic<long>* rival) {
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
    const int nv = M.num_vertices(), nh = M.num_halfedges();
    auto len = [&](int a, int b) {
      const double base = search_length(P, first_mid, hops, a, b);
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

}  // namespace igm::topology_internal
