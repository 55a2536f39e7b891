// Tests of the open surfaces' cut: check_open_cut on every result (it recomputes the
// post-conditions from the arrays), the side counts predicted by hand from genus and loops, and the
// typed errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <filesystem>
#include <limits>
#include <string>

#include "igm/core/error.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/topology/open_cut.h"
#include "random_mesh.h"
#include "test_data.h"

using namespace igm;

namespace {

// The side count the construction promises: a disk 4; genus 0 with b >= 2 loops 3b - 2 (the
// annulus: loop, leg, loop, leg^-1; each further hole adds leg, loop, leg^-1); genus g >= 1
// 4g + 3b; an odd count gets one more corner.
int predicted_sides(int genus, int loops) {
  const int k = genus == 0 ? (loops == 1 ? 4 : 3 * loops - 2) : 4 * genus + 3 * loops;
  return k + k % 2;
}

SurfaceComponent only_component(const PolygonSoup& soup) {
  SurfaceSet set = validate_surfaces(soup);
  REQUIRE(set.components.size() == 1);
  return std::move(set.components[0]);
}

// Cuts, checks everything and the counts: sides, glued and free, and the legs.
OpenCut cut_and_check(const SurfaceComponent& s, const std::string& what, const OpenCutOptions& o = {}) {
  INFO(what << ": genus " << s.genus << ", loops " << s.boundary_loops.size());
  OpenCut c = cut_open_surface(s, o);
  CHECK(check_open_cut(s, c) == "");
  const int b = static_cast<int>(s.boundary_loops.size());
  CHECK(c.genus == s.genus);
  CHECK(c.sides.size() == static_cast<std::size_t>(predicted_sides(s.genus, b)));
  int glued = 0, free_sides = 0;
  for (const OpenSide& side : c.sides) (side.mate >= 0 ? glued : free_sides) += 1;
  const int legs = s.genus == 0 ? b - 1 : b;
  CHECK(c.stats.legs == legs);
  CHECK(glued == 4 * s.genus + 2 * legs);
  CHECK(free_sides == (s.genus == 0 && b == 1 ? 4 : b + c.stats.extra_corners));
  CHECK((c.root >= 0) == (s.genus >= 1));
  return c;
}

}  // namespace

TEST_CASE("open cut: the shared open meshes and the genus 2 mesh with 3 holes") {
  IGM_REQUIRE_DATA(dir);
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir / "meshes" / "open")) {
    if (e.path().extension() != ".off") continue;
    cut_and_check(only_component(read_soup(e.path())), e.path().filename().string());
    ++n;
  }
  CHECK(n == 15);
  const SurfaceComponent dt = only_component(read_soup(dir / "meshes" / "invalid" / "double-torus-3-holes.off"));
  CHECK(dt.genus == 2);
  CHECK(dt.boundary_loops.size() == 3);
  const OpenCut c = cut_and_check(dt, "double-torus-3-holes");
  CHECK(c.sides.size() == 18);  // 4 * 2 + 3 * 3 = 17, made even
}

TEST_CASE("open cut: generated genus 0-6 with 1-10 loops") {
  for (int genus = 0; genus <= 6; ++genus)
    for (int loops : {1, 2, 3, 5, 10}) {
      GenerateOptions g;
      g.genus = genus;
      g.faces = 3000;
      g.seed = static_cast<std::uint64_t>(7 * genus + loops);
      g.boundaries = loops;
      cut_and_check(only_component(generate_mesh(g)), "generated");
    }
}

TEST_CASE("open cut: hostile geometry and refined meshes") {
  using igm_test::Geometry;
  for (int k = 0; k < static_cast<int>(Geometry::Count); ++k)
    for (int genus : {0, 1, 3}) {
      igm_test::RandomMeshSpec spec;
      spec.genus = genus;
      spec.faces = 1200;
      spec.seed = static_cast<std::uint64_t>(100 + 10 * k + genus);
      spec.boundaries = 1 + (k + genus) % 4;
      spec.edge_splits = 40;
      spec.face_splits = 40;
      spec.geometry = static_cast<Geometry>(k);
      cut_and_check(only_component(igm_test::random_mesh(spec)), igm_test::describe(spec));
    }
}

