// Step 3c of the topology stage: the normal form by handle slides drawn on the surface
// (normal_form.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "igm/topology/tighten_loops.h"
#include "normal_form.h"

namespace igm::topology_internal {

namespace {

int wrap(int a, int n) { return ((a % n) + n) % n; }

// A step's candidates are ranked by their vertices plus their loops' vertices over this: the
// fewest vertices alone is myopic, since long loops are walls that make the later slides long
// (generated genus 12 on 12k faces: 10.5k vertices against 7.4k; bench/README.md, step 3c).
constexpr long kLoopVerticesPerVertex = 4;
// How many of a step's candidates, so ranked after their first slide, get their second.
constexpr std::size_t kSlideFinalists = 6;

// The half-edges out of the root in ccw order from its stored one, and the loop ends among them:
// ends[k] = (loop, whether it is the loop's last edge), at[k] = its index in he. O(valence log g).
struct RootRotation {
  std::vector<int> he;
  std::vector<Letter> ends;
  std::vector<int> at;
};
RootRotation root_rotation(const TriMesh& M, int root, const std::vector<std::vector<int>>& loops) {
  std::vector<std::pair<int, Letter>> by_vertex;  // the vertex after (or before) the root on each loop
  for (int i = 0; i < static_cast<int>(loops.size()); ++i) {
    if (loops[i].size() < 3 || loops[i][0] != root)
      internal("slides: loop " + std::to_string(i) + " is not a cycle from the root");
    by_vertex.push_back({loops[i][1], Letter{i, false}});
    by_vertex.push_back({loops[i].back(), Letter{i, true}});
  }
  std::sort(by_vertex.begin(), by_vertex.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  RootRotation R;
  const int h0 = M.vertex_halfedge(root);
  int h = h0;
  do {  // valence(root) steps
    const int t = M.target(h);
    auto it = std::lower_bound(by_vertex.begin(), by_vertex.end(), t, [](const auto& a, int v) { return a.first < v; });
    for (; it != by_vertex.end() && it->first == t; ++it) {
      R.ends.push_back(it->second);
      R.at.push_back(static_cast<int>(R.he.size()));
    }
    R.he.push_back(h);
    h = M.next_around_origin(h);
  } while (h != h0);
  if (R.ends.size() != by_vertex.size()) internal("slides: a loop's end is not beside the root");
  return R;
}

// The start in R.ends from which trace_word reads w, or -1. O(m^2 log m) for m ends.
int start_reading(const RootRotation& R, const Word& w, std::vector<int>& departures) {
  for (int s = 0; s < static_cast<int>(R.ends.size()); ++s)
    if (trace_word(R.ends, s, &departures) == w) return s;
  return -1;
}

// Per loop: whether it is in a commutator block of w (mark_blocks from nothing marked). O(|w|).
std::vector<char> loops_in_blocks(const Word& w) {
  std::vector<char> done(w.size() / 2, 0);
  mark_blocks(w, done);
  return done;
}

// The moves redraw_loops tries for loop x of w: the slide {p, p + 1, x} from the corner before
// x's forward letter to the one after it, which reads w again (up to rotation); and if w is in
// commutator blocks, every other slide of x whose word is in blocks too, one per resulting word
// up to rotation (a slide's arc depends only on the wedges of its corners, so moves with the same
// word draw the same loops). O(|w|^3).
std::vector<Slide> redraw_moves(const Word& w, int x) {
  const int n = static_cast<int>(w.size());
  int p = -1, q = -1;  // x's forward and inverse letters
  for (int k = 0; k < n; ++k)
    if (w[k].loop == x) (w[k].inverse ? q : p) = k;
  if (p < 0 || q < 0) internal("slides: loop " + std::to_string(x) + " is not twice in " + to_string(w));
  std::vector<Slide> moves{Slide{p, (p + 1) % n, x}};
  if (commutator_rotation(w) < 0) return moves;
  auto rotation_key = [n](const Word& o) {  // the least rotation, letters as 2 loop + inverse
    std::vector<int> best;
    for (int r = 0; r < n; ++r) {
      std::vector<int> c(n);
      for (int k = 0; k < n; ++k) c[k] = 2 * o[(r + k) % n].loop + (o[(r + k) % n].inverse ? 1 : 0);
      if (best.empty() || c < best) best = std::move(c);
    }
    return best;
  };
  std::vector<std::vector<int>> seen{rotation_key(w)};
  auto inside = [n](int k, int i, int j) { return wrap(k - i, n) < wrap(j - i, n); };  // k in [i, j)
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i == j || inside(p, i, j) == inside(q, i, j)) continue;  // the chord must separate p, q
      const Slide s{i, j, x};
      const Word o = apply_slide(w, s);
      if (commutator_rotation(o) < 0) continue;
      std::vector<int> key = rotation_key(o);
      if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
      seen.push_back(std::move(key));
      moves.push_back(s);
    }
  return moves;
}

}  // namespace

