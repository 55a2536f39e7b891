#include "igm/topology/tighten_loops.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <string>
#include <utility>

#include "igm/core/error.h"
#include "igm/exact/predicates.h"

namespace igm {

namespace {

[[noreturn]] void internal(const std::string& what, std::vector<std::int64_t> ids = {}) {
  throw Error(ErrorKind::Internal, "loop tightening: " + what, std::move(ids));
}

// out = the weight of input vertex u in p (0 if u is not in its support). An assignment: out's
// limbs are reused.
void set_weight_of(const SurfacePoint& p, int u, Rational& out) {
  for (int i = 0; i < 3; ++i)
    if (p.v[i] == u) {
      out = p.w[i];
      return;
    }
  out = 0;
}

// q = the point p in the barycentric chart of the input face with vertices U (sorted): the weights
// of U[1] and U[2]. An affine chart: the orientations of all triangles of the face in it differ
// from those on the surface by one common sign.
void set_chart(const SurfacePoint& p, const std::array<int, 3>& U, Point2q& q) {
  set_weight_of(p, U[1], q.x);
  set_weight_of(p, U[2], q.y);
}

// The input vertices with positive weight in the three points, sorted, without repeats, into U;
// false if they are not exactly three (then the points do not span one input face).
bool face_support(const SurfacePoint& a, const SurfacePoint& b, const SurfacePoint& c, std::array<int, 3>& U) {
  int n = 0;
  for (const SurfacePoint* p : {&a, &b, &c})
    for (int i = 0; i < 3; ++i) {
      if (p->v[i] < 0 || sgn(p->w[i]) <= 0) continue;
      const int u = p->v[i];
      if (std::find(U.begin(), U.begin() + n, u) != U.begin() + n) continue;
      if (n == 3) return false;
      U[n++] = u;
    }
  if (n != 3) return false;
  if (U[0] > U[1]) std::swap(U[0], U[1]);
  if (U[1] > U[2]) std::swap(U[1], U[2]);
  if (U[0] > U[1]) std::swap(U[0], U[1]);
  return true;
}

bool supported_in(const SurfacePoint& p, const std::array<int, 3>& U) {
  for (int i = 0; i < 3; ++i)
    if (p.v[i] >= 0 && sgn(p.w[i]) > 0 && std::find(U.begin(), U.end(), p.v[i]) == U.end()) return false;
  return true;
}

bool has(const std::array<int, 3>& t, int v) { return t[0] == v || t[1] == v || t[2] == v; }

// The refined surface as a face list with per-vertex incident faces, for edge collapses: a collapse
// is O(valence). A vertex's list is read off rs.mesh (which is not changed here) the first time it
// is needed: a collapse changes the lists of c, w and the two apexes only, and checks all four
// before it does, so a list built later is still right (face ids are stable; the faces' corners
// are in tri). The pairing of half-edges (3f + i runs from tri[f][i] to tri[f][(i + 1) % 3]) is
// kept in twin through the collapses, so that the compaction renumbers it instead of pairing the
// faces' edges again by sorting.
struct FaceList {
  const RefinedSurface& rs;
  std::vector<std::array<int, 3>> tri;
  std::vector<int> twin;
  std::vector<char> face_alive, alive, built;
  std::vector<std::vector<int>> inc;
  std::vector<int> stamp;
  int clock = 0;
  std::vector<int> nc, nw;  // the neighbours of c and of w found by the last collapse_ok
  // collapse_ok's scratch, kept so that its exact checks allocate nothing once warm: an input
  // vertex's weight-1 point per role (only the id changes), and the four chart points.
  std::array<SurfacePoint, 4> unit_point;
  Point2q qc, qw, qa, qb;

