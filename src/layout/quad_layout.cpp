#include "igm/layout/quad_layout.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "igm/arrange/planar_walk.h"
#include "igm/core/error.h"
#include "igm/core/union_find.h"
#include "igm/embed/polygon.h"

namespace igm {

namespace {

Point2q lerp_point(const Point2q& a, const Point2q& b, const Rational& t) {
  return {Rational(a.x + t * (b.x - a.x)), Rational(a.y + t * (b.y - a.y))};
}

int add_point(QuadLayout& L, Point2q p) {
  L.points.push_back(std::move(p));
  return static_cast<int>(L.points.size()) - 1;
}

// A dyadic rational within 2^-bits of x (x finite): the layouts' placement constants are chosen in
// double and then fixed exactly.
Rational dyadic(double x, int bits) {
  const double scaled = std::nearbyint(std::ldexp(x, bits));
  Integer den;
  mpz_ui_pow_ui(den.get_mpz_t(), 2, static_cast<unsigned long>(bits));
  return make_rational(Integer(static_cast<long>(scaled)), den);
}

// Paper §4.2, Fig. 3-4: per group i of sides P0..P4 the inner points A0 = (P1+P2+C)/3,
// A1 = C + 5/6 (P2 - C), A2 = (P2+P3+C)/3 and the quads (P0 P1 A0 C), (P1 P2 A1 A0),
// (P2 P3 A2 A1), (P3 P4 C A2), (A0 A1 A2 C). (A1 = (C+P2)/2 would make (A0 A1 A2 C) reflex for large
// g: in the thin-wedge limit it needs 2/3 < lambda < 1.) Genus 1: the square itself.
void build_paper(QuadLayout& L, const Point2q& centre) {
  const int n = L.num_corners();
  if (n % 4 != 0)
    throw Error(ErrorKind::InvalidArgument, "paper layout: needs a multiple of 4 corners, got " + std::to_string(n));
  for (int s = 0; s < n; ++s) L.side_points.push_back({s, (s + 1) % n});
  if (n == 4) {
    L.quads.push_back({0, 1, 2, 3});
    return;
  }
  const int C = add_point(L, centre);
  const Rational third(1, 3);
  for (int i = 0; i < n / 4; ++i) {
    const int p0 = 4 * i, p1 = p0 + 1, p2 = p0 + 2, p3 = p0 + 3, p4 = (p0 + 4) % n;
    const Point2q &P1 = L.points[p1], &P2 = L.points[p2], &P3 = L.points[p3];
    const int a0 = add_point(L, {Rational((P1.x + P2.x + centre.x) * third), Rational((P1.y + P2.y + centre.y) * third)});
    const int a1 = add_point(L, lerp_point(centre, P2, Rational(5, 6)));
    const int a2 = add_point(L, {Rational((P2.x + P3.x + centre.x) * third), Rational((P2.y + P3.y + centre.y) * third)});
    L.quads.push_back({p0, p1, a0, C});
    L.quads.push_back({p1, p2, a1, a0});
    L.quads.push_back({p2, p3, a2, a1});
    L.quads.push_back({p3, p4, C, a2});
    L.quads.push_back({a0, a1, a2, C});
  }
}

// Every side split at its midpoint M_k; kite k = (P_k, M_k, C, M_(k-1)).
void build_kite(QuadLayout& L, const Point2q& centre) {
  const int n = L.num_corners();
  std::vector<int> mid(n);
  for (int k = 0; k < n; ++k) {
    mid[k] = add_point(L, lerp_point(L.points[k], L.points[(k + 1) % n], Rational(1, 2)));
    L.side_points.push_back({k, mid[k], (k + 1) % n});
  }
  const int C = add_point(L, centre);
  for (int k = 0; k < n; ++k) L.quads.push_back({k, mid[k], C, mid[(k + n - 1) % n]});
}

// Ring + grid (see the header): sides split at 1/3 and 2/3 (S1_k, S2_k), inner points
// Y_k = C + rho (P_k - C); corner quad (P_k, S1_k, Y_k, S2_(k-1)), ring quad (S1_k, S2_k, Y_(k+1), Y_k);
// the inner 4g-gon Y_0 .. Y_(4g-1) carries an m x n grid (m + n = 2g): its boundary runs
// G(i,0) = Y_i, G(n,j) = Y_(n+j), G(i,m) = Y_(2n+m-i), G(0,j) = Y_(-j mod 4g), and its inner
// points lie on the straight chords from Y_i to Y_(2n+m-i) at the fractions j/m (the chords are
// parallel on a regular polygon, so the inner quads are trapezoids).
// The spread layout's automatic rows for N corners: clamp(round(sqrt(N/2)), 1, N/4).
int automatic_rows(int N) {
  return std::min(N / 4, std::max(1, static_cast<int>(std::lround(std::sqrt(0.5 * N)))));
}

void build_spread(QuadLayout& L, const Point2q& centre, int rows, double ring_depth) {
  const int N = L.num_corners();
  if (N % 2 != 0)
    throw Error(ErrorKind::InvalidArgument, "spread layout: needs an even number of corners, got " + std::to_string(N));
  if (N == 4) {  // no index to spread: the square itself (as the paper's template for a torus)
    if (rows > 1) throw Error(ErrorKind::InvalidArgument, "spread layout: a square has one row, got " + std::to_string(rows));
    build_paper(L, centre);
    return;
  }
  const int m = rows > 0 ? rows : automatic_rows(N);
  if (m < 1 || m > N / 4)
    throw Error(ErrorKind::InvalidArgument, "spread layout: rows must be in 1.." + std::to_string(N / 4) + ", got " +
                                                std::to_string(m));
  const int n = N / 2 - m;
  std::vector<int> s1(N), s2(N), y(N);
  for (int k = 0; k < N; ++k) {
    s1[k] = add_point(L, lerp_point(L.points[k], L.points[(k + 1) % N], Rational(1, 3)));
    s2[k] = add_point(L, lerp_point(L.points[k], L.points[(k + 1) % N], Rational(2, 3)));
    L.side_points.push_back({k, s1[k], s2[k], (k + 1) % N});
  }
  // rho: on the regular N-gon (circumradius R) a corner's ring point at depth R (1 - rho) gives the
  // ring quads the depth R (1 - rho) cos(pi/N), against side thirds of 2 R sin(pi/N) / 3; the
  // corner quad stays convex at Y_k while Y_k lies beyond the chord S2_(k-1) S1_k, at depth
  // (2/3) R sin^2(pi/N) from the corner. The ring is made (1/6) tan(pi/N) R deep (a quarter of the
  // depth of square ring quads), at least twice the chord's depth: the disk's Tutte map puts little
  // of the surface near the polygon's sides, and deeper rings measured worse on the shared meshes of
  // genus >= 3 (docs/layouts.md).
  const double pi = std::acos(-1.0);
  const double x = pi / N;
  const double depth = std::max(ring_depth * (2.0 / 3.0) * std::tan(x), (4.0 / 3.0) * std::sin(x) * std::sin(x));
  if (!(ring_depth > 0) || !(depth < 0.9 * std::cos(x)))
    throw Error(ErrorKind::InvalidArgument, "spread layout: the ring depth " + std::to_string(ring_depth) +
                                                " does not fit a " + std::to_string(N) + "-gon");
  const Rational rho = dyadic(1.0 - depth, 24);
  for (int k = 0; k < N; ++k) y[k] = add_point(L, lerp_point(centre, L.points[k], rho));
  for (int k = 0; k < N; ++k) {
    const int prev = (k + N - 1) % N, next = (k + 1) % N;
    L.quads.push_back({k, s1[k], y[k], s2[prev]});
    L.quads.push_back({s1[k], s2[k], y[next], y[k]});
  }
  std::vector<int> inner((n + 1) * (m + 1), -1);
  auto G = [&](int i, int j) -> int {
    if (j == 0) return y[i];
    if (i == n) return y[n + j];
    if (j == m) return y[2 * n + m - i];
    if (i == 0) return y[(N - j) % N];
    return inner[j * (n + 1) + i];
  };
  for (int i = 1; i < n; ++i)
    for (int j = 1; j < m; ++j)
      inner[j * (n + 1) + i] = add_point(L, lerp_point(L.points[y[i]], L.points[y[2 * n + m - i]], make_rational(Integer(j), Integer(m))));
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) L.quads.push_back({G(i, j), G(i + 1, j), G(i + 1, j + 1), G(i, j + 1)});
}

std::string str(int x) { return std::to_string(x); }

// Half-plane class of the direction from o to a (a != o): 0 for angles in [0, pi), 1 for [pi, 2 pi).
int half_of(const Point2q& o, const Point2q& a) {
  const int sy = cmp(a.y, o.y);
  return (sy < 0 || (sy == 0 && cmp(a.x, o.x) < 0)) ? 1 : 0;
}

// Exact "angle(a - o) < angle(b - o)" in [0, 2 pi), for a, b != o.
bool angle_less(const Point2q& o, const Point2q& a, const Point2q& b) {
  const int ha = half_of(o, a), hb = half_of(o, b);
  if (ha != hb) return ha < hb;
  return orient2d(o, a, b) == Sign::Positive;
}

}  // namespace