Word root_word(const TriMesh& M, int root, const std::vector<std::vector<int>>& loops) {
  const RootRotation R = root_rotation(M, root, loops);
  std::vector<int> departures;
  Word w = trace_word(R.ends, 0, &departures);
  if (w.empty()) internal("slides: the loops' ends at the root do not make one boundary cycle");
  return w;
}

bool draw_slide(SlideState& st, int root, const Slide& s, double beside_cost) {
  const TriMesh& M = st.rs.mesh;
  const int nv = M.num_vertices(), nh = M.num_halfedges(), x = s.loop;
  // Walls: the root and the other loops; chords: edges joining two walls that no loop uses. Per
  // vertex, the walls beside it but the root (read for free vertices only, whose neighbours on the
  // chord-split copy below are these and chord midpoints).
  std::vector<char> wall(nv, 0), loop_edge(nh, 0);
  std::vector<int> walls_beside(nv, 0);
  wall[root] = 1;
  for (int i = 0; i < static_cast<int>(st.loops.size()); ++i) {
    if (i == x) continue;
    const std::vector<int>& L = st.loops[i];
    for (std::size_t k = 0; k < L.size(); ++k) {
      wall[L[k]] = 1;
      const int h = find_he(M, L[k], L[(k + 1) % L.size()]);
      loop_edge[h] = loop_edge[M.twin(h)] = 1;
      if (k == 0) continue;  // the root
      const int g0 = M.vertex_halfedge(L[k]);
      int g = g0;
      do {
        ++walls_beside[M.target(g)];
        g = M.next_around_origin(g);
      } while (g != g0);
    }
  }
  const auto chords = sorted_chords(
      M, [&](int v) { return wall[v] != 0; }, [&](int, int, int h) { return loop_edge[h] != 0; });
  std::vector<int> mid;
  std::vector<Vec3d> pos_copy;
  const TriMesh C = split_copy(M, std::vector<Vec3d>(nv, Vec3d{0, 0, 0}), chords, mid, pos_copy);  // no lengths used
  const int cn = C.num_vertices();
  // Corner k of the word lies between the ends departures[k] and departures[k] + 1 (ccw): the
  // walk arrives at an end's mate and leaves along the next end clockwise. With x removed, its
  // wedge runs from the nearest other loop's end clockwise of it to the next one counter-clockwise.
  const RootRotation R = root_rotation(C, root, st.loops);
  std::vector<int> departures;
  if (start_reading(R, st.word, departures) < 0)
    internal("slides: the loops do not read the expected word " + to_string(st.word));
  const int m = static_cast<int>(R.ends.size()), rn = static_cast<int>(R.he.size());
  std::vector<char> other_end(rn, 0);
  for (int k = 0; k < m; ++k)
    if (R.ends[k].loop != x) other_end[R.at[k]] = 1;
  auto wedge = [&](int corner) {
    int e = departures[wrap(corner, m)];
    for (int t = 0; t < m && R.ends[e].loop == x; ++t) e = wrap(e - 1, m);  // x has two ends of m >= 4
    std::vector<int> hs;
    for (int q = (R.at[e] + 1) % rn; !other_end[q]; q = (q + 1) % rn) hs.push_back(R.he[q]);  // < rn steps
    return hs;
  };
  const std::vector<int> from = wedge(s.from_corner), to = wedge(s.to_corner);
  auto blocked = [&](int v) { return v == root || (v < nv && wall[v]); };
  std::vector<char> beside_root(cn, 0), target(cn, 0);
  for (int h : R.he) beside_root[C.target(h)] = 1;
  for (int h : to)
    if (!blocked(C.target(h))) target[C.target(h)] = 1;
  // A path vertex costs kSlideHopCost plus beside_cost per wall beside it (each such edge becomes a
  // chord that later slides and redraws must split to cross), a chord midpoint kMidpointCost more.
  auto cost = [&](int v) { return kSlideHopCost + (v >= nv ? kMidpointCost : beside_cost * walls_beside[v]); };
  std::vector<double> dist(cn, INFINITY);
  std::vector<int> par(cn, -1);
  MinQueue pq;
  for (int h : from) {
    const int v = C.target(h);
    if (!blocked(v) && !target[v]) dist[v] = cost(v), pq.push({dist[v], v});
  }
  // Dijkstra over free vertices not beside the root; it ends at the first wedge vertex of corner j
  // settled (each vertex pushed at most once per half-edge into it).
  int hit = -1;
  double best = INFINITY;
  while (!pq.empty()) {
    const auto [d, u] = pq.top();
    pq.pop();
    if (d > dist[u]) continue;
    if (d >= best) break;
    const int h0 = C.vertex_halfedge(u);
    int h = h0;
    do {
      const int v = C.target(h);
      const double dv = d + cost(v);
      if (!blocked(v) && dv < dist[v]) {
        if (target[v]) {
          if (dv < best) best = dv, dist[v] = dv, par[v] = u, hit = v;
        } else if (!beside_root[v]) {
          dist[v] = dv, par[v] = u, pq.push({dv, v});
        }
      }
      h = C.next_around_origin(h);
    } while (h != h0);
  }
  if (hit < 0) return false;
  std::vector<int> path;
  for (int v = hit; v >= 0; v = par[v]) path.push_back(v);  // a shortest path: no vertex twice
  std::reverse(path.begin(), path.end());
  std::vector<std::pair<int, int>> used{{root, path.front()}, {path.back(), root}};
  for (std::size_t k = 0; k + 1 < path.size(); ++k) used.push_back({path[k], path[k + 1]});
  const std::vector<int> to_surface = split_like_copy(st.rs, chords, mid, cn, used, st.splits);
  std::vector<int> loop{root};
  for (int v : path) {
    if (to_surface[v] < 0) internal("slides: a drawn loop uses a chord midpoint that was not split");
    loop.push_back(to_surface[v]);
  }
  for (std::size_t k = 0; k < loop.size(); ++k)
    if (st.rs.mesh.find_halfedge(loop[k], loop[(k + 1) % loop.size()]) < 0)
      internal("slides: a drawn loop's edge is missing after the splits", {loop[k]});
  st.loops[x] = std::move(loop);
  st.word = apply_slide(st.word, s);
  TightenedLoops t = tighten_loops(std::move(st.rs), std::move(st.loops), root);
  st.rs = std::move(t.surface);
  st.loops = std::move(t.loops);
  st.collapsed += t.stats.collapsed;
  const RootRotation after = root_rotation(st.rs.mesh, root, st.loops);
  if (start_reading(after, st.word, departures) < 0)
    internal("slides: slide {" + std::to_string(s.from_corner) + ", " + std::to_string(s.to_corner) + ", L" +
             std::to_string(x) + "} drew a loop that does not read " + to_string(st.word));
  return true;
}

