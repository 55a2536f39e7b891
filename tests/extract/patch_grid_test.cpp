#include <doctest/doctest.h>

#include <map>
#include <set>

#include "../igm/patch_fixture.h"
#include "generated_mesh.h"
#include "igm/core/error.h"
#include "igm/extract/patch_grid.h"

using namespace igm;

namespace {

struct Grid {
  PatchGrid grid;
  Sizing sizing;
};

Grid grid_of(const igm_test::PatchSetup& s, const SizingOptions& so) {
  Grid out;
  out.sizing = size_layout(s.layout, layout_edge_lengths(s.layout, s.mesh), so);
  out.grid = extract_patch_grids(s.layout, s.mesh, out.sizing, igm_test::tutte_maps(s, out.sizing).igm.corner_uv);
  return out;
}

certify::Report certify_grid(const PatchGrid& g, int genus) {
  certify::QuadInput in;
  in.quads = g.quads;
  in.num_vertices = static_cast<std::int64_t>(g.vertices.size());
  certify::Options o;
  o.expected_genus = genus;
  return certify::certify_quads(in, o);
}

}  // namespace

TEST_CASE("patch grid: a b quads per layout quad, a closed quad mesh of the input's genus, layout vertices once") {
  for (int g = 1; g <= 3; ++g)
    for (LayoutKind kind : {LayoutKind::Spread, LayoutKind::Kite, LayoutKind::Paper}) {
      CAPTURE(g);
      CAPTURE(to_string(kind));
      const igm_test::PatchSetup s = igm_test::patch_setup(igm_test::generated_mesh(g, 300 * g, 2), kind, false);
      SizingOptions so;
      so.quads = 300;
      const Grid G = grid_of(s, so);
      std::int64_t expected = 0;
      for (const auto& ab : G.sizing.quad_size) expected += std::int64_t(ab[0]) * ab[1];
      CHECK(static_cast<std::int64_t>(G.grid.quads.size()) == expected);
      const certify::Report r = certify_grid(G.grid, g);
      CHECK_MESSAGE(r.valid(), certify::summary(r));
      // Every layout vertex appears exactly once among the grid's vertices.
      std::map<int, int> seen;
      for (const GridVertex& v : G.grid.vertices)
        if (v.layout_vertex >= 0) ++seen[v.layout_vertex];
      CHECK(static_cast<int>(seen.size()) == s.layout.num_layout_vertices);
      for (const auto& [lv, n] : seen) CHECK(n == 1);
      // Barycentric coordinates are a convex combination.
      for (const GridVertex& v : G.grid.vertices) {
        CHECK(v.barycentric[0] + v.barycentric[1] + v.barycentric[2] == 1);
        for (const Rational& w : v.barycentric) CHECK(sgn(w) >= 0);
      }
    }
}

TEST_CASE("patch grid: --resolution N gives the paper layout its 5g N^2 quads, valences 8g, 3g and 3 at the layout vertices") {
  const int g = 2, N = 3;
  const igm_test::PatchSetup s = igm_test::patch_setup(igm_test::generated_mesh(g, 600, 4), LayoutKind::Paper, false);
  SizingOptions so;
  so.resolution = N;
  const Grid G = grid_of(s, so);
  CHECK(G.grid.quads.size() == static_cast<std::size_t>(5 * g * N * N));
  std::vector<int> valence(G.grid.vertices.size(), 0);
  for (const auto& q : G.grid.quads)
    for (int v : q) ++valence[v];
  std::multiset<int> layout_valences;
  for (std::size_t v = 0; v < G.grid.vertices.size(); ++v)
    if (G.grid.vertices[v].layout_vertex >= 0) layout_valences.insert(valence[v]);
  CHECK(layout_valences.count(8 * g) == 1);
  CHECK(layout_valences.count(3 * g) == 1);
  CHECK(layout_valences.count(3) == static_cast<std::size_t>(3 * g));
  // Below the paper layout's floor (its sides are loops at the root) the sizing raises them to it.
  so.resolution = 2;
  const Sizing raised = size_layout(s.layout, layout_edge_lengths(s.layout, s.mesh), so);
  CHECK(raised.raised_chords > 0);
  CHECK(raised.quads == raised.floor_quads);
}

TEST_CASE("patch grid: UVs that do not cover a patch's rectangle are an Internal error, not a guess") {
  const igm_test::PatchSetup s = igm_test::patch_setup(igm_test::generated_mesh(1, 300, 1), LayoutKind::Spread, false);
  SizingOptions so;
  so.resolution = 3;  // a torus's one quad has loops for sides: 3 is its least count
  const Sizing sizing = size_layout(s.layout, layout_edge_lengths(s.layout, s.mesh), so);
  std::vector<std::array<Point2q, 3>> uv = igm_test::tutte_maps(s, sizing).igm.corner_uv;
  for (auto& tri : uv)
    for (Point2q& p : tri) p.x /= 2;  // the patch now covers [0, 3/2] x [0, 3] only
  CHECK_THROWS_AS(extract_patch_grids(s.layout, s.mesh, sizing, uv), Error);
}