const char* to_string(LayoutKind kind) {
  switch (kind) {
    case LayoutKind::Paper:
      return "paper";
    case LayoutKind::Kite:
      return "kite";
    case LayoutKind::Spread:
      return "spread";
    case LayoutKind::Field:
      return "field";
  }
  return "?";
}

std::vector<int> canonical_side_mates(int g) {
  if (g < 1) throw Error(ErrorKind::InvalidArgument, "canonical_side_mates: genus must be >= 1");
  std::vector<int> m(4 * static_cast<std::size_t>(g));
  for (int i = 0; i < g; ++i)
    for (int k = 0; k < 4; ++k) m[4 * i + k] = 4 * i + (k + 2) % 4;
  return m;
}

int layout_quad_count(LayoutKind kind, int n, int rows) {
  if (n < 3) throw Error(ErrorKind::InvalidArgument, "layout_quad_count: a polygon needs at least 3 corners");
  switch (kind) {
    case LayoutKind::Paper:
      return n == 4 ? 1 : 5 * n / 4;
    case LayoutKind::Kite:
      return n;
    case LayoutKind::Spread: {
      if (n == 4) return 1;
      const int m = rows > 0 ? rows : automatic_rows(n);
      return 2 * n + m * (n / 2 - m);
    }
    case LayoutKind::Field:
      throw Error(ErrorKind::InvalidArgument, "layout_quad_count: the field layout is not a layout of the schema");
  }
  return 0;
}