int redraw_loops(SlideState& st, int root, int max_passes, bool parallel) {
  const int n = static_cast<int>(st.word.size());
  int kept = 0;
  for (int pass = 0; pass < max_passes; ++pass) {
    int kept_now = 0;
    // The longest loops first (36 generated meshes, measured with a pass after every step of step
    // 3c: 6,180 vertices added against 6,267 in id order).
    std::vector<int> order(n / 2);
    for (int x = 0; x < n / 2; ++x) order[x] = x;
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return st.loops[a].size() > st.loops[b].size(); });
    for (int x : order) {
      const std::vector<Slide> moves = redraw_moves(st.word, x);
      std::vector<SlideState> drawn(moves.size());
      std::vector<char> ok(moves.size(), 0);
      auto draw = [&](std::size_t from) {
        for (std::size_t k = from; k < moves.size(); k += 2) {
          drawn[k] = st;
          ok[k] = draw_slide(drawn[k], root, moves[k]);
        }
      };
      run_pair(parallel && moves.size() > 1, [&] { draw(0); }, [&] { draw(1); });
      SlideState* best = &st;  // the fewest vertices, then loop vertices, then the first move
      for (std::size_t k = 0; k < moves.size(); ++k) {
        if (!ok[k]) continue;
        const int dv = drawn[k].rs.mesh.num_vertices(), bv = best->rs.mesh.num_vertices();
        if (dv < bv || (dv == bv && drawn[k].loop_vertices() < best->loop_vertices())) best = &drawn[k];
      }
      if (best != &st) {
        st = std::move(*best);
        ++kept_now;
      }
    }
    kept += kept_now;
    if (kept_now == 0) break;
  }
  st.redrawn += kept;
  return kept;
}

