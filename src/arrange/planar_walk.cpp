#include "igm/arrange/planar_walk.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "igm/core/error.h"

namespace igm {

Rational cross(const Point2q& o, const Point2q& a, const Point2q& b) {
  Rational r = (a.x - o.x) * (b.y - o.y);
  r -= (a.y - o.y) * (b.x - o.x);
  return r;
}

Rational dot(const Point2q& o, const Point2q& a, const Point2q& b) {
  Rational r = (a.x - o.x) * (b.x - o.x);
  r += (a.y - o.y) * (b.y - o.y);
  return r;
}

bool same_point(const Point2q& a, const Point2q& b) { return a.x == b.x && a.y == b.y; }


PlanarAdjacency PlanarAdjacency::build(int num_vertices, const std::vector<std::array<int, 3>>& triangles) {
  PlanarAdjacency adj;
  const int nf = static_cast<int>(triangles.size());
  adj.neighbor.assign(nf, {-1, -1, -1});
  adj.neighbor_edge.assign(nf, {-1, -1, -1});
  adj.star_begin.assign(num_vertices + 1, 0);
  for (int t = 0; t < nf; ++t) {
    const auto& tri = triangles[t];
    for (int i = 0; i < 3; ++i) {
      if (tri[i] < 0 || tri[i] >= num_vertices)
        throw Error(ErrorKind::IndexOutOfRange, "triangle " + std::to_string(t) + " uses vertex " + std::to_string(tri[i]),
                    {t});
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      throw Error(ErrorKind::RepeatedVertex, "triangle " + std::to_string(t) + " uses a vertex twice", {t});
    for (int i = 0; i < 3; ++i) ++adj.star_begin[tri[i] + 1];
  }
  for (int v = 0; v < num_vertices; ++v) adj.star_begin[v + 1] += adj.star_begin[v];
  adj.star.assign(3 * static_cast<std::size_t>(nf), -1);
  std::vector<int> fill(adj.star_begin.begin(), adj.star_begin.end() - 1);
  for (int t = 0; t < nf; ++t)
    for (int i = 0; i < 3; ++i) adj.star[fill[triangles[t][i]]++] = t;
  // Pair directed edges (a,b) with (b,a) by sorting on (min, max).
  struct Key {
    int lo, hi, t, i;
  };
  std::vector<Key> keys;
  keys.reserve(3 * static_cast<std::size_t>(nf));
  for (int t = 0; t < nf; ++t)
    for (int i = 0; i < 3; ++i) {
      int a = triangles[t][i], b = triangles[t][(i + 1) % 3];
      keys.push_back({std::min(a, b), std::max(a, b), t, i});
    }
  std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) {
    return x.lo != y.lo ? x.lo < y.lo : (x.hi != y.hi ? x.hi < y.hi : (x.t != y.t ? x.t < y.t : x.i < y.i));
  });
  for (std::size_t k = 0; k < keys.size();) {
    std::size_t j = k;
    while (j < keys.size() && keys[j].lo == keys[k].lo && keys[j].hi == keys[k].hi) ++j;  // bounded by keys.size()
    const std::string edge = "edge (" + std::to_string(keys[k].lo) + ", " + std::to_string(keys[k].hi) + ")";
    if (j - k > 2) throw Error(ErrorKind::NonManifoldEdge, edge + " has more than two triangles", {keys[k].t});
    if (j - k == 2) {
      const Key &x = keys[k], &y = keys[k + 1];
      if (triangles[x.t][x.i] == triangles[y.t][y.i])
        throw Error(ErrorKind::NonManifoldEdge, edge + ": its two triangles have the same orientation", {x.t, y.t});
      adj.neighbor[x.t][x.i] = y.t;
      adj.neighbor_edge[x.t][x.i] = y.i;
      adj.neighbor[y.t][y.i] = x.t;
      adj.neighbor_edge[y.t][y.i] = x.i;
    }
    k = j;
  }
  return adj;
}