std::vector<char> QuadLayout::on_boundary() const {
  std::vector<char> b(num_layout_vertices, 0);
  for (std::size_t s = 0; s < side_points.size(); ++s)
    if (side_mate[s] < 0)
      for (int p : side_points[s]) b[layout_vertex[p]] = 1;
  return b;
}

std::vector<int> QuadLayout::valences() const {
  std::vector<int> v(num_layout_vertices, 0);
  for (const auto& q : quads)
    for (int p : q) ++v[layout_vertex[p]];
  return v;
}

void finish_layout(QuadLayout& L) {
  const int np = static_cast<int>(L.points.size());
  const int nq = static_cast<int>(L.quads.size());
  const int ns = static_cast<int>(L.side_points.size());
  L.edges.clear();
  L.quad_edge.assign(nq, {-1, -1, -1, -1});
  L.quad_edge_forward.assign(nq, {0, 0, 0, 0});
  std::map<std::pair<int, int>, int> index;
  for (int q = 0; q < nq; ++q)
    for (int k = 0; k < 4; ++k) {
      const int a = L.quads[q][k], b = L.quads[q][(k + 1) % 4];
      if (a < 0 || a >= np || b < 0 || b >= np || a == b)
        throw Error(ErrorKind::Internal, "layout: quad " + str(q) + " has a bad corner", {q});
      auto [it, fresh] = index.emplace(std::make_pair(std::min(a, b), std::max(a, b)), static_cast<int>(L.edges.size()));
      if (fresh) {
        LayoutEdge e;
        e.a = a, e.b = b, e.quad[0] = q, e.quad_side[0] = k;
        L.edges.push_back(e);
        L.quad_edge[q][k] = it->second;
        L.quad_edge_forward[q][k] = 1;
        continue;
      }
      LayoutEdge& e = L.edges[it->second];
      if (e.a != b || e.b != a || e.quad[1] >= 0)
        throw Error(ErrorKind::Internal, "layout: edge (" + str(a) + ", " + str(b) + ") has two quads on one side",
                    {a, b});
      e.quad[1] = q, e.quad_side[1] = k;
      L.quad_edge[q][k] = it->second;
      L.quad_edge_forward[q][k] = 0;
    }
  // Boundary edges are exactly the side pieces, each running in its side's direction.
  if (static_cast<int>(L.side_mate.size()) != ns || ns != L.num_corners())
    throw Error(ErrorKind::InvalidArgument, "layout: one side mate per polygon side is needed");
  std::vector<std::vector<int>> piece_edge(ns);
  for (int s = 0; s < ns; ++s) {
    const auto& sp = L.side_points[s];
    if (sp.size() < 2 || sp.front() != s || sp.back() != (s + 1) % ns)
      throw Error(ErrorKind::Internal, "layout: side " + str(s) + " does not run from corner to corner", {s});
    for (std::size_t j = 0; j + 1 < sp.size(); ++j) {
      auto it = index.find({std::min(sp[j], sp[j + 1]), std::max(sp[j], sp[j + 1])});
      if (it == index.end() || L.edges[it->second].quad[1] >= 0 || L.edges[it->second].a != sp[j])
        throw Error(ErrorKind::Internal, "layout: piece " + str(static_cast<int>(j)) + " of side " + str(s) +
                                             " is not a boundary edge of one quad in the side's direction",
                    {s});
      L.edges[it->second].side = s;
      L.edges[it->second].piece = static_cast<int>(j);
      piece_edge[s].push_back(it->second);
    }
  }
  for (const LayoutEdge& e : L.edges)
    if (e.quad[1] < 0 && e.side < 0)
      throw Error(ErrorKind::Internal, "layout: edge (" + str(e.a) + ", " + str(e.b) + ") has one quad but lies on no side",
                  {e.a, e.b});
  // Gluing: points and surface edges.
  UnionFind points(np), surface(L.edges.size());
  if (!L.corner_label.empty() && static_cast<int>(L.corner_label.size()) != ns)
    throw Error(ErrorKind::InvalidArgument, "layout: one label per corner is needed");
  if (L.corner_label.empty()) {
    for (int k = 1; k < ns; ++k) points.unite(0, k);  // the closed schema: every corner the root
  } else {
    std::map<int, int> first;  // label -> its first corner
    for (int k = 0; k < ns; ++k) {
      auto [it, fresh] = first.emplace(L.corner_label[k], k);
      if (!fresh) points.unite(it->second, k);
    }
  }
  for (int s = 0; s < ns; ++s) {
    const int m = L.side_mate[s];
    if (m == -1) continue;  // a free side
    if (m < 0 || m >= ns || m == s || L.side_mate[m] != s)
      throw Error(ErrorKind::InvalidArgument, "layout: the side pairing is not a fixed-point-free involution at side " +
                                                  str(s),
                  {s});
    const auto &a = L.side_points[s], &b = L.side_points[m];
    if (a.size() != b.size())
      throw Error(ErrorKind::InvalidArgument, "layout: sides " + str(s) + " and " + str(m) +
                                                  " are glued but split into different numbers of pieces",
                  {s, m});
    const std::size_t n = a.size() - 1;
    for (std::size_t j = 0; j <= n; ++j) points.unite(a[j], b[n - j]);
    for (std::size_t j = 0; j < n; ++j) surface.unite(piece_edge[s][j], piece_edge[m][n - 1 - j]);
  }
  L.layout_vertex.assign(np, -1);
  std::vector<int> id(np, -1);
  L.num_layout_vertices = 0;
  for (int p = 0; p < np; ++p) {
    const int r = points.find(p);
    if (id[r] < 0) id[r] = L.num_layout_vertices++;
    L.layout_vertex[p] = id[r];
  }
  const int ne = static_cast<int>(L.edges.size());
  L.surface_edge.assign(ne, -1);
  L.surface_edge_forward.assign(ne, 1);
  std::vector<int> sid(ne, -1);
  L.num_surface_edges = 0;
  for (int e = 0; e < ne; ++e) {
    const int r = surface.find(e);
    if (sid[r] < 0) {
      sid[r] = L.num_surface_edges++;
      L.surface_edge_forward[e] = 1;  // the first edge of a surface edge fixes its direction
    } else {
      L.surface_edge_forward[e] = 0;  // a glued mate runs the other way
    }
    L.surface_edge[e] = sid[r];
  }
  UnionFind chords(L.num_surface_edges);
  for (int q = 0; q < nq; ++q) {
    chords.unite(L.surface_edge[L.quad_edge[q][0]], L.surface_edge[L.quad_edge[q][2]]);
    chords.unite(L.surface_edge[L.quad_edge[q][1]], L.surface_edge[L.quad_edge[q][3]]);
  }
  L.chord.assign(L.num_surface_edges, -1);
  std::vector<int> cid(L.num_surface_edges, -1);
  L.num_chords = 0;
  for (int e = 0; e < L.num_surface_edges; ++e) {
    const int r = chords.find(e);
    if (cid[r] < 0) cid[r] = L.num_chords++;
    L.chord[e] = cid[r];
  }
}