bool canonical_slides(SlideState& st, int root, bool parallel, int* slides, long long* trials) {
  const int n = static_cast<int>(st.word.size());
  SlideState cur = st;
  int made = 0;
  long long drawn = 0;
  for (int step = 0;; ++step) {  // each step forms a block: at most g steps
    const Word& w = cur.word;
    const std::vector<char> done = loops_in_blocks(w);
    const long in_blocks = std::count(done.begin(), done.end(), 1);
    if (in_blocks == n / 2) break;
    if (step == n / 4) internal("slides: no normal form after g steps: " + to_string(w));
    // The candidates: every two-slide formation among the loops not in a block.
    const std::vector<Formation> cands = formations(w, done);
    if (cands.empty()) internal("slides: no linked pair in " + to_string(w));
    // Each candidate's first slide drawn on a copy; the kSlideFinalists best (`better`) also get
    // their second, and the best of those wins. Two halves on two threads, merged in candidate
    // order: the threads change nothing.
    struct Drawn {
      long vertices = 0, loop_vertices = 0;
      std::size_t index = 0;
      SlideState state;
      bool ok = false;
    };
    auto better = [](const Drawn& a, const Drawn& b) {
      const long ka = a.vertices + a.loop_vertices / kLoopVerticesPerVertex;
      const long kb = b.vertices + b.loop_vertices / kLoopVerticesPerVertex;
      if (ka != kb) return ka < kb;
      if (a.vertices != b.vertices) return a.vertices < b.vertices;
      if (a.loop_vertices != b.loop_vertices) return a.loop_vertices < b.loop_vertices;
      return a.index < b.index;
    };
    // Each half keeps only its kSlideFinalists best copies (memory: at most 2 kSlideFinalists + 2
    // copies of the surface at once); merged, the best kSlideFinalists are those of a global sort.
    auto keep = [&](std::vector<Drawn>& top, Drawn&& d) {
      auto at = std::upper_bound(top.begin(), top.end(), d, better);
      if (static_cast<std::size_t>(at - top.begin()) >= kSlideFinalists) return;
      top.insert(at, std::move(d));
      if (top.size() > kSlideFinalists) top.pop_back();
    };
    auto first_slides = [&](std::size_t from, std::vector<Drawn>& top) {
      for (std::size_t c = from; c < cands.size(); c += 2) {
        Drawn d;
        d.index = c;
        d.state = cur;
        if (!draw_slide(d.state, root, cands[c].first)) continue;
        d.vertices = d.state.rs.mesh.num_vertices(), d.loop_vertices = d.state.loop_vertices(), d.ok = true;
        keep(top, std::move(d));
      }
    };
    std::vector<Drawn> top_even, top_odd;
    run_pair(parallel && cands.size() > 1, [&] { first_slides(0, top_even); }, [&] { first_slides(1, top_odd); });
    drawn += static_cast<long long>(cands.size());
    for (Drawn& d : top_odd) keep(top_even, std::move(d));
    std::vector<Drawn*> finalists;
    for (Drawn& d : top_even) finalists.push_back(&d);
    auto slide_two = [&](std::size_t k) {
      Drawn& d = *finalists[k];
      d.ok = draw_slide(d.state, root, second_slide(d.state.word, cands[d.index]));
      if (!d.ok) return;
      const std::vector<char> now = loops_in_blocks(d.state.word);
      if (std::count(now.begin(), now.end(), 1) <= in_blocks)  // its corners lie between blocks
        internal("slides: a two-slide formation added no block: " + to_string(d.state.word));
      d.vertices = d.state.rs.mesh.num_vertices(), d.loop_vertices = d.state.loop_vertices();
    };
    run_pair(
        parallel && finalists.size() > 1,
        [&] {
          for (std::size_t k = 0; k < finalists.size(); k += 2) slide_two(k);
        },
        [&] {
          for (std::size_t k = 1; k < finalists.size(); k += 2) slide_two(k);
        });
    drawn += static_cast<long long>(finalists.size());
    Drawn* win = nullptr;
    for (Drawn* d : finalists)
      if (d->ok && (!win || better(*d, *win))) win = d;
    if (!win) {
      if (trials) *trials = drawn;
      return false;
    }
    cur = std::move(win->state);
    made += 2;
  }
  // The redraws only after the last step: one pass after each step too changes later choices for
  // no gain (36 generated genus 2-12 meshes: 6,180 vertices added against 6,231 without, at 11 %
  // more time; couplingdown 1,982 against 1,969; by hop counts, bench/README.md, step 3d).
  redraw_loops(cur, root, kRedrawPasses, parallel);
  st = std::move(cur);
  if (slides) *slides = made;
  if (trials) *trials = drawn;
  return true;
}

}  // namespace igm::topology_internal