namespace {

// One triangle of the fan around the current point x: the fan triangle (x, u, w) lies in mesh
// triangle `tri`; edge `opp` of `tri` runs from u to w. `xu_edge`/`xw_edge`: the mesh edge
// (triangle, index) that contains the segment x-u / x-w, or -1 when that segment crosses the
// interior of `tri`.
struct FanEntry {
  int u, w, tri, opp;
  int xu_tri, xu_edge, xw_tri, xw_edge;
};

void fan_of(const std::vector<std::array<int, 3>>& tris, const PlanarAdjacency& adj, const PlanarLocation& loc,
            std::vector<FanEntry>& fan) {
  fan.clear();
  const auto& T = tris[loc.triangle];
  if (loc.kind == PlanarLocation::Kind::Vertex) {
    const int v = T[loc.index];
    for (int k = adj.star_begin[v]; k < adj.star_begin[v + 1]; ++k) {
      const int t = adj.star[k];
      const auto& S = tris[t];
      const int i = S[0] == v ? 0 : (S[1] == v ? 1 : 2);
      fan.push_back({S[(i + 1) % 3], S[(i + 2) % 3], t, (i + 1) % 3, t, i, t, (i + 2) % 3});
    }
  } else if (loc.kind == PlanarLocation::Kind::Edge) {
    const int t = loc.triangle, i = loc.index;
    const int a = T[i], b = T[(i + 1) % 3], c = T[(i + 2) % 3];
    fan.push_back({b, c, t, (i + 1) % 3, t, i, -1, -1});
    fan.push_back({c, a, t, (i + 2) % 3, -1, -1, t, i});
    const int n = adj.neighbor[t][i];
    if (n >= 0) {
      const int j = adj.neighbor_edge[t][i];
      const auto& N = tris[n];  // N[j] = b, N[j+1] = a
      const int d = N[(j + 2) % 3];
      fan.push_back({a, d, n, (j + 1) % 3, n, j, -1, -1});
      fan.push_back({d, b, n, (j + 2) % 3, -1, -1, n, j});
    }
  } else {
    const int t = loc.triangle;
    for (int i = 0; i < 3; ++i) fan.push_back({T[i], T[(i + 1) % 3], t, i, -1, -1, -1, -1});
  }
}

[[noreturn]] void leaves(const std::string& where) {
  throw Error(ErrorKind::InvalidArgument, "a segment leaves the triangulated region " + where);
}

}  // namespace

