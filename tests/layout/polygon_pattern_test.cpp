#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <string>

#include "certify/certify.h"
#include "igm/igm/layout_map.h"
#include "igm/layout/polygon_pattern.h"
#include "igm/layout/quantize.h"
#include "layout_builder.h"
#include "igm/output/igm_mesh.h"

using namespace igm;
using namespace igm_test;

namespace {

auto bumpy = [](int i, int j) { return Vec3d{double(i), double(j), 0.3 * std::sin(i * 0.9) * std::cos(j * 0.7)}; };

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Per node (arc end): the number of arc ends there.
std::map<int, int> node_degrees(const SurfaceLayout& L) {
  std::map<int, int> d;
  for (const LayoutArc& a : L.arcs) ++d[a.vertices.front()], ++d[a.vertices.back()];
  return d;
}

// Patch p of L as a polygon whose sides 0 and 1 are one side (their corner made straight): 3 sides.
PolygonPatch merged_corner(const SurfaceLayout& L, int p) {
  PolygonPatch poly{p, {}, {}};
  const LayoutPatch& P = L.patches[p];
  std::vector<ArcUse> s01 = P.sides[0];
  s01.insert(s01.end(), P.sides[1].begin(), P.sides[1].end());
  poly.sides = {s01, P.sides[2], P.sides[3]};
  return poly;
}

// Patch p of L as a polygon whose side 0 (one arc use) is cut in two at the arc's middle vertex, a
// new corner there: 5 sides. The arc is cut in every patch that uses it.
PolygonPatch cut_side(SurfaceLayout& L, int p) {
  const ArcUse u = L.patches[p].sides[0].front();
  REQUIRE(L.patches[p].sides[0].size() == 1);
  LayoutArc& a = L.arcs[u.arc];
  const std::size_t half = a.vertices.size() / 2;
  REQUIRE(half >= 1);
  LayoutArc b;
  b.vertices.assign(a.vertices.begin() + static_cast<std::ptrdiff_t>(half), a.vertices.end());
  b.patch = a.patch;
  a.vertices.resize(half + 1);
  const int nb = static_cast<int>(L.arcs.size());
  L.arcs.push_back(b);
  for (LayoutPatch& P : L.patches)
    for (auto& side : P.sides)
      for (std::size_t i = 0; i < side.size(); ++i)
        if (side[i].arc == u.arc) {
          if (side[i].forward) side.insert(side.begin() + static_cast<std::ptrdiff_t>(i) + 1, ArcUse{nb, true});
          else side.insert(side.begin() + static_cast<std::ptrdiff_t>(i), ArcUse{nb, false});
          break;
        }
  const LayoutPatch& P = L.patches[p];
  PolygonPatch poly{p, {{P.sides[0][0]}, {P.sides[0][1]}, P.sides[1], P.sides[2], P.sides[3]}, {}};
  return poly;
}

// Quantized at edge length H, mapped, certified (the back end of every layout).
void quantize_map_certify(const SurfaceLayout& L, double H, bool boundary) {
  QuantizeOptions qo;
  qo.edge_length = H;
  const Quantization q = quantize_layout(L, qo);
  const std::string why = std::string(to_string(q.status)) + ": " + q.reason;
  INFO(why);
  REQUIRE(q.ok());
  const LayoutMap m = map_layout(L, q.arc_length);
  certify::Options o;
  o.allow_boundary = boundary;
  const certify::Report r = certify::certify_igm(certify_input(m.igm, m.igm.corner_uv), o);
  CHECK_MESSAGE(r.valid(), certify::summary(r));
}

}  // namespace

TEST_CASE("polygon pattern: an open square as one patch with three corners: three quads around a valence-3 node, certified") {
  SurfaceLayout L = build_layout(grid_spec(6, 5, false, false, {Rect{0, 0, 6, 5}}, bumpy));
  REQUIRE(check_surface_layout(L) == "");
  const std::size_t arcs_before = L.arcs.size();
  const auto degrees_before = node_degrees(L);
  PolygonPatternStats st;
  REQUIRE(fill_polygon_patches(L, {merged_corner(L, 0)}, {}, &st) == "");
  CHECK(check_surface_layout(L) == "");
  CHECK(L.patches.size() == 3);
  CHECK(st.patterns == 1);
  CHECK(st.split_edges == 0);  // every side has vertices inside it
  // Three paths from the centre; every side cut at a middle vertex inside one of its arcs (the
  // merged side's middle is not its old corner: 5.5 of 11 edges).
  CHECK(st.split_arcs == 3);
  CHECK(L.arcs.size() == arcs_before + 3 + 3);
  int boundary_arcs = 0;
  for (const LayoutArc& a : L.arcs) boundary_arcs += a.patch[0] < 0 || a.patch[1] < 0;
  CHECK(boundary_arcs == 7);
  // New nodes: the centre (three paths) and three middle nodes (two halves and a path).
  int new_nodes = 0;
  for (const auto& [v, k] : node_degrees(L))
    if (!degrees_before.count(v)) {
      ++new_nodes;
      CHECK(k == 3);
    }
  CHECK(new_nodes == 4);
  quantize_map_certify(L, 0.5, true);
}