std::string check_layout(const QuadLayout& L) {
  const int n = L.num_corners();
  if (n < 3 || static_cast<int>(L.points.size()) < n) return "fewer points than polygon corners";
  std::vector<Point2q> corners(L.points.begin(), L.points.begin() + n);
  if (!is_strictly_convex_ccw(corners)) return "the polygon is not strictly convex and counter-clockwise";
  for (std::size_t q = 0; q < L.quads.size(); ++q) {
    const auto& Q = L.quads[q];
    for (int i = 0; i < 4; ++i)
      if (orient2d(L.points[Q[i]], L.points[Q[(i + 1) % 4]], L.points[Q[(i + 2) % 4]]) != Sign::Positive)
        return "quad " + str(static_cast<int>(q)) + " is not strictly convex and counter-clockwise at its corner " +
               str((i + 1) % 4);
  }
  // Around every point off the boundary the quads wind exactly once: their corners there, each an
  // angle in (0, pi), follow each other counter-clockwise and pass the direction of angle 0 once.
  // With positive quads, an edge-manifold subdivision and the polygon's sides as its boundary
  // (checked below), this makes the quads a tiling of the polygon (a covering of degree one).
  {
    std::vector<std::vector<std::pair<int, int>>> star(L.points.size());  // point -> (next, prev) per corner
    for (const auto& Q : L.quads)
      for (int i = 0; i < 4; ++i) star[Q[i]].push_back({Q[(i + 1) % 4], Q[(i + 3) % 4]});
    std::vector<char> on_boundary(L.points.size(), 0);
    for (const auto& sp : L.side_points)
      for (int p : sp) on_boundary[p] = 1;
    for (std::size_t p = 0; p < L.points.size(); ++p) {
      if (on_boundary[p]) continue;
      const auto& st = star[p];
      if (st.size() < 3) return "inner point " + str(static_cast<int>(p)) + " has fewer than three quads";
      // Order the corners by chaining prev -> next (the quad after corner c starts where c's prev ends).
      std::map<int, int> by_next;
      for (std::size_t c = 0; c < st.size(); ++c) by_next[st[c].first] = static_cast<int>(c);
      int c = 0, wraps = 0;
      for (std::size_t step = 0; step < st.size(); ++step) {  // bounded by the corners at p
        auto it = by_next.find(st[c].second);
        if (it == by_next.end()) return "the quads around inner point " + str(static_cast<int>(p)) + " do not close";
        const int d = it->second;
        if (angle_less(L.points[p], L.points[st[d].first], L.points[st[c].first])) ++wraps;
        c = d;
      }
      if (c != 0 || wraps != 1)
        return "the quads around inner point " + str(static_cast<int>(p)) + " do not wind around it once";
    }
  }
  // Edges: interior ones in two quads, boundary ones side pieces.
  int boundary = 0;
  for (std::size_t e = 0; e < L.edges.size(); ++e) {
    const LayoutEdge& E = L.edges[e];
    if (E.quad[1] < 0) {
      if (E.side < 0) return "edge " + str(static_cast<int>(e)) + " has one quad and is no side piece";
      ++boundary;
    }
  }
  std::size_t pieces = 0;
  for (int s = 0; s < n; ++s) {
    const auto& sp = L.side_points[s];
    pieces += sp.size() - 1;
    const Point2q &A = corners[s], &B = corners[(s + 1) % n];
    const Rational len2 = dot(A, B, B);
    std::vector<Rational> t;
    for (int p : sp) {
      if (sign(cross(A, B, L.points[p])) != Sign::Zero) return "side point " + str(p) + " is off side " + str(s);
      t.push_back(dot(A, L.points[p], B) / len2);
    }
    for (std::size_t j = 0; j + 1 < t.size(); ++j)
      if (t[j] >= t[j + 1]) return "the points of side " + str(s) + " are not in increasing order";
    if (L.side_mate[s] < 0) continue;  // a free side: nothing to mirror
    const auto& mp = L.side_points[L.side_mate[s]];
    if (mp.size() != sp.size()) return "sides " + str(s) + " and its mate are split differently";
    const Point2q &MA = corners[L.side_mate[s]], &MB = corners[(L.side_mate[s] + 1) % n];
    const Rational mlen2 = dot(MA, MB, MB);
    for (std::size_t j = 0; j < sp.size(); ++j) {
      const Rational tm = dot(MA, L.points[mp[sp.size() - 1 - j]], MB) / mlen2;
      if (tm != 1 - t[j]) return "side " + str(s) + " and its mate are split at parameters that do not mirror";
    }
  }
  if (static_cast<std::size_t>(boundary) != pieces) return "the boundary edges are not exactly the side pieces";
  const long long V = static_cast<long long>(L.points.size()), E = static_cast<long long>(L.edges.size()),
                  F = static_cast<long long>(L.quads.size());
  if (V - E + F != 1) return "the planar subdivision has Euler characteristic " + std::to_string(V - E + F) + ", not 1";
  // The glued surface: every surface edge in two quads, or in one on a free side; then the index
  // formula with boundary terms.
  std::vector<int> edge_quads(L.num_surface_edges, 0);
  std::vector<char> free_edge(L.num_surface_edges, 0);
  for (std::size_t e = 0; e < L.edges.size(); ++e) {
    edge_quads[L.surface_edge[e]] += L.edges[e].quad[1] >= 0 ? 2 : 1;
    if (L.edges[e].side >= 0 && L.side_mate[L.edges[e].side] < 0) free_edge[L.surface_edge[e]] = 1;
  }
  for (int e = 0; e < L.num_surface_edges; ++e)
    if (edge_quads[e] != (free_edge[e] ? 1 : 2)) return "surface edge " + str(e) + " is not in two quads (or one, free)";
  const std::vector<char> on_free_side = L.on_boundary();
  long long index = 0;
  const std::vector<int> valence = L.valences();
  for (int v = 0; v < L.num_layout_vertices; ++v) index += (on_free_side[v] ? 2 : 4) - valence[v];
  const long long chi = static_cast<long long>(L.num_layout_vertices) - L.num_surface_edges + F;
  if (index != 4 * chi)
    return "the index sum is " + std::to_string(index) + ", not 4 chi = " + std::to_string(4 * chi);
  return "";
}