PlanarLocation walk_segment(const std::vector<Point2q>& pos, const std::vector<std::array<int, 3>>& tris,
                            const PlanarAdjacency& adj, const PlanarLocation& start, const Point2q& p,
                            const Point2q& q, std::vector<WalkStep>* steps) {
  auto emit = [&](const WalkStep& s) {
    if (steps) steps->push_back(s);
  };
  if (same_point(p, q)) return start;
  std::vector<FanEntry> fan;
  // State: at a point (`at`, whose position is `x`) or entering triangle `cur` across its edge `cur_edge`.
  bool at_point = true;
  PlanarLocation at = start;
  Point2q x = p;
  int cur = -1, cur_edge = -1;
  const std::size_t bound = pos.size() + tris.size() + 2;  // every iteration reaches a new vertex or triangle
  for (std::size_t iter = 0; iter <= bound; ++iter) {
    if (at_point) {
      fan_of(tris, adj, at, fan);
      bool moved = false;
      for (const FanEntry& f : fan) {
        const Point2q &pu = pos[f.u], &pw = pos[f.w];
        const Sign su = orient2d(x, pu, q), sw = orient2d(x, pw, q);
        int along = -1, along_tri = -1, along_edge = -1;
        if (su == Sign::Zero && sign(dot(x, pu, q)) == Sign::Positive) {
          along = f.u, along_tri = f.xu_tri, along_edge = f.xu_edge;
        } else if (sw == Sign::Zero && sign(dot(x, pw, q)) == Sign::Positive) {
          along = f.w, along_tri = f.xw_tri, along_edge = f.xw_edge;
        }
        if (along >= 0) {
          WalkStep s;
          if (along_edge >= 0) {
            s.medium = WalkStep::Medium::Edge, s.triangle = along_tri, s.edge = along_edge;
          } else {
            s.medium = WalkStep::Medium::Face, s.triangle = f.tri;
          }
          const Point2q& pa = pos[along];
          const int c = cmp(dot(x, q, pa), dot(x, pa, pa));
          if (c == 0) {  // q is the vertex
            s.next = WalkStep::Next::Vertex, s.vertex = along;
            emit(s);
            const auto& S = tris[f.tri];
            return {PlanarLocation::Kind::Vertex, f.tri, S[0] == along ? 0 : (S[1] == along ? 1 : 2)};
          }
          if (c < 0) {  // q strictly between x and the vertex
            s.next = WalkStep::Next::End;
            emit(s);
            if (along_edge >= 0) return {PlanarLocation::Kind::Edge, along_tri, along_edge};
            return {PlanarLocation::Kind::Face, f.tri, 0};
          }
          s.next = WalkStep::Next::Vertex, s.vertex = along;
          emit(s);
          const auto& S = tris[f.tri];
          at = {PlanarLocation::Kind::Vertex, f.tri, S[0] == along ? 0 : (S[1] == along ? 1 : 2)};
          x = pa;
          moved = true;
          break;
        }
        if (su == Sign::Positive && sw == Sign::Negative) {  // through the interior of the fan triangle
          WalkStep s;
          s.medium = WalkStep::Medium::Face, s.triangle = f.tri;
          const Sign o = orient2d(pu, pw, q);
          if (o == Sign::Positive) {
            s.next = WalkStep::Next::End;
            emit(s);
            return {PlanarLocation::Kind::Face, f.tri, 0};
          }
          if (o == Sign::Zero) {
            s.next = WalkStep::Next::End;
            emit(s);
            return {PlanarLocation::Kind::Edge, f.tri, f.opp};
          }
          s.next = WalkStep::Next::Crossing, s.cross_triangle = f.tri, s.cross_edge = f.opp;
          emit(s);
          const int n = adj.neighbor[f.tri][f.opp];
          if (n < 0) leaves("across boundary edge (" + std::to_string(f.u) + ", " + std::to_string(f.w) + ")");
          cur = n, cur_edge = adj.neighbor_edge[f.tri][f.opp];
          at_point = false;
          moved = true;
          break;
        }
      }
      if (!moved) {
        if (at.kind == PlanarLocation::Kind::Vertex) leaves("at vertex " + std::to_string(tris[at.triangle][at.index]));
        leaves("at its start point");
      }
    } else {
      // Entering `cur` across its edge cur_edge = (b, a); c is the third corner.
      const auto& T = tris[cur];
      const int j = cur_edge;
      const int b = T[j], a = T[(j + 1) % 3], c = T[(j + 2) % 3];
      const Sign o1 = orient2d(pos[a], pos[c], q), o2 = orient2d(pos[c], pos[b], q);
      WalkStep s;
      s.medium = WalkStep::Medium::Face, s.triangle = cur;
      if (o1 != Sign::Negative && o2 != Sign::Negative) {
        if (o1 == Sign::Zero && o2 == Sign::Zero) {
          s.next = WalkStep::Next::Vertex, s.vertex = c;
          emit(s);
          return {PlanarLocation::Kind::Vertex, cur, (j + 2) % 3};
        }
        s.next = WalkStep::Next::End;
        emit(s);
        if (o1 == Sign::Zero) return {PlanarLocation::Kind::Edge, cur, (j + 1) % 3};
        if (o2 == Sign::Zero) return {PlanarLocation::Kind::Edge, cur, (j + 2) % 3};
        return {PlanarLocation::Kind::Face, cur, 0};
      }
      const Sign sc = orient2d(p, q, pos[c]);
      if (sc == Sign::Zero) {
        s.next = WalkStep::Next::Vertex, s.vertex = c;
        emit(s);
        at = {PlanarLocation::Kind::Vertex, cur, (j + 2) % 3};
        x = pos[c];
        at_point = true;
        continue;
      }
      const Sign sa = orient2d(p, q, pos[a]);
      const int e = (sc == sa) ? (j + 2) % 3 : (j + 1) % 3;  // exit edge: (c, b) or (a, c)
      s.next = WalkStep::Next::Crossing, s.cross_triangle = cur, s.cross_edge = e;
      emit(s);
      const int n = adj.neighbor[cur][e];
      if (n < 0) leaves("across boundary edge (" + std::to_string(T[e]) + ", " + std::to_string(T[(e + 1) % 3]) + ")");
      cur_edge = adj.neighbor_edge[cur][e];
      cur = n;
    }
  }
  throw Error(ErrorKind::Internal, "straight walk exceeded its step bound (triangulation not planar?)");
}

PlanarLocation locate_point(const std::vector<Point2q>& pos, const std::vector<std::array<int, 3>>& tris,
                            const PlanarAdjacency& adj, int from, const Point2q& q) {
  if (from < 0 || from + 1 >= static_cast<int>(adj.star_begin.size()) || adj.star_begin[from] == adj.star_begin[from + 1])
    throw Error(ErrorKind::InvalidArgument, "locate_point: start vertex is used by no triangle", {from});
  const int t = adj.star[adj.star_begin[from]];
  const auto& S = tris[t];
  PlanarLocation start{PlanarLocation::Kind::Vertex, t, S[0] == from ? 0 : (S[1] == from ? 1 : 2)};
  return walk_segment(pos, tris, adj, start, pos[from], q, nullptr);
}

}  // namespace igm