TEST_CASE("polygon pattern: five corners give five quads around a valence-5 node, certified") {
  SurfaceLayout L = build_layout(grid_spec(8, 6, false, false, {Rect{0, 0, 8, 6}}, bumpy));
  const PolygonPatch poly = cut_side(L, 0);
  const auto degrees_before = node_degrees(L);
  PolygonPatternStats st;
  REQUIRE(fill_polygon_patches(L, {poly}, {}, &st) == "");
  CHECK(check_surface_layout(L) == "");
  CHECK(L.patches.size() == 5);
  int valence5 = 0;
  for (const auto& [v, k] : node_degrees(L))
    if (!degrees_before.count(v)) valence5 += k == 5;
  CHECK(valence5 == 1);
  quantize_map_certify(L, 0.5, true);
}

TEST_CASE("polygon pattern: a patch of two triangles has no room until refined, then is certified") {
  SurfaceLayout L = build_layout(grid_spec(1, 1, false, false, {Rect{0, 0, 1, 1}}, bumpy));
  REQUIRE(check_surface_layout(L) == "");
  PolygonPatternStats st;
  REQUIRE(fill_polygon_patches(L, {merged_corner(L, 0)}, {}, &st) == "");
  CHECK(check_surface_layout(L) == "");
  CHECK(st.split_edges == 2);  // the two one-edge sides get their midpoint; the merged side has its old corner
  CHECK(st.refine_rounds >= 1);
  CHECK(st.added_vertices > 2);
  CHECK(L.patches.size() == 3);
  quantize_map_certify(L, 0.1, true);

  SUBCASE("with no refinement allowed, the patch is named") {
    SurfaceLayout M = build_layout(grid_spec(1, 1, false, false, {Rect{0, 0, 1, 1}}, bumpy));
    PolygonPatternOptions o;
    o.max_refine_rounds = 0;
    const std::string e = fill_polygon_patches(M, {merged_corner(M, 0)}, o);
    CHECK(contains(e, "patch 0"));
    CHECK(contains(e, "0 refinement rounds"));
  }
}

TEST_CASE("polygon pattern: on a closed cube, neighbours get T-junctions, and a degenerate polygon's lengths are infeasible") {
  // A cube face whose corner is made straight is a triangle with sides a + b, a, b: the pattern is
  // a valid layout, but its paths would need length (a + b - (a + b)) / 2 = 0, which the
  // quantization proves infeasible (the field layout then treats the patch as contradicting).
  SurfaceLayout L = build_layout(cube_spec(4, false));
  PolygonPatternStats st;
  REQUIRE(fill_polygon_patches(L, {merged_corner(L, 1)}, {}, &st) == "");
  CHECK(check_surface_layout(L) == "");
  CHECK(L.patches.size() == 8);
  int t_junction_sides = 0;  // sides of the unchanged faces made of two arcs
  for (int p = 0; p < 6; ++p)
    if (p != 1)
      for (const auto& side : L.patches[p].sides) t_junction_sides += side.size() == 2;
  CHECK(t_junction_sides == 2);  // the merged side's middle is the old corner: two T-junctions
  QuantizeOptions qo;
  qo.edge_length = 0.7;
  CHECK(quantize_layout(L, qo).status == QuantizeStatus::Infeasible);
}

TEST_CASE("polygon pattern: two neighbouring polygons, and bad polygons named") {
  SUBCASE("two patches of an open rectangle, both with three corners, share an arc") {
    SurfaceLayout L = build_layout(grid_spec(8, 5, false, false, {Rect{0, 0, 4, 5}, Rect{4, 0, 8, 5}}, bumpy));
    const std::vector<PolygonPatch> polys = {merged_corner(L, 0), merged_corner(L, 1)};
    PolygonPatternStats st;
    REQUIRE(fill_polygon_patches(L, polys, {}, &st) == "");
    CHECK(st.patterns == 2);
    CHECK(L.patches.size() == 6);
    quantize_map_certify(L, 0.5, true);
  }
  SUBCASE("seven sides") {
    SurfaceLayout L = build_layout(cube_spec(4, false));
    PolygonPatch poly{1, {L.patches[1].sides[0], L.patches[1].sides[1], L.patches[1].sides[2], L.patches[1].sides[3], {},
                          {}, {}}, {}};
    CHECK(contains(fill_polygon_patches(L, {poly}), "patch 1: 7 sides"));
  }
  SUBCASE("a patch the layout does not have") {
    SurfaceLayout L = build_layout(cube_spec(4, false));
    CHECK(contains(fill_polygon_patches(L, {PolygonPatch{9, {}, {}}}), "not a patch"));
  }
}