  explicit FaceList(const RefinedSurface& s)
      : rs(s), tri(s.mesh.num_faces()), twin(s.mesh.twins()), face_alive(tri.size(), 1), alive(s.mesh.num_vertices(), 1),
        built(s.mesh.num_vertices(), 0), inc(s.mesh.num_vertices()), stamp(s.mesh.num_vertices(), 0) {
    if (static_cast<int>(rs.constructed.size()) != rs.mesh.num_vertices() - rs.num_input_vertices)
      internal("constructed points out of step with the mesh");
    for (SurfacePoint& p : unit_point) p = SurfacePoint::vertex(0);
    for (int f = 0; f < rs.mesh.num_faces(); ++f) tri[f] = rs.mesh.face_vertices(f);
  }
  std::vector<int>& faces_at(int v) {
    if (!built[v]) {
      built[v] = 1;
      inc[v].reserve(static_cast<std::size_t>(rs.mesh.valence(v)) + 2);  // one allocation: a collapse adds a few
      const int h0 = rs.mesh.vertex_halfedge(v);
      int h = h0;
      do {  // valence steps
        inc[v].push_back(TriMesh::face(h));
        h = rs.mesh.next_around_origin(h);
      } while (h != h0);
    }
    return inc[v];
  }
  // v's neighbours, each once, into nb; marks them with the new clock.
  void neighbours(int v, std::vector<int>& nb) {
    nb.clear();
    ++clock;
    for (int f : faces_at(v))
      for (int u : tri[f])
        if (u != v && stamp[u] != clock) stamp[u] = clock, nb.push_back(u);
  }
  void unlink_face(int f, int except) {
    face_alive[f] = 0;
    for (int u : tri[f]) {
      if (u == except) continue;
      auto& l = faces_at(u);
      const auto it = std::find(l.begin(), l.end(), f);
      if (it == l.end()) internal("incidence out of step", {u});
      *it = l.back();
      l.pop_back();
    }
  }
  // v's exact point: a constructed vertex's own, an input vertex's in unit_point[role] (weight 1).
  const SurfacePoint& point(int v, int role) {
    if (v >= rs.num_input_vertices) return rs.constructed[v - rs.num_input_vertices];
    unit_point[role].v[0] = v;
    return unit_point[role];
  }
  bool face_with(int a, int b, int c) {
    for (int f : faces_at(a))
      if (has(tri[f], b) && has(tri[f], c)) return true;
    return false;
  }
  // The geometric and combinatorial checks of an edge collapse c -> w (c constructed): the link
  // condition, valences >= 3, and every face moving from c to w keeping its exact orientation in
  // its input face. Fills shared with the two faces at cw, nc and nw with the neighbours of c and
  // w. O(valence) exact orientations.
  bool collapse_ok(int c, int w, int shared[2]) {
    int ns = 0;
    for (int f : faces_at(c))
      if (has(tri[f], w)) {
        if (ns == 2) return false;
        shared[ns++] = f;
      }
    if (ns != 2) return false;
    int apex[2];
    for (int k = 0; k < 2; ++k) {
      const auto& t = tri[shared[k]];
      apex[k] = t[0] != c && t[0] != w ? t[0] : (t[1] != c && t[1] != w ? t[1] : t[2]);
    }
    if (apex[0] == apex[1]) return false;
    // Link condition (neighbours(c) runs last: its marks hold the current clock).
    neighbours(w, nw);
    neighbours(c, nc);
    int common = 0;
    for (int u : nw)
      if (u != c && stamp[u] == clock) ++common;
    if (common != 2) return false;
    if (faces_at(apex[0]).size() < 4 || faces_at(apex[1]).size() < 4 || faces_at(c).size() + faces_at(w).size() < 7) return false;
    const SurfacePoint &pc = point(c, 0), &pw = point(w, 1);
    for (int f : faces_at(c)) {
      if (f == shared[0] || f == shared[1]) continue;
      const auto& t = tri[f];
      const int k = t[0] == c ? 0 : (t[1] == c ? 1 : 2);
      const SurfacePoint &pa = point(t[(k + 1) % 3], 2), &pb = point(t[(k + 2) % 3], 3);
      std::array<int, 3> U{-1, -1, -1};
      if (!face_support(pc, pa, pb, U) || !supported_in(pw, U)) return false;
      set_chart(pa, U, qa), set_chart(pb, U, qb), set_chart(pc, U, qc), set_chart(pw, U, qw);
      const Sign before = orient2d(qc, qa, qb);
      if (before == Sign::Zero) internal("a refined face is flat in its input face", {c});
      if (orient2d(qw, qa, qb) != before) return false;
    }
    return true;
  }
  void collapse(int c, int w, const int shared[2]) {
    // A face (c, w, a) at the edge goes; the faces beyond its edges wa and ac become neighbours.
    for (int k = 0; k < 2; ++k) {
      const int f = shared[k];
      int outer[2], n = 0;
      for (int i = 0; i < 3; ++i) {
        const int a = tri[f][i], b = tri[f][(i + 1) % 3];
        if (!((a == c && b == w) || (a == w && b == c))) outer[n++] = twin[3 * f + i];
      }
      twin[outer[0]] = outer[1], twin[outer[1]] = outer[0];
    }
    for (int k = 0; k < 2; ++k) unlink_face(shared[k], c);
    for (int f : faces_at(c)) {
      if (!face_alive[f]) continue;
      for (int& u : tri[f])
        if (u == c) u = w;
      faces_at(w).push_back(f);
    }
    std::vector<int>().swap(faces_at(c));
    alive[c] = 0;
  }
  // The surface without the collapsed vertices: input vertices keep their ids, the surviving
  // constructed ones are renumbered in order (new_id; -1 for a collapsed one). With none collapsed
  // the surface is returned as it is (only loops on it may have moved). O(n + F).
  RefinedSurface compacted(RefinedSurface&& old, std::vector<int>& new_id) const {
    const int nv = old.mesh.num_vertices(), nin = old.num_input_vertices;
    if (std::find(alive.begin(), alive.end(), 0) == alive.end()) {
      new_id.resize(nv);
      std::iota(new_id.begin(), new_id.end(), 0);
      return std::move(old);
    }
    new_id.assign(nv, -1);
    std::iota(new_id.begin(), new_id.begin() + nin, 0);
    int next_id = nin;
    RefinedSurface out;
    // The survivors move down in place (a move swaps the weights: no allocation), the rest go.
    std::vector<SurfacePoint>& pts = old.constructed;
    for (int v = nin; v < nv; ++v)
      if (alive[v]) {
        if (next_id != v) pts[next_id - nin] = std::move(pts[v - nin]);
        new_id[v] = next_id++;
      }
    pts.erase(pts.begin() + (next_id - nin), pts.end());
    out.constructed = std::move(pts);
    // The surviving faces in order, their half-edges paired through the kept twins: the mesh that
    // from_triangles would build from their corners.
    std::vector<int> new_face(tri.size(), -1);
    int nf = 0;
    for (std::size_t f = 0; f < tri.size(); ++f)
      if (face_alive[f]) new_face[f] = nf++;
    std::vector<int> origin(3 * static_cast<std::size_t>(nf)), tw(3 * static_cast<std::size_t>(nf));
    for (std::size_t f = 0; f < tri.size(); ++f) {
      if (!face_alive[f]) continue;
      const std::size_t h = 3 * static_cast<std::size_t>(new_face[f]);
      for (int i = 0; i < 3; ++i) {
        const int t = twin[3 * f + i], g = new_face[TriMesh::face(t)];
        if (g < 0) internal("a kept half-edge is paired with a collapsed face", {static_cast<std::int64_t>(f)});
        origin[h + i] = new_id[tri[f][i]];
        tw[h + i] = 3 * g + t % 3;
      }
    }
    out.mesh = TriMesh::from_halfedges(next_id, std::move(origin), std::move(tw));
    out.num_input_vertices = nin;
    out.input_positions = std::move(old.input_positions);
    return out;
  }
};

}  // namespace

TightenedLoops tighten_loops(RefinedSurface surface, std::vector<std::vector<int>> loops, int root,
                             bool every_vertex_every_pass, const std::vector<char>& barred) {
  TightenedLoops out;
  RefinedSurface& rs = surface;
  const int nv = rs.mesh.num_vertices();
  const int nin = rs.num_input_vertices;
  const int nloops = static_cast<int>(loops.size());

  FaceList fl(rs);

  // The loops as linked lists over their vertices (the root excluded: every other vertex is on at
  // most one loop): loop_of (-1: free), nxt / prv (the root at the two ends).
  std::vector<int> loop_of(nv, -1), nxt(nv, -1), prv(nv, -1), head(nloops), tail(nloops);
  for (int i = 0; i < nloops; ++i) {
    const auto& L = loops[i];
    if (L.size() < 3 || L[0] != root) internal("loop does not start at the root", {i});
    for (std::size_t j = 1; j < L.size(); ++j) {
      const int v = L[j];
      if (v < 0 || v >= nv) internal("loop vertex out of range", {v});
      if (v == root || loop_of[v] != -1) internal("loops not simple or not disjoint", {v});
      if (rs.mesh.find_halfedge(L[j - 1], v) < 0 || (j + 1 == L.size() && rs.mesh.find_halfedge(v, root) < 0))
        internal("a loop step is not an edge", {L[j - 1], v});
      loop_of[v] = i;
      prv[v] = L[j - 1];
      nxt[v] = j + 1 < L.size() ? L[j + 1] : root;
    }
    head[i] = L[1], tail[i] = L.back();
  }
  // Vertices no loop may move onto (ids past the flags are not barred).
  auto is_barred = [&](int v) { return v < static_cast<int>(barred.size()) && barred[v]; };
  // The vertices whose loop state or incident faces a move changed (see the passes below).
  std::vector<int> touched;
  // Scratch lists of the moves, kept across calls so that a pass allocates nothing once warm; each
  // has one user (pull's candidates stay intact through the M1 -> M2 -> M3 calls it makes).
  std::vector<int> free_cand, pull_cand, arc, np, pn, nz;
  // fl.collapse(c, w) right after fl.collapse_ok(c, w): the faces change at c and at fl.nc, c's
  // neighbours, which collapse_ok left there.
  auto collapse = [&](int c, int w, const int shared[2]) {
    touched.insert(touched.end(), fl.nc.begin(), fl.nc.end());
    touched.push_back(c);
    fl.collapse(c, w, shared);
  };
  auto set_next = [&](int L, int a, int b) {  // a -> b along L (either may be the root)
    touched.push_back(a), touched.push_back(b);
    if (a == root) head[L] = b;
    else nxt[a] = b;
    if (b == root) tail[L] = a;
    else prv[b] = a;
  };

  // Whether `keeper`, a vertex of loop L (-1: on none) with its loop neighbours already set, may be
  // adjacent to u: not if u is another vertex of L, or the root while keeper is neither end of L
  // (such an edge could join two vertices of one polygon side, which the cut would split again).
  auto adjacency_ok = [&](int keeper, int L, int u) {
    if (L < 0 || u == prv[keeper] || u == nxt[keeper]) return true;
    if (u == root) return prv[keeper] == root || nxt[keeper] == root;
    return loop_of[u] != L;
  };

  // M3: a free constructed vertex v is removed by collapsing it into a neighbour y (the lowest id
  // that passes), if y gains no forbidden adjacency.
  auto remove_free = [&](int v) {
    if (v < nin || !fl.alive[v] || loop_of[v] != -1) return false;
    std::vector<int>& cand = free_cand;
    fl.neighbours(v, cand);
    std::sort(cand.begin(), cand.end());
    for (int y : cand) {
      if (y == root) continue;
      int shared[2];
      if (!fl.collapse_ok(v, y, shared)) continue;
      bool ok = true;  // fl.nc = v's neighbours (from collapse_ok): y's new ones
      for (int u : fl.nc)
        if (u != y && !adjacency_ok(y, loop_of[y], u)) ok = false;
      if (!ok) continue;
      collapse(v, y, shared);
      ++out.stats.collapsed;
      return true;
    }
    return false;
  };
  // M2: a loop vertex v whose loop neighbours u, t span a face (u, v, t), neither of them the
  // root, leaves the loop (u -> t directly, across that face: an isotopy); a constructed v is then
  // removed if it can be (M3).
  auto shortcut = [&](int v) {
    const int L = loop_of[v];
    if (L < 0) return false;
    const int u = prv[v], t = nxt[v];
    if (u == root || t == root || !fl.face_with(v, u, t)) return false;
    set_next(L, u, t);
    loop_of[v] = -1, prv[v] = nxt[v] = -1;
    touched.push_back(v);
    ++out.stats.shortcuts;
    remove_free(v);
    return true;
  };
  // M1: a constructed loop vertex c collapses into its free neighbour w, the loop then running
  // through w. w may gain an edge to the loop vertex two steps from c only where a face makes the
  // shortcut (M2) that turns it into a loop edge, done at once. False (nothing changed) if a check
  // fails.
  auto pull_into = [&](int c, int w) {
    const int L = loop_of[c];
    int shared[2];
    if (!fl.collapse_ok(c, w, shared)) return false;
    const int p = prv[c], n = nxt[c];
    const int pp = p == root ? -1 : prv[p], nn = n == root ? -1 : nxt[n];
    int via = -1;  // the loop neighbour of c to shortcut past afterwards
    for (int u : fl.nw) {  // w's neighbours before the collapse (c's are kept by c's own rules)
      if (u == c || adjacency_ok(c, L, u)) continue;
      if (u == nn && nn != root && via < 0 && (fl.face_with(w, n, nn) || fl.face_with(c, n, nn))) via = n;
      else if (u == pp && pp != root && via < 0 && (fl.face_with(w, p, pp) || fl.face_with(c, p, pp))) via = p;
      else return false;
    }
    collapse(c, w, shared);
    loop_of[w] = L, prv[w] = p, nxt[w] = n;
    set_next(L, p, w);
    set_next(L, w, n);
    loop_of[c] = -1;
    ++out.stats.collapsed;
    if (via >= 0) shortcut(via);
    return true;
  };
  // M4: a constructed loop vertex c next to a vertex w of another loop B: B is pushed off w to
  // w's neighbours on the side away from c (p -> z_1 .. z_r -> n, r >= 1, all free: an isotopy
  // across w's faces on that side, which hold no other loop), then c collapses into w (M1). Both
  // or neither: the push is undone (from a log) if the collapse fails. B must not touch itself at
  // its new vertices. (Pushing a third loop off an occupied z first, recursively, measured no
  // better: couplingdown 2062 instead of 2070 vertices, cheese 28359 instead of 28274.)
  struct Saved { int v, loop, prev, next; };
  std::vector<Saved> saved;
  std::vector<std::array<int, 3>> saved_ends;  // (loop, head, tail)
  auto save = [&](int v) { saved.push_back({v, loop_of[v], prv[v], nxt[v]}); };
  auto save_ends = [&](int L) { saved_ends.push_back({L, head[L], tail[L]}); };
  auto undo = [&] {
    for (auto it = saved.rbegin(); it != saved.rend(); ++it) loop_of[it->v] = it->loop, prv[it->v] = it->prev, nxt[it->v] = it->next;
    for (auto it = saved_ends.rbegin(); it != saved_ends.rend(); ++it) head[(*it)[0]] = (*it)[1], tail[(*it)[0]] = (*it)[2];
  };
  std::vector<std::pair<int, int>> fan;  // (a, b) per face (w, a, b) at w: b follows a ccw
  // The neighbours of w strictly between its loop neighbours p and n on the side without `from`,
  // in order from p, into arc. Empty if none (or `from` is on neither side).
  auto far_arc = [&](int w, int from, int p, int n) {
    fan.clear();
    for (int f : fl.faces_at(w)) {
      const auto& t = fl.tri[f];
      const int k = t[0] == w ? 0 : (t[1] == w ? 1 : 2);
      fan.push_back({t[(k + 1) % 3], t[(k + 2) % 3]});
    }
    auto succ = [&](int a) {
      for (const auto& [x, y] : fan)
        if (x == a) return y;
      internal("a vertex fan does not close", {w});
    };
    auto walk = [&](int from_v, int to_v, std::vector<int>& arc) {  // ccw, strictly between
      bool met = false;
      for (int a = succ(from_v), guard = 0; a != to_v; a = succ(a), ++guard) {
        if (guard > static_cast<int>(fan.size())) internal("a vertex fan does not close", {w});
        met = met || a == from;
        arc.push_back(a);
      }
      return met;
    };
    np.clear(), pn.clear(), arc.clear();
    const bool in_np = walk(n, p, np), in_pn = walk(p, n, pn);
    if (in_np == in_pn) return;
    if (in_pn) arc.assign(np.rbegin(), np.rend());  // from p's side
    else arc.assign(pn.begin(), pn.end());
  };
  auto push_off = [&](int w, int from) {
    const int B = loop_of[w];
    if (B < 0 || w == root) return false;
    const int p = prv[w], n = nxt[w];
    if (p == root || n == root) return false;
    far_arc(w, from, p, n);
    if (arc.empty()) return false;
    for (int z : arc)
      if (z == root || loop_of[z] != -1 || is_barred(z)) return false;
    save(w);
    save_ends(B);
    int before = p;
    save(p);
    for (int z : arc) {
      save(z);
      loop_of[z] = B;
      set_next(B, before, z);
      before = z;
    }
    save(n);
    set_next(B, before, n);
    loop_of[w] = -1, prv[w] = nxt[w] = -1;
    touched.push_back(w);
    for (int z : arc) {
      fl.neighbours(z, nz);
      for (int u : nz)
        if (!adjacency_ok(z, B, u)) return false;
    }
    return true;
  };
  auto push_and_pull = [&](int c, int w) {
    if (loop_of[w] < 0 || loop_of[w] == loop_of[c]) return false;
    saved.clear();
    saved_ends.clear();
    if (push_off(w, c) && pull_into(c, w)) {
      ++out.stats.pushes;
      return true;
    }
    undo();
    return false;
  };
  auto pull = [&](int c) {
    if (c < nin || loop_of[c] < 0) return -1;
    std::vector<int>& cand = pull_cand;
    fl.neighbours(c, cand);
    std::sort(cand.begin(), cand.end());
    for (int w : cand)
      if (loop_of[w] == -1 && w != root && !is_barred(w) && pull_into(c, w)) return w;
    for (int w : cand)
      if (loop_of[w] >= 0 && !is_barred(w) && push_and_pull(c, w)) return w;
    return -1;
  };

  // Passes until one changes nothing. Each change lowers (alive vertices) * (V + 1) + (total loop
  // length), V the vertices at the start: M1, M3 and M4 remove a vertex and lengthen the loops by
  // less than V + 1, M2 shortens one. So at most V (V + 2) + 1 passes (in practice 3 to 9); a pass
  // visits every loop vertex and every free constructed vertex once, in the same order, but checks
  // only the dirty ones: a check reads the loop state of the vertices within three edges of its
  // vertex and the faces at those within two, so a vertex whose check failed is clean until a move
  // changes that state within kReach edges of it (each move marks the kReach-ring of the vertices
  // it touched, in the surface after it). A clean vertex's check would fail again, so the moves
  // and the result are those of checking every vertex in every pass; on cheese's normal form
  // (9 passes) 1.4 s -> 0.2 s.
  constexpr int kReach = 4;  // one more than the reads need
  std::vector<char> dirty(nv, 1);
  std::vector<int> seen(nv, 0), frontier, next_frontier, nb;
  int seen_clock = 0;
  auto mark_touched = [&] {
    ++seen_clock;
    frontier.clear();
    for (int x : touched)
      if (x >= 0 && fl.alive[x] && seen[x] != seen_clock) seen[x] = seen_clock, dirty[x] = 1, frontier.push_back(x);
    for (int r = 0; r < kReach && !frontier.empty(); ++r) {
      next_frontier.clear();
      for (int x : frontier) {
        fl.neighbours(x, nb);
        for (int u : nb)
          if (seen[u] != seen_clock) seen[u] = seen_clock, dirty[u] = 1, next_frontier.push_back(u);
      }
      frontier.swap(next_frontier);
    }
    touched.clear();
  };
  const long long max_passes = static_cast<long long>(nv) * (nv + 2) + 1;
  for (bool changed = true; changed;) {
    changed = false;
    ++out.stats.passes;
    if (out.stats.passes > max_passes) internal("no fixed point");
    for (int L = 0; L < nloops; ++L)
      for (int v = head[L], guard = 0; v != root; ++guard) {
        if (guard > nv) internal("loop list does not end at the root");
        if (!dirty[v] && !every_vertex_every_pass) {
          v = nxt[v];
          continue;
        }
        touched.clear();
        const int before = prv[v];
        if (shortcut(v)) {
          changed = true;
          mark_touched();
          v = before == root ? head[L] : nxt[before];
          continue;
        }
        const int w = pull(v);
        if (w >= 0) changed = true, mark_touched();
        else dirty[v] = 0;
        v = nxt[w >= 0 ? w : v];
      }
    for (int v = nin; v < nv; ++v) {
      if ((!dirty[v] && !every_vertex_every_pass) || !fl.alive[v] || loop_of[v] != -1) continue;
      touched.clear();
      if (remove_free(v)) changed = true, mark_touched();
      else dirty[v] = 0;
    }
  }

  // Compact: input vertices keep their ids, surviving constructed ones are renumbered in order.
  std::vector<int> new_id;
  out.surface = fl.compacted(std::move(rs), new_id);
  out.loops.assign(nloops, {});
  for (int L = 0; L < nloops; ++L) {
    auto& P = out.loops[L];
    P.push_back(root);
    for (int v = head[L]; v != root; v = nxt[v]) P.push_back(new_id[v]);
    if (P.size() < 3) internal("a loop became shorter than three vertices", {L});
  }
  return out;
}

StraightenedPaths straighten_paths(RefinedSurface surface, const std::vector<std::pair<int, int>>& edges,
                                   const std::vector<int>& keep, int first) {
  RefinedSurface& rs = surface;
  const int n = rs.mesh.num_vertices();
  const int nin = rs.num_input_vertices;
  if (first < nin || first > n) internal("first candidate out of range", {first});
  // Each vertex's path neighbours (a candidate has exactly two).
  std::vector<int> degree(n, 0);
  std::vector<std::array<int, 2>> nb(n, {-1, -1});
  for (const auto& [x, y] : edges) {
    if (x < 0 || x >= n || y < 0 || y >= n || x == y) internal("a path edge out of range", {x, y});
    if (rs.mesh.find_halfedge(x, y) < 0) internal("a path step is not an edge", {x, y});
    for (const auto& [a, b] : {std::pair{x, y}, std::pair{y, x}})
      if (++degree[a] <= 2) nb[a][degree[a] - 1] = b;
  }
  std::vector<char> kept(n, 0);
  for (int v : keep)
    if (v >= 0 && v < n) kept[v] = 1;
  FaceList fl(rs);
  std::vector<int> into(n, -1);  // a removed vertex -> the vertex it was collapsed into
  StraightenedPaths out;
  for (int v = first; v < n; ++v) {  // each candidate once: O(candidates x valence) checks
    if (degree[v] != 2 || kept[v]) continue;
    const SurfacePoint& pv = rs.constructed[v - nin];  // v >= first >= nin: constructed
    int support = 0;
    for (int i = 0; i < 3; ++i) support += pv.v[i] >= 0 && sgn(pv.w[i]) > 0;
    if (support != 3) continue;  // on an input edge: where the path crosses it
    for (int k = 0; k < 2; ++k) {
      const int w = nb[v][k], o = nb[v][1 - k];
      int shared[2];
      if (!fl.collapse_ok(v, w, shared)) continue;
      fl.collapse(v, w, shared);
      into[v] = w;
      for (int& z : nb[w])
        if (z == v) z = o;
      for (int& z : nb[o])
        if (z == v) z = w;
      ++out.removed;
      break;
    }
  }
  std::vector<int> new_id;
  out.surface = fl.compacted(std::move(rs), new_id);
  // Each removed vertex's chain of targets ends at a surviving vertex (a target was alive when
  // taken); chains are compressed as they are followed, so O(n) steps in all.
  out.to.resize(n);
  for (int v = 0; v < n; ++v) {
    int u = v;
    for (int guard = 0; into[u] >= 0; ++guard) {
      if (guard > n) internal("collapse chain does not end", {v});
      u = into[u];
    }
    for (int x = v; into[x] >= 0;) {
      const int next = into[x];
      into[x] = u;
      x = next;
    }
    out.to[v] = new_id[u];
  }
  return out;
}

}  // namespace igm
