#include <doctest/doctest.h>

#include <map>
#include <string>

#include "igm/layout/surface_layout.h"
#include "layout_builder.h"

using namespace igm;
using namespace igm_test;

namespace {

// A gently uneven plane (z from 0 to 0.4), for open grids.
Vec3d flat_point(int i, int j) { return {double(i), double(j), 0.1 * ((i * 7 + j * 3) % 5)}; }

SurfaceLayout torus_one_patch(int n = 6, int m = 5) {
  return build_layout(grid_spec(n, m, true, true, {Rect{0, 0, n, m}}, torus_embedding(n, m)));
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Per node (arc end): the number of arc ends there.
std::map<int, int> node_degrees(const SurfaceLayout& L) {
  std::map<int, int> d;
  for (const LayoutArc& a : L.arcs) ++d[a.vertices.front()], ++d[a.vertices.back()];
  return d;
}

}  // namespace

TEST_CASE("surface layout: the subdivided cube's six faces, eight valence-3 corners, twelve arcs") {
  const SurfaceLayout L = build_layout(cube_spec(4, false));
  CHECK(check_surface_layout(L) == "");
  CHECK(L.patches.size() == 6);
  CHECK(L.arcs.size() == 12);
  const auto d = node_degrees(L);
  CHECK(d.size() == 8);
  for (const auto& [v, k] : d) CHECK(k == 3);
  for (const LayoutArc& a : L.arcs) CHECK(a.vertices.size() == 5);  // 4 edges along each cube edge
}

TEST_CASE("surface layout: a cube face split in two puts T-junctions on its neighbours") {
  const SurfaceLayout L = build_layout(cube_spec(4, true));
  CHECK(check_surface_layout(L) == "");
  CHECK(L.patches.size() == 7);
  CHECK(L.arcs.size() == 15);  // two cube edges split in two, one new arc across the top
  int two_arc_sides = 0;
  for (const LayoutPatch& P : L.patches)
    for (const auto& side : P.sides) two_arc_sides += side.size() == 2;
  CHECK(two_arc_sides == 2);  // the top sides of faces -y and +y
  const auto d = node_degrees(L);
  CHECK(d.size() == 10);  // 8 corners and 2 T-junctions of degree 3
}

TEST_CASE("surface layout: a torus as one patch, its arcs with the patch on both sides, one vertex met four times") {
  const SurfaceLayout L = torus_one_patch();
  CHECK(check_surface_layout(L) == "");
  REQUIRE(L.arcs.size() == 2);
  for (const LayoutArc& a : L.arcs) {
    CHECK(a.patch[0] == 0);
    CHECK(a.patch[1] == 0);
    CHECK(a.vertices.front() == a.vertices.back());
  }
  const LayoutAdjacency A = layout_adjacency(L);
  const PatchDisk d = patch_disk(L, A, 0);
  CHECK(d.error == "");
  int root_wedges = 0;
  for (int v : d.vertex) root_wedges += v == 0;
  CHECK(root_wedges == 4);
  // Every local vertex on the seams appears twice in the disk, the root four times: the disk has
  // (6 + 1) x (5 + 1) vertices.
  CHECK(d.vertex.size() == 7 * 6);
  CHECK(d.boundary.size() == 2 * (6 + 5));
}

TEST_CASE("surface layout: an open square of 2 x 2 patches, boundary arcs with no patch on one side") {
  const SurfaceLayout L = build_layout(
      grid_spec(4, 6, false, false, {Rect{0, 0, 2, 3}, Rect{2, 0, 4, 3}, Rect{0, 3, 2, 6}, Rect{2, 3, 4, 6}}, flat_point));
  CHECK(check_surface_layout(L) == "");
  int boundary_arcs = 0;
  for (const LayoutArc& a : L.arcs) boundary_arcs += a.patch[1] < 0 || a.patch[0] < 0;
  CHECK(boundary_arcs == 8);
  CHECK(L.arcs.size() == 12);
}

TEST_CASE("surface layout: a cylinder as one patch meets both ends of its seam twice") {
  const SurfaceLayout L = build_layout(grid_spec(8, 3, true, false, {Rect{0, 0, 8, 3}}, cylinder_embedding(8)));
  CHECK(check_surface_layout(L) == "");
  const PatchDisk d = patch_disk(L, layout_adjacency(L), 0);
  REQUIRE(d.error == "");
  std::map<int, int> wedges;
  for (int v : d.vertex) ++wedges[v];
  const int bottom = L.patches[0].sides[0].front().forward ? L.arcs[L.patches[0].sides[0].front().arc].vertices.front()
                                                           : L.arcs[L.patches[0].sides[0].front().arc].vertices.back();
  CHECK(wedges[bottom] == 2);
  CHECK(d.vertex.size() == 9 * 4);
}

TEST_CASE("surface layout: the check catches every kind of broken layout") {
  const SurfaceLayout cube = build_layout(cube_spec(3, true));
  REQUIRE(check_surface_layout(cube) == "");
  SUBCASE("sides in the wrong order") {
    SurfaceLayout L = cube;
    std::swap(L.patches[2].sides[0], L.patches[2].sides[1]);
    CHECK(contains(check_surface_layout(L), "does not continue the boundary"));
  }
  SUBCASE("a side's arcs in the wrong order (at a T-junction)") {
    SurfaceLayout L = cube;
    bool swapped = false;
    for (auto& P : L.patches)
      for (auto& side : P.sides)
        if (side.size() == 2 && !swapped) std::swap(side[0], side[1]), swapped = true;
    REQUIRE(swapped);
    CHECK(contains(check_surface_layout(L), "does not continue the boundary"));
  }
  SUBCASE("an arc used twice by a patch") {
    SurfaceLayout L = cube;
    L.patches[0].sides[0].push_back(L.patches[0].sides[0].front());
    CHECK(contains(check_surface_layout(L), "a second time"));
  }
  SUBCASE("an arc's patches swapped (left and right)") {
    SurfaceLayout L = cube;
    std::swap(L.arcs[0].patch[0], L.arcs[0].patch[1]);
    CHECK(contains(check_surface_layout(L), "the arc has patch"));
  }
  SUBCASE("a triangle labelled with the neighbouring patch: a non-arc edge between patches") {
    SurfaceLayout L = cube;
    // A triangle of patch 0 at an arc: give it the patch across that arc.
    const LayoutAdjacency A = layout_adjacency(L);
    int moved = -1;
    for (int h = 0; h < 3 * static_cast<int>(L.triangles.size()) && moved < 0; ++h)
      if (A.on_arc[h] && L.triangle_patch[h / 3] == 0) {
        L.triangle_patch[h / 3] = L.triangle_patch[A.twin[h] / 3];
        moved = h / 3;
      }
    REQUIRE(moved >= 0);
    CHECK(contains(check_surface_layout(L), "lies on no arc but joins"));
  }
  SUBCASE("an arc that leaves the surface's edges") {
    SurfaceLayout L = cube;
    L.arcs[0].vertices[1] = L.arcs[1].vertices[1];
    const std::string e = check_surface_layout(L);
    CHECK(!e.empty());
  }
  SUBCASE("an arc passing a vertex twice") {
    SurfaceLayout L = cube;
    L.arcs[0].vertices.push_back(L.arcs[0].vertices[1]);
    CHECK(contains(check_surface_layout(L), "passes a vertex twice"));
  }
  SUBCASE("an arc edge on two arcs") {
    SurfaceLayout L = cube;
    LayoutArc extra{{L.arcs[0].vertices[0], L.arcs[0].vertices[1]}, {L.arcs[0].patch[0], L.arcs[0].patch[1]}};
    L.arcs.push_back(extra);
    CHECK(contains(check_surface_layout(L), "lies on another arc too"));
  }
  SUBCASE("an input vertex located elsewhere") {
    SurfaceLayout L = cube;
    L.locations[1] = SurfacePoint::vertex(2);
    CHECK(contains(check_surface_layout(L), "input vertex"));
  }
  SUBCASE("a constructed vertex whose weights do not sum to 1") {
    SurfaceLayout L = cube;
    L.num_input_vertices = static_cast<int>(L.locations.size()) - 1;
    const int v = L.num_input_vertices;
    L.locations[v] = lerp(SurfacePoint::vertex(0), SurfacePoint::vertex(1), Rational(1, 3));
    L.locations[v].w[0] = Rational(1, 2);
    CHECK(contains(check_surface_layout(L), "sum to 1"));
  }
  SUBCASE("an empty side") {
    SurfaceLayout L = cube;
    L.patches[3].sides[2].clear();
    CHECK(contains(check_surface_layout(L), "has no arc"));
  }
  SUBCASE("a boundary arc that claims a patch on its empty side") {
    SurfaceLayout L = build_layout(grid_spec(3, 3, false, false, {Rect{0, 0, 3, 3}}, flat_point));
    REQUIRE(check_surface_layout(L) == "");
    int a = 0;
    while (L.arcs[a].patch[1] >= 0 && L.arcs[a].patch[0] >= 0) ++a;
    L.arcs[a].patch = {0, 0};
    CHECK(!check_surface_layout(L).empty());
  }
  SUBCASE("a triangle flipped") {
    SurfaceLayout L = cube;
    std::swap(L.triangles[5][0], L.triangles[5][1]);
    CHECK(contains(check_surface_layout(L), "consistently oriented"));
  }
}

TEST_CASE("surface layout: a patch that is not a disk (an annulus) is named as such") {
  // A cylinder without a seam: one patch between two boundary circles; the bottom circle split
  // into four arcs makes the four sides, the top circle is an arc of the patch too.
  const int n = 8;
  LayoutSpec spec = grid_spec(n, 2, true, false, {}, cylinder_embedding(n));
  // Boundary arcs are added by the builder; corners on the bottom circle at i = 0, 2, 4, 6.
  spec.corners.push_back({std::pair{0, 1}, std::pair{2, 3}, std::pair{4, 5}, std::pair{6, 7}});
  spec.extra_nodes = {2 * n};  // the top circle's node
  const SurfaceLayout L = build_layout(spec);
  const std::string e = check_surface_layout(L);
  CHECK(contains(e, "Euler characteristic 0"));
}

TEST_CASE("surface layout: a patch in two pieces is named as such") {
  // Two separate squares of one open grid labelled one patch: relabel the right half's triangles.
  SurfaceLayout L = build_layout(grid_spec(4, 2, false, false, {Rect{0, 0, 2, 2}, Rect{2, 0, 4, 2}}, flat_point));
  REQUIRE(check_surface_layout(L) == "");
  for (int& p : L.triangle_patch) p = 0;
  const std::string e = check_surface_layout(L);
  CHECK(!e.empty());
}