TEST_CASE("polygon pattern: the same layout twice") {
  SurfaceLayout A = build_layout(cube_spec(3, false)), B = A;
  REQUIRE(fill_polygon_patches(A, {merged_corner(A, 4)}) == "");
  REQUIRE(fill_polygon_patches(B, {merged_corner(B, 4)}) == "");
  CHECK(A.triangles == B.triangles);
  CHECK(A.triangle_patch == B.triangle_patch);
  REQUIRE(A.arcs.size() == B.arcs.size());
  for (std::size_t a = 0; a < A.arcs.size(); ++a) CHECK(A.arcs[a].vertices == B.arcs[a].vertices);
}

namespace {

// An open 6 x 6 square in two patches: the 3 x 3 square at the top right, and the L around it as a
// four-sided patch (corners (0,0), (6,0), (6,3), (0,6); its side 2 runs (6,3) -> (3,3) -> (3,6) ->
// (0,6)). Returns the layout and the L as a polygon with its real corners: (3,3) reflex.
std::pair<SurfaceLayout, PolygonPatch> l_shape() {
  LayoutSpec spec = grid_spec(6, 6, false, false, {Rect{0, 0, 6, 6}, Rect{3, 3, 6, 6}}, bumpy);
  auto id = [](int i, int j) { return i + 7 * j; };
  spec.corners[0] = {std::pair{id(0, 0), id(1, 0)}, std::pair{id(6, 0), id(6, 1)}, std::pair{id(6, 3), id(5, 3)},
                     std::pair{id(0, 6), id(0, 5)}};
  SurfaceLayout L = build_layout(spec);
  REQUIRE(check_surface_layout(L) == "");
  const LayoutPatch& P = L.patches[0];
  REQUIRE(P.sides[2].size() == 3);
  PolygonPatch poly{0, {P.sides[0], P.sides[1], {P.sides[2][0]}, {P.sides[2][1]}, {P.sides[2][2]}, P.sides[3]}, {1, 1, 1, 3, 1, 1}};
  return {L, poly};
}

}  // namespace

TEST_CASE("polygon pattern: an L-shaped patch (one reflex corner) is cut into two quads, certified") {
  auto [L, poly] = l_shape();
  const std::size_t arcs_before = L.arcs.size();
  PolygonPatternStats st;
  REQUIRE(fill_polygon_patches(L, {poly}, {}, &st) == "");
  CHECK(check_surface_layout(L) == "");
  CHECK(st.reflex_cuts == 1);
  CHECK(st.patterns == 0);  // both parts have four corners
  CHECK(L.patches.size() == 3);
  CHECK(L.arcs.size() == arcs_before + 1 + static_cast<std::size_t>(st.split_arcs));
  // The cut runs from the reflex corner (3,3) to the middle of a side three edges away.
  const LayoutArc& cut = L.arcs.back();
  CHECK((cut.vertices.front() == 3 + 7 * 3 || cut.vertices.back() == 3 + 7 * 3));
  CHECK(cut.vertices.size() == 4);
  quantize_map_certify(L, 0.5, true);
}

TEST_CASE("polygon pattern: a reflex corner with five convex ones: the cut, then the pattern on a part") {
  auto [L, poly] = l_shape();
  // (6,0) made straight: sides 0 and 1 one side; the polygon holds a quarter turn of field inside.
  PolygonPatch five{0, {poly.sides[0], poly.sides[2], poly.sides[3], poly.sides[4], poly.sides[5]}, {1, 1, 3, 1, 1}};
  five.sides[0].insert(five.sides[0].end(), poly.sides[1].begin(), poly.sides[1].end());
  PolygonPatternStats st;
  REQUIRE(fill_polygon_patches(L, {five}, {}, &st) == "");
  CHECK(check_surface_layout(L) == "");
  CHECK(st.reflex_cuts == 1);
  CHECK(st.patterns == 1);  // the part with three corners
  CHECK(L.patches.size() == 1 + 2 + 2);
  quantize_map_certify(L, 0.5, true);

  SUBCASE("two reflex corners are refused, naming the patch") {
    auto [M, p] = l_shape();
    p.turns[0] = 3;
    CHECK(contains(fill_polygon_patches(M, {p}), "patch 0: 2 reflex corners"));
  }
}