namespace {

PolygonSoup soup_of(const std::vector<Vec3d>& positions, const std::vector<std::array<int, 3>>& tris) {
  PolygonSoup s;
  s.positions = positions;
  for (const auto& t : tris) s.add_face({t[0], t[1], t[2]});
  return s;
}

// An n x n grid on a torus (R = 2, r = 1), two triangles per cell.
void torus_grid(int n, std::vector<Vec3d>& pos, std::vector<std::array<int, 3>>& tris) {
  pos.clear(), tris.clear();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / n;
      pos.push_back({(2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v)});
    }
  auto id = [n](int i, int j) { return ((i + n) % n) * n + (j + n) % n; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

// Removes pairwise vertex-disjoint triangles (visited in a seeded order) until none can go: each
// leaves a loop of 3 edges, and on a fine enough grid every vertex ends on a loop. Returns how many.
int punch(std::vector<std::array<int, 3>>& tris, int num_vertices, std::uint64_t seed) {
  std::vector<int> order(tris.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<char> taken(num_vertices, 0), removed(tris.size(), 0);
  int k = 0;
  for (int f : order) {
    const auto& t = tris[f];
    if (taken[t[0]] || taken[t[1]] || taken[t[2]]) continue;
    taken[t[0]] = taken[t[1]] = taken[t[2]] = 1;
    removed[f] = 1;
    ++k;
  }
  std::vector<std::array<int, 3>> kept;
  for (std::size_t f = 0; f < tris.size(); ++f)
    if (!removed[f]) kept.push_back(tris[f]);
  tris = std::move(kept);
  return k;
}

// A hexagon 0..5 triangulated as a fan from vertex 0 (every vertex on the boundary).
SurfaceComponent hexagon() {
  std::vector<Vec3d> pos;
  for (int i = 0; i < 6; ++i) pos.push_back({std::cos(M_PI * i / 3), std::sin(M_PI * i / 3), 0});
  return only_component(soup_of(pos, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}));
}

// The random open mesh of genus g with `loops` loops (tests/support/random_mesh.h, plain geometry).
SurfaceComponent random_open(int genus, std::int64_t faces, std::uint64_t seed, int loops) {
  igm_test::RandomMeshSpec spec;
  spec.genus = genus;
  spec.faces = faces;
  spec.seed = seed;
  spec.boundaries = loops;
  return only_component(igm_test::random_mesh(spec));
}

template <class F>
ErrorKind error_kind(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.kind();
  }
  return ErrorKind::Internal;  // nothing thrown: no kind the tests expect
}

}  // namespace

