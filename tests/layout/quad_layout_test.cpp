#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>

#include "igm/core/error.h"
#include "igm/embed/polygon.h"
#include "igm/layout/quad_layout.h"

using namespace igm;

namespace {

// A random fixed-point-free involution of 4g sides (the pairing of a cut without the normal form).
std::vector<int> random_mates(int g, std::uint64_t seed) {
  std::vector<int> order(4 * g);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<int> m(4 * g);
  for (int i = 0; i < 2 * g; ++i) m[order[2 * i]] = order[2 * i + 1], m[order[2 * i + 1]] = order[2 * i];
  return m;
}

// Layout vertices by valence, counted independently of QuadLayout::valences().
std::map<int, int> valence_histogram(const QuadLayout& L) {
  std::vector<int> v(L.num_layout_vertices, 0);
  for (const auto& q : L.quads)
    for (int p : q) ++v[L.layout_vertex[p]];
  std::map<int, int> h;
  for (int x : v) ++h[x];
  return h;
}

int root_valence(const QuadLayout& L) {
  int r = 0;
  for (const auto& q : L.quads)
    for (int p : q) r += L.layout_vertex[p] == 0;
  return r;
}

QuadLayout build(int g, LayoutKind kind, const std::vector<int>& mates, int rows = 0) {
  const auto corners = canonical_polygon(g);
  LayoutOptions o;
  o.kind = kind;
  o.rows = rows;
  return make_layout(corners, polygon_centre(corners), mates, o);
}

}  // namespace

TEST_CASE("layouts: valences by the index formula, genus 1-200, canonical and random pairings") {
  for (int g = 1; g <= 200; g += (g < 24 ? 1 : 11)) {
    CAPTURE(g);
    for (int pairing = 0; pairing < 2; ++pairing) {
      const auto mates = pairing == 0 ? canonical_side_mates(g) : random_mates(g, 7 + g);
      {
        const QuadLayout L = build(g, LayoutKind::Paper, mates);
        CHECK(check_layout(L).empty());
        CHECK(L.quads.size() == static_cast<std::size_t>(g == 1 ? 1 : 5 * g));
        const auto h = valence_histogram(L);
        if (g == 1) {
          CHECK(root_valence(L) == 4);
        } else {
          CHECK(root_valence(L) == 8 * g);  // paper: the root 8g
          CHECK(h.at(3 * g) >= 1);          // the centre 3g (for g = 2 also ... 3g = 6, one vertex)
          CHECK(h.at(3) == 3 * g);          // 3g inner points of valence 3
          CHECK(L.num_layout_vertices == 2 + 3 * g);
        }
      }
      {
        const QuadLayout L = build(g, LayoutKind::Kite, mates);
        CHECK(check_layout(L).empty());
        CHECK(L.quads.size() == static_cast<std::size_t>(4 * g));
        CHECK(root_valence(L) == 4 * g);
        const auto h = valence_histogram(L);
        if (g == 1) {
          CHECK(h.size() == 1);  // a torus: every vertex regular
        } else {
          CHECK(h.at(4 * g) == 2);  // the root and the centre
          CHECK(h.size() == 2);     // and every midpoint regular (2 + 2 quads)
          CHECK(h.at(4) == 2 * g);
        }
      }
      {
        const QuadLayout L = build(g, LayoutKind::Spread, mates);
        CHECK(check_layout(L).empty());
        CHECK(root_valence(L) == 4 * g);
        const auto h = valence_histogram(L);
        if (g == 1) {
          CHECK(h.size() == 1);
          CHECK(L.quads.size() == 1);  // a torus: the square itself
        } else {
          CHECK(h.at(5) == 4 * g - 4);  // the index of the paper's centre spread over 4g - 4 vertices
          CHECK(h.at(4 * g) == 1);      // the root alone
          for (const auto& [valence, count] : h) CHECK((valence == 4 || valence == 5 || valence == 4 * g));
        }
      }
    }
  }
}

TEST_CASE("spread layout: every row count from 1 to g gives a layout, and it grows with rows x (2g - rows)") {
  for (int g : {2, 3, 5, 9}) {
    for (int rows = 1; rows <= g; ++rows) {
      CAPTURE(g);
      CAPTURE(rows);
      const QuadLayout L = build(g, LayoutKind::Spread, canonical_side_mates(g), rows);
      CHECK(check_layout(L).empty());
      CHECK(L.quads.size() == static_cast<std::size_t>(8 * g + rows * (2 * g - rows)));
    }
  }
  CHECK_THROWS_AS(build(3, LayoutKind::Spread, canonical_side_mates(3), 4), Error);
}

TEST_CASE("layouts are built and checked exactly up to genus 1000") {
  for (int g : {500, 1000}) {
    CAPTURE(g);
    for (LayoutKind kind : {LayoutKind::Paper, LayoutKind::Kite, LayoutKind::Spread}) {
      const QuadLayout L = build(g, kind, random_mates(g, 3));
      CHECK(check_layout(L).empty());
      CHECK(root_valence(L) == (kind == LayoutKind::Paper ? 8 * g : 4 * g));
    }
  }
}

