#include "detach.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "igm/core/union_find.h"
#include "igm/core/weight_sort.h"

namespace igm::topology_internal {

namespace {

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

// v's exact point without a copy: a constructed vertex's own, an input vertex's (weight 1) set in
// `scratch` (its limbs reused).
const SurfacePoint& point_of(const RefinedSurface& rs, int v, SurfacePoint& scratch) {
  if (v >= rs.num_input_vertices) return rs.constructed[v - rs.num_input_vertices];
  scratch.v = {v, -1, -1};
  scratch.w[0] = 1, scratch.w[1] = 0, scratch.w[2] = 0;
  return scratch;
}

}  // namespace

DetachPlan plan_detach(const TriMesh& mesh, const std::vector<Vec3d>& positions, int root, int genus, bool hops,
                       const std::vector<double>* penalty) {
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

void raise_penalties(const DetachPlan& p, int nv0, double raise, std::vector<double>& penalty) {
  for (int x = 0; x < nv0; ++x)  // input vertices only (band splits and chord splits come after them)
    if (x != p.root && p.pruned[x] && !p.is_leaf[x]) {
      const int k = p.max_leaf[x] - p.min_leaf[x] + 1;
      if (k > 1) penalty[x] += raise * (k - 1);
    }
}

double metric_unit(const TriMesh& mesh, const std::vector<Vec3d>& unit, bool hops) {
  if (hops) return 1.0;
  double sum = 0;
  for (int h = 0; h < mesh.num_halfedges(); ++h) sum += length(unit[mesh.origin(h)], unit[mesh.target(h)]);
  return sum / mesh.num_halfedges();
}

void check_congestion_step(double step) {
  if (!(step > 0) || !std::isfinite(step))
    throw Error(ErrorKind::InvalidArgument, "CutOptions::congestion_step must be finite and > 0, got " + std::to_string(step));
}

int congestion_budget(const CutOptions& options, const TriMesh& mesh, long per_faces, long least,
                      long most) {
  if (options.congestion_rounds >= 0) return options.congestion_rounds;
  return static_cast<int>(std::clamp(per_faces / std::max(1, mesh.num_faces()), least, most));
}

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

std::size_t fewest_drawn(const std::vector<const DetachPlan*>& plans, const std::vector<Vec3d>& positions,
                         bool parallel, DrawnPlan* winner) {
  long fewest = -1;
  std::size_t win = 0;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    DetachPlan copy = *plans[i];
    copy.rs.input_positions = positions;
    DrawnPlan d;
    std::vector<std::vector<int>> loops = realize_strands(copy, d.drawing, parallel);
    d.tightened = tighten_loops(std::move(copy.rs), std::move(loops), copy.root);
    const long drawn = d.tightened.surface.mesh.num_vertices();
    if (fewest < 0 || drawn < fewest) {
      fewest = drawn, win = i;
      if (winner) *winner = std::move(d);
    }
  }
  return win;
}

}  // namespace igm::topology_internal