TEST_CASE("open cut: hand-made surfaces") {
  SUBCASE("one triangle: a loop of 3 gets a fourth vertex") {
    const SurfaceComponent s = only_component(soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}));
    const OpenCut c = cut_and_check(s, "triangle");
    CHECK(c.stats.boundary_splits == 1);
    CHECK(c.stats.chord_splits == 1);  // the new vertex's edge to the opposite corner
    CHECK(c.refined_loops[0].size() == 4);
    CHECK(c.disk_triangles.size() == 4);  // the split edge's face in two, and one of them again
    for (const OpenSide& side : c.sides) CHECK(side.disk_vertices.size() == 2);
  }
  SUBCASE("hexagon fan: its three diagonals are chords") {
    const OpenCut c = cut_and_check(hexagon(), "hexagon");
    CHECK(c.stats.chord_splits == 3);
    CHECK(c.stats.vertices_after == 6 + 1 + 3);  // S's, the center, the midpoints
    CHECK(c.boundary.size() == 6);
  }
  SUBCASE("annulus: loop, leg, loop, leg reversed") {
    // Two concentric squares (outer 0..3 ccw, inner 4..7), joined by 8 triangles.
    std::vector<Vec3d> pos{{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    std::vector<std::array<int, 3>> tris;
    for (int i = 0; i < 4; ++i) {
      const int a = i, b = (i + 1) % 4, p = 4 + i, q = 4 + (i + 1) % 4;
      tris.push_back({a, b, q});
      tris.push_back({a, q, p});
    }
    const SurfaceComponent s = only_component(soup_of(pos, tris));
    REQUIRE(s.boundary_loops.size() == 2);
    const OpenCut c = cut_and_check(s, "annulus");
    REQUIRE(c.sides.size() == 4);
    // Free, glued, free, glued: the leg's two copies are mates, each free side a whole loop.
    CHECK(c.sides[0].mate < 0);
    CHECK(c.sides[1].mate == 3);
    CHECK(c.sides[2].mate < 0);
    CHECK(c.sides[3].mate == 1);
    CHECK(c.sides[0].loop != c.sides[2].loop);
    for (int k : {0, 2}) CHECK(c.sides[k].disk_vertices.size() == c.refined_loops[c.sides[k].loop].size() + 1);
  }
  SUBCASE("coarse punched tori and spheres: every vertex on a loop") {
    for (int n : {4, 5, 6, 7}) {
      std::vector<Vec3d> pos;
      std::vector<std::array<int, 3>> tris;
      torus_grid(n, pos, tris);
      const int k = punch(tris, n * n, static_cast<std::uint64_t>(n));
      const SurfaceComponent s = only_component(soup_of(pos, tris));
      CHECK(s.genus == 1);
      CHECK(static_cast<int>(s.boundary_loops.size()) == k);
      cut_and_check(s, "punched torus " + std::to_string(n));
    }
    for (int genus : {0, 2, 3}) {
      GenerateOptions g;
      g.genus = genus;
      g.faces = 40;
      g.seed = 11;
      const ValidMesh v = validate(generate_closed_mesh(g));
      std::vector<std::array<int, 3>> tris;
      for (int f = 0; f < v.mesh.num_faces(); ++f) tris.push_back(v.mesh.face_vertices(f));
      const int k = punch(tris, v.mesh.num_vertices(), 3);
      const SurfaceComponent s = only_component(soup_of(v.positions, tris));
      CHECK(s.genus == genus);
      CHECK(static_cast<int>(s.boundary_loops.size()) == k);
      cut_and_check(s, "punched generated genus " + std::to_string(genus));
    }
  }
}

TEST_CASE("open cut: options") {
  const SurfaceComponent s = random_open(2, 1500, 5, 3);
  const OpenCut base = cut_and_check(s, "default");
  OpenCutOptions serial;
  serial.parallel = false;
  const OpenCut other = cut_open_surface(s, serial);
  CHECK(other.disk_to_surface == base.disk_to_surface);
  CHECK(other.boundary == base.boundary);
  OpenCutOptions loose;
  loose.tighten = false;
  const OpenCut untightened = cut_and_check(s, "untightened", loose);
  CHECK(untightened.stats.tightening.collapsed == 0);
  CHECK(base.stats.tightening.collapsed > 0);
  // A given root: an interior vertex of S of the lowest id.
  int root = 0;
  std::vector<char> on_loop(s.positions.size(), 0);
  for (const auto& L : s.boundary_loops)
    for (int v : L) on_loop[v] = 1;
  while (on_loop[root]) ++root;
  OpenCutOptions rooted;
  rooted.root = root;
  CHECK(cut_and_check(s, "rooted", rooted).root == root);
}

TEST_CASE("open cut: typed errors") {
  const SurfaceComponent hex = hexagon();
  SUBCASE("closed input") {
    const SurfaceComponent tet =
        only_component(soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
    CHECK(error_kind([&] { cut_open_surface(tet); }) == ErrorKind::Unsupported);
  }
  SUBCASE("bad loops, genus, positions, triangles") {
    SurfaceComponent s = hex;
    std::reverse(s.boundary_loops[0].begin(), s.boundary_loops[0].end());
    CHECK(error_kind([&] { cut_open_surface(s); }) == ErrorKind::InvalidArgument);
    s = hex;
    s.boundary_loops[0].pop_back();
    CHECK(error_kind([&] { cut_open_surface(s); }) == ErrorKind::InvalidArgument);
    s = hex;
    s.boundary_loops.push_back({0, 1, 2});
    CHECK(error_kind([&] { cut_open_surface(s); }) == ErrorKind::InvalidArgument);
    s = hex;
    s.genus = 1;
    CHECK(error_kind([&] { cut_open_surface(s); }) == ErrorKind::InvalidArgument);
    s = hex;
    s.positions[3].y = std::numeric_limits<double>::quiet_NaN();
    CHECK(error_kind([&] { cut_open_surface(s); }) == ErrorKind::NonFinite);
    s = hex;
    s.triangles[1][2] = 9;
    CHECK(error_kind([&] { cut_open_surface(s); }) == ErrorKind::IndexOutOfRange);
    s = hex;
    s.triangles.push_back(s.triangles[0]);
    CHECK(error_kind([&] { cut_open_surface(s); }) == ErrorKind::NonManifoldEdge);
  }
  SUBCASE("bad roots") {
    const SurfaceComponent s = random_open(1, 400, 1, 1);
    OpenCutOptions o;
    o.root = s.boundary_loops[0][0];
    CHECK(error_kind([&] { cut_open_surface(s, o); }) == ErrorKind::InvalidArgument);
    o.root = static_cast<int>(s.positions.size());
    CHECK(error_kind([&] { cut_open_surface(s, o); }) == ErrorKind::InvalidArgument);
  }
}

TEST_CASE("open cut: check_open_cut finds broken results") {
  const SurfaceComponent s = random_open(1, 600, 9, 2);
  const OpenCut good = cut_open_surface(s);
  REQUIRE(check_open_cut(s, good) == "");
  int glued = -1, free_side = -1;
  for (int k = 0; k < static_cast<int>(good.sides.size()); ++k) (good.sides[k].mate >= 0 ? glued : free_side) = k;
  REQUIRE(glued >= 0);
  REQUIRE(free_side >= 0);
  auto broken = [&](auto&& mutate) {
    OpenCut c = good;
    mutate(c);
    return check_open_cut(s, c);
  };
  CHECK(broken([&](OpenCut& c) { c.sides[glued].mate = (c.sides[glued].mate + 1) % static_cast<int>(c.sides.size()); }) != "");
  CHECK(broken([&](OpenCut& c) { c.sides[free_side].loop = 1 - c.sides[free_side].loop; }) != "");
  CHECK(broken([&](OpenCut& c) {  // two sides merged at a corner
    auto& a = c.sides[0].disk_vertices;
    const auto& b = c.sides[1].disk_vertices;
    a.insert(a.end(), b.begin() + 1, b.end());
    c.sides.erase(c.sides.begin() + 1);
  }) != "");
  CHECK(broken([&](OpenCut& c) { std::swap(c.disk_triangles[0][0], c.disk_triangles[0][1]); }) != "");
  CHECK(broken([&](OpenCut& c) { c.disk_triangles.pop_back(); }) != "");
  CHECK(broken([&](OpenCut& c) { c.disk_to_surface[c.boundary[0]] = c.disk_to_surface[c.boundary[1]]; }) != "");
  CHECK(broken([&](OpenCut& c) { std::rotate(c.boundary.begin(), c.boundary.begin() + 1, c.boundary.end()); }) != "");
  CHECK(broken([&](OpenCut& c) { c.num_surface_faces += 1; }) != "");
  CHECK(broken([&](OpenCut& c) {  // a constructed point moved onto an input vertex
    SurfacePoint& p = c.surface.constructed.back();
    p = SurfacePoint::vertex(p.v[0]);
  }) != "");
  CHECK(broken([&](OpenCut& c) {  // a constructed point moved into a face it does not touch
    SurfacePoint& p = c.surface.constructed.back();
    for (const auto& t : s.triangles)
      if (std::find(p.v.begin(), p.v.end(), t[0]) == p.v.end() && std::find(p.v.begin(), p.v.end(), t[1]) == p.v.end()) {
        p = lerp(SurfacePoint::vertex(t[0]), SurfacePoint::vertex(t[1]), make_rational(1, 2));
        break;
      }
  }) != "");
  CHECK(broken([&](OpenCut& c) { c.surface.input_positions[0].x += 1; }) != "");
  SUBCASE("an interior edge within one side (Tutte's pre-condition)") {
    // The hexagon fan as it is, without chord splits: the disk is S' s faces, corners 0, 1, 2, 3;
    // the side 3 -> 4 -> 5 -> 0 and the interior edge 0-4.
    const SurfaceComponent h = hexagon();
    OpenCut c;
    std::vector<std::array<int, 3>> tris = h.triangles;
    for (int i = 0; i < 6; ++i) tris.push_back({(i + 1) % 6, i, 6});
    c.surface.mesh = TriMesh::from_triangles(7, tris);
    c.surface.num_input_vertices = 7;
    c.surface.input_positions = h.positions;
    c.surface.input_positions.push_back({0, 0, 0});
    c.num_surface_faces = 4;
    c.boundary_loops = 1;
    c.disk_triangles = h.triangles;
    c.disk_to_surface = {0, 1, 2, 3, 4, 5};
    c.boundary = {0, 1, 2, 3, 4, 5};
    c.sides = {{{0, 1}, -1, 0}, {{1, 2}, -1, 0}, {{2, 3}, -1, 0}, {{3, 4, 5, 0}, -1, 0}};
    CHECK(check_open_cut(h, c).find("joins two vertices of one side") != std::string::npos);
    c.sides = {{{0, 1, 2}, -1, 0}, {{2, 3}, -1, 0}, {{3, 4}, -1, 0}, {{4, 5, 0}, -1, 0}};  // corners 0, 2, 3, 4
    CHECK(check_open_cut(h, c).find("joins two vertices of one side") != std::string::npos);  // 0-2
    c.sides = {{{0, 1}, -1, 0}, {{1, 2, 3}, -1, 0}, {{3, 4, 5}, -1, 0}, {{5, 0}, -1, 0}};  // corners 0, 1, 3, 5
    CHECK(check_open_cut(h, c) == "");  // 0 is on sides 3 and 0 alone, 2, 3, 4 on neither
  }
}
