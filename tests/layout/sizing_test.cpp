#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "igm/core/error.h"
#include "igm/embed/polygon.h"
#include "igm/layout/sizing.h"

using namespace igm;

namespace {

QuadLayout build(int g, LayoutKind kind) {
  const auto corners = canonical_polygon(g);
  LayoutOptions o;
  o.kind = kind;
  return make_layout(corners, polygon_centre(corners), canonical_side_mates(g), o);
}

}  // namespace

TEST_CASE("sizing: the floor (paper 3 for loops, kite 2 for some double spokes, spread 1)") {
  for (int g : {2, 3, 6}) {
    CAPTURE(g);
    const auto paper = minimum_chord_counts(build(g, LayoutKind::Paper));
    CHECK(*std::max_element(paper.begin(), paper.end()) == 3);
    const auto kite = minimum_chord_counts(build(g, LayoutKind::Kite));
    CHECK(*std::max_element(kite.begin(), kite.end()) == 2);
    const auto spread = minimum_chord_counts(build(g, LayoutKind::Spread));
    CHECK(*std::max_element(spread.begin(), spread.end()) == 1);
  }
  // A torus's one quad: its sides are loops at the root.
  const auto torus = minimum_chord_counts(build(1, LayoutKind::Spread));
  CHECK(torus == std::vector<int>{3, 3});
}

TEST_CASE("sizing: counts by the mean length of a chord's edges over H, rounded, at least the minimum") {
  const QuadLayout L = build(2, LayoutKind::Spread);
  // Lengths: surface edge e has length e + 1, so each chord's mean is computable by hand.
  std::vector<double> len(L.num_surface_edges);
  for (int e = 0; e < L.num_surface_edges; ++e) len[e] = e + 1;
  SizingOptions o;
  o.edge_length = 2.5;
  const Sizing s = size_layout(L, len, o);
  std::vector<double> sum(L.num_chords, 0);
  std::vector<int> n(L.num_chords, 0);
  for (int e = 0; e < L.num_surface_edges; ++e) sum[L.chord[e]] += len[e], ++n[L.chord[e]];
  std::int64_t quads = 0;
  for (int c = 0; c < L.num_chords; ++c)
    CHECK(s.chord_count[c] == std::max(1, static_cast<int>(std::nearbyint(sum[c] / n[c] / 2.5))));
  for (std::size_t q = 0; q < L.quads.size(); ++q) {
    const int a = s.chord_count[L.chord[L.surface_edge[L.quad_edge[q][0]]]];
    const int b = s.chord_count[L.chord[L.surface_edge[L.quad_edge[q][1]]]];
    CHECK(s.quad_size[q][0] == a);
    CHECK(s.quad_size[q][1] == b);
    // Opposite sides of every quad have the same count.
    CHECK(s.edge_count[L.surface_edge[L.quad_edge[q][2]]] == a);
    CHECK(s.edge_count[L.surface_edge[L.quad_edge[q][3]]] == b);
    quads += std::int64_t(a) * b;
  }
  CHECK(s.quads == quads);
  CHECK(s.edge_length == 2.5);
}

TEST_CASE("sizing: a quad count target is met within a quarter from 1,000 to 100,000, more quads for a smaller H") {
  const QuadLayout L = build(3, LayoutKind::Spread);
  std::vector<double> len(L.num_surface_edges);
  for (int e = 0; e < L.num_surface_edges; ++e) len[e] = 1 + (e * 37 % 11);  // uneven lengths
  std::int64_t last = 0;
  for (std::int64_t target : {1000, 3000, 10000, 30000, 100000}) {
    SizingOptions o;
    o.quads = target;
    const Sizing s = size_layout(L, len, o);
    CAPTURE(target);
    CHECK(std::llabs(s.quads - target) <= target / 4);
    CHECK(s.quads > last);
    last = s.quads;
  }
  // Below the layout's least count: every chord at its minimum.
  SizingOptions tiny;
  tiny.quads = 1;
  CHECK(size_layout(L, len, tiny).quads == static_cast<std::int64_t>(L.quads.size()));
}

TEST_CASE("sizing: bad options and lengths are typed errors") {
  const QuadLayout L = build(2, LayoutKind::Kite);
  std::vector<double> len(L.num_surface_edges, 1.0);
  CHECK_THROWS_AS(size_layout(L, len, SizingOptions{}), Error);
  SizingOptions o;
  o.edge_length = 1;
  CHECK_THROWS_AS(size_layout(L, std::vector<double>(3, 1.0), o), Error);
  len[0] = std::nan("");
  CHECK_THROWS_AS(size_layout(L, len, o), Error);
  len[0] = 1;
  o = SizingOptions{};
  o.resolution = 2;
  CHECK(size_layout(L, len, o).quads == 4 * 4 * 2);
  CHECK(size_layout(L, len, o).raised_chords == 0);
}

TEST_CASE("sizing: below the floor every option is raised to it, and says so") {
  const QuadLayout L = build(2, LayoutKind::Kite);  // some spokes need 2
  const std::vector<double> len(L.num_surface_edges, 1.0);
  const std::vector<int> minimum = minimum_chord_counts(L);
  const int raised = static_cast<int>(std::count(minimum.begin(), minimum.end(), 2));
  REQUIRE(raised > 0);
  SizingOptions o;
  o.resolution = 1;
  Sizing s = size_layout(L, len, o);
  CHECK(s.chord_count == minimum);
  CHECK(s.raised_chords == raised);
  CHECK(s.quads == s.floor_quads);
  o = SizingOptions{};
  o.edge_length = 10;  // round(1 / 10) = 0 quads per chord asked
  s = size_layout(L, len, o);
  CHECK(s.chord_count == minimum);
  CHECK(s.raised_chords == raised);
  o = SizingOptions{};
  o.quads = 1;
  s = size_layout(L, len, o);
  CHECK(s.quads == s.floor_quads);
  o.quads = 100000;
  s = size_layout(L, len, o);
  CHECK(s.quads > 4 * s.floor_quads);
  CHECK(s.raised_chords == 0);
}