QuadLayout make_layout(const std::vector<Point2q>& corners, const Point2q& centre, const std::vector<int>& side_mate,
                       const LayoutOptions& options, const std::vector<int>& corner_label) {
  const int n = static_cast<int>(corners.size());
  if (n < 3) throw Error(ErrorKind::InvalidArgument, "layout: the polygon needs at least 3 corners, got " + str(n));
  if (!is_strictly_convex_ccw(corners))
    throw Error(ErrorKind::InvalidArgument, "layout: the polygon is not strictly convex and counter-clockwise");
  for (int k = 0; k < n; ++k)
    if (orient2d(corners[k], corners[(k + 1) % n], centre) != Sign::Positive)
      throw Error(ErrorKind::InvalidArgument, "layout: the centre is not strictly inside the polygon (side " + str(k) + ")",
                  {k});
  if (static_cast<int>(side_mate.size()) != n)
    throw Error(ErrorKind::InvalidArgument, "layout: " + str(n) + " sides but " +
                                                str(static_cast<int>(side_mate.size())) + " side mates");
  QuadLayout L;
  L.corners = n;
  L.kind = options.kind;
  L.points = corners;
  L.side_mate = side_mate;
  L.corner_label = corner_label;
  switch (options.kind) {
    case LayoutKind::Paper:
      build_paper(L, centre);
      break;
    case LayoutKind::Kite:
      build_kite(L, centre);
      break;
    case LayoutKind::Spread:
      build_spread(L, centre, options.rows, options.ring_depth);
      break;
    case LayoutKind::Field:
      throw Error(ErrorKind::InvalidArgument, "make_layout: the field layout is not a layout of the schema");
  }
  finish_layout(L);
  const std::string problem = check_layout(L);
  if (!problem.empty())
    throw Error(ErrorKind::Internal, std::string("layout ") + to_string(options.kind) + " on " + str(n) +
                                         " corners: " + problem);
  return L;
}

}  // namespace igm