TEST_CASE("layout: chords link opposite quad sides and glued sides") {
  const QuadLayout L = build(2, LayoutKind::Spread, canonical_side_mates(2));
  // Every quad's opposite sides share a chord; glued pieces share a surface edge.
  for (std::size_t q = 0; q < L.quads.size(); ++q) {
    CHECK(L.chord[L.surface_edge[L.quad_edge[q][0]]] == L.chord[L.surface_edge[L.quad_edge[q][2]]]);
    CHECK(L.chord[L.surface_edge[L.quad_edge[q][1]]] == L.chord[L.surface_edge[L.quad_edge[q][3]]]);
  }
  std::map<std::pair<int, int>, int> piece;  // (side, piece) -> edge
  for (std::size_t e = 0; e < L.edges.size(); ++e)
    if (L.edges[e].side >= 0) piece[{L.edges[e].side, L.edges[e].piece}] = static_cast<int>(e);
  CHECK(piece.size() == 4 * 2 * 3);  // 8 sides in thirds
  for (const auto& [key, e] : piece) {
    const int mate = L.side_mate[key.first];
    const int f = piece.at({mate, 2 - key.second});
    CHECK(L.surface_edge[e] == L.surface_edge[f]);
    CHECK(L.surface_edge_forward[e] != L.surface_edge_forward[f]);
  }
  CHECK(L.num_surface_edges == static_cast<int>(L.edges.size()) - 12);
}

TEST_CASE("layout: a broken layout is refused by the check") {
  QuadLayout L = build(2, LayoutKind::Kite, canonical_side_mates(2));
  CHECK(check_layout(L).empty());
  // Move the centre outside: the kites stop being convex.
  QuadLayout bad = L;
  bad.points.back() = {Rational(5), Rational(0)};
  CHECK(!check_layout(bad).empty());
  // Pair sides split differently: refused by finish_layout.
  QuadLayout uneven = L;
  uneven.side_points[0] = {0, 1};
  CHECK_THROWS_AS(finish_layout(uneven), Error);
  // A pairing with a fixed point.
  auto mates = canonical_side_mates(2);
  mates[0] = 0;
  CHECK_THROWS_AS(build(2, LayoutKind::Kite, mates), Error);
}

TEST_CASE("layouts of open surfaces' disks: free sides, corners identified by labels, boundary index terms") {
  const auto square = canonical_polygon(1);
  const Point2q c = polygon_centre(square);
  // A disk: four free sides, four distinct boundary corners (each of boundary valence 1).
  for (LayoutKind kind : {LayoutKind::Spread, LayoutKind::Kite, LayoutKind::Paper}) {
    LayoutOptions o;
    o.kind = kind;
    const QuadLayout L = make_layout(square, c, {-1, -1, -1, -1}, o, {0, 1, 2, 3});
    CHECK(check_layout(L).empty());
    const auto boundary = L.on_boundary();
    const auto valence = L.valences();
    int corners = 0;
    for (int v = 0; v < L.num_layout_vertices; ++v) corners += boundary[v] && valence[v] == 1;
    CHECK(corners == 4);
    CHECK(L.num_surface_edges == static_cast<int>(L.edges.size()));  // nothing glued
  }
  // An annulus [loop 1, arc, loop 2, arc^-1]: corners 0, 1 on loop 1, 2, 3 on loop 2, the arc's
  // ends; every boundary vertex straight (2 quads), no interior cone (chi = 0).
  const QuadLayout A = make_layout(square, c, {-1, 3, -1, 1}, LayoutOptions{}, {0, 0, 1, 1});
  CHECK(check_layout(A).empty());
  CHECK(A.num_layout_vertices == 2);
  for (int v : A.valences()) CHECK(v == 2);
  // Eight sides (genus 0, three loops): two glued pairs of arcs, four free sides.
  const auto octagon = canonical_polygon(2);
  for (LayoutKind kind : {LayoutKind::Spread, LayoutKind::Kite, LayoutKind::Paper}) {
    LayoutOptions o;
    o.kind = kind;
    const QuadLayout L = make_layout(octagon, polygon_centre(octagon), {-1, 7, -1, 5, -1, 3, -1, 1}, o,
                                     {0, 0, 1, 2, 3, 3, 2, 1});
    CHECK(check_layout(L).empty());
  }
  // Errors: an odd polygon for the spread layout, a mate that is not an involution.
  const auto pentagon = rational_circle_polygon(5);
  CHECK_THROWS_AS(make_layout(pentagon, polygon_centre(pentagon), {-1, -1, -1, -1, -1}), Error);
  LayoutOptions kite;
  kite.kind = LayoutKind::Kite;
  CHECK(check_layout(make_layout(pentagon, polygon_centre(pentagon), {-1, -1, -1, -1, -1}, kite, {0, 1, 2, 3, 4})).empty());
  CHECK_THROWS_AS(make_layout(square, c, {-1, 3, -1, 2}, LayoutOptions{}, {0, 0, 1, 1}), Error);
}
