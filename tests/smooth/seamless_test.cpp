// Tests of the seamless structure derived from exact corner UVs (smooth/seamless.h).
#include <doctest/doctest.h>

#include <map>
#include <set>
#include <utility>

#include "igm/core/error.h"
#include "igm/smooth/seamless.h"
#include "open_igm.h"
#include "smooth_fixture.h"

using namespace igm;
using igm_test::pipeline_igm;
using igm_test::square_torus;

namespace {

// Every corner is its vertex's UV carried by the corner's map, and every transition carries both
// ends of its edge from one face's chart to the other's: the definitions, checked exactly.
void check_definitions(const IgmMesh& igm, const SeamlessStructure& s) {
  const TriMesh& m = s.mesh;
  int wrong_corners = 0, wrong_edges = 0;
  for (int c = 0; c < m.num_halfedges(); ++c) {
    const Point2q uv = apply(s.corner_motion[c], s.vertex_uv[m.origin(c)]);
    const Point2q& want = igm.corner_uv[c / 3][c % 3];
    if (uv.x != want.x || uv.y != want.y) ++wrong_corners;
    const int t = m.twin(c);
    if (t < 0) {  // a boundary half-edge: no transition
      if (!s.transition[c].is_identity()) ++wrong_edges;
      continue;
    }
    const Point2q a = apply(s.transition[c], igm.corner_uv[c / 3][c % 3]);
    const Point2q b = apply(s.transition[c], igm.corner_uv[c / 3][TriMesh::next(c) % 3]);
    const Point2q& a_twin = igm.corner_uv[t / 3][TriMesh::next(t) % 3];
    const Point2q& b_twin = igm.corner_uv[t / 3][t % 3];
    if (a.x != a_twin.x || a.y != a_twin.y || b.x != b_twin.x || b.y != b_twin.y) ++wrong_edges;
    if (!(s.transition[t] == inverse(s.transition[c]))) ++wrong_edges;
  }
  CHECK(wrong_corners == 0);
  CHECK(wrong_edges == 0);
  for (int v = 0; v < m.num_vertices(); ++v)
    CHECK(s.corner_motion[s.reference_corner[v]].is_identity());
}

}  // namespace

TEST_CASE("motions: apply, compose and inverse by hand") {
  const GridMotion r{1, 2, -3};  // (x, y) -> (-y + 2, x - 3)
  const Point2q p{Rational(1, 2), Rational(5)};
  const Point2q q = apply(r, p);
  CHECK(q.x == -3);
  CHECK(q.y == Rational(-5, 2));
  const GridMotion twice =
      compose(r, r);  // (x, y) -> (-(x - 3) + 2, (-y + 2) - 3) = (-x + 5, -y - 1)
  CHECK(twice == GridMotion{2, 5, -1});
  const Point2q back = apply(inverse(r), q);
  CHECK(back.x == p.x);
  CHECK(back.y == p.y);
  CHECK(compose(inverse(r), r).is_identity());
  CHECK_FALSE(r.is_identity());
}

TEST_CASE("the square torus: translations by the torus size across its seams, no cones") {
  const IgmMesh igm = square_torus(4);
  const SeamlessStructure s = seamless_structure(igm);
  check_definitions(igm, s);
  for (int v = 0; v < 16; ++v) CHECK(s.angle_index[v] == 4);
  // The seams are the 4 edges at u = 0 = 4 and the 4 at v = 0 = 4: translations by (+-4, 0),
  // (0, +-4); every other edge (and every rotation) is the identity.
  std::map<std::pair<long, long>, int> translations;
  for (int h = 0; h < s.mesh.num_halfedges(); ++h) {
    CHECK(s.transition[h].k == 0);
    if (!s.transition[h].is_identity())
      ++translations[{s.transition[h].tx.get_si(), s.transition[h].ty.get_si()}];
  }
  CHECK(translations ==
        std::map<std::pair<long, long>, int>{{{-4, 0}, 4}, {{4, 0}, 4}, {{0, -4}, 4}, {{0, 4}, 4}});
  // Vertex 0 = (0, 0) has its corners at (0, 0), (4, 0), (0, 4) and (4, 4): its reference corner
  // is its last one in face order, in the last face, at (4, 4).
  CHECK(s.reference_corner[0] == 3 * 31 + 1);
  CHECK(s.vertex_uv[0].x == 4);
  CHECK(s.vertex_uv[0].y == 4);
  std::set<std::pair<long, long>> copies;
  for (int c = 0; c < s.mesh.num_halfedges(); ++c)
    if (s.mesh.origin(c) == 0)
      copies.insert({s.corner_motion[c].tx.get_si(), s.corner_motion[c].ty.get_si()});
  CHECK(copies == std::set<std::pair<long, long>>{{0, 0}, {-4, 0}, {0, -4}, {-4, -4}});
}

TEST_CASE("a pipeline IGM of genus 2: rotations, cones and angles as the certifier counts them") {
  const IgmMesh igm = pipeline_igm(2, 300, 1);
  const SeamlessStructure s = seamless_structure(igm);
  check_definitions(igm, s);
  int rotated = 0;
  for (const GridMotion& t : s.transition) rotated += t.k != 0;
  CHECK(rotated > 0);
  const certify::Report report = igm_test::certify_uv(igm, igm.corner_uv);
  REQUIRE(report.valid());
  std::map<std::int64_t, std::int64_t> angles;
  for (int k : s.angle_index) ++angles[k];
  CHECK(angles == report.check(4)->histogram);
  // The layout's cones (pipeline.h): root 8g, centre 3g, 3g inner points of index 3.
  int cones = 0;
  for (int v = 0; v < s.num_vertices(); ++v)
    if (s.is_cone(v)) {
      ++cones;
      CHECK(s.vertex_uv[v].x.get_den() == 1);
      CHECK(s.vertex_uv[v].y.get_den() == 1);
    }
  CHECK(cones == 2 + 3 * 2);
}

TEST_CASE("invalid maps are rejected with the element") {
  SUBCASE("a flipped triangle: the face") {
    IgmMesh igm = square_torus(4);
    std::swap(igm.corner_uv[7][1], igm.corner_uv[7][2]);
    const auto e = igm_test::error_of([&] { seamless_structure(igm); });
    REQUIRE(e.has_value());
    CHECK(e->kind() == ErrorKind::InvalidArgument);
    CHECK(e->elements() == std::vector<std::int64_t>{7});
  }
  SUBCASE("an edge without a rigid transition: its two vertices") {
    IgmMesh igm = square_torus(4);
    igm.corner_uv[0][1].x =
        Rational(4, 3);  // face 0 (0,0),(1,0),(1,1): vertex 1's copy moved alone
    const auto e = igm_test::error_of([&] { seamless_structure(igm); });
    REQUIRE(e.has_value());
    CHECK(e->kind() == ErrorKind::InvalidArgument);
    REQUIRE(e->elements().size() == 2);
    CHECK((e->elements()[0] == 1 || e->elements()[1] == 1));
  }
  SUBCASE("cones off the integer points: the vertex (and the certifier agrees)") {
    // Shifting every UV of the genus-0 map by (1/2, 0) keeps its transitions x -> +-x + t rigid
    // (t becomes t + (1, 0) where x -> -x) but moves its four pi-cones to half-integer points.
    IgmMesh igm = pipeline_igm(0, 200, 2);
    for (auto& tri : igm.corner_uv)
      for (Point2q& p : tri) p.x += Rational(1, 2);
    CHECK_FALSE(igm_test::certify_uv(igm, igm.corner_uv).valid());
    const auto e = igm_test::error_of([&] { seamless_structure(igm); });
    REQUIRE(e.has_value());
    CHECK(e->kind() == ErrorKind::InvalidArgument);
    REQUIRE(e->elements().size() == 1);
    CHECK(std::string(e->what()).find("cone") != std::string::npos);
  }
  SUBCASE("a vertex used by no face") {
    IgmMesh igm = square_torus(4);
    igm.positions.push_back({9, 9, 9});
    const auto e = igm_test::error_of([&] { seamless_structure(igm); });
    REQUIRE(e.has_value());
    CHECK(e->kind() == ErrorKind::InvalidArgument);
    CHECK(e->elements() == std::vector<std::int64_t>{16});
  }
}

// ---- surfaces with boundary and several components ----

namespace {

// The structure's boundary bookkeeping against the certifier's report with allow_boundary and
// allow_components: boundary vertices, boundary angles (histogram), loops, components, genus.
void check_against_certifier(const IgmMesh& igm, const SeamlessStructure& s) {
  const certify::Report r =
      certify::certify_igm(certify_input(igm, igm.corner_uv), igm_test::open_options());
  REQUIRE(r.valid());
  std::map<std::int64_t, std::int64_t> interior, boundary;
  for (int v = 0; v < s.num_vertices(); ++v)
    ++(s.boundary[v] ? boundary : interior)[s.angle_index[v]];
  CHECK(interior == r.check(4)->histogram);
  CHECK(boundary == r.check(4)->boundary_histogram);
  CHECK(s.boundary_loops == *r.boundary_loops);
  CHECK(s.components == static_cast<int>(r.components.size()));
  CHECK(s.genus == *r.genus);
  CHECK(static_cast<std::int64_t>(s.boundary_edges.size()) == r.num_boundary_edges);
}

}  // namespace

TEST_CASE(
    "the square disk: four corners fixed, the sides' vertices slide along u = 0, n or v = 0, n") {
  const int n = 4;
  const certify_test::GridPatch g = certify_test::square_disk(n);
  const IgmMesh igm = igm_test::lifted(g.igm, igm_test::bumped);
  const SeamlessStructure s = seamless_structure(igm);
  check_definitions(igm, s);
  check_against_certifier(igm, s);
  CHECK(s.components == 1);
  CHECK(s.boundary_loops == 1);
  CHECK(s.genus == 0);
  CHECK(s.boundary_edges.size() == std::size_t(4 * n));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      CAPTURE(i);
      CAPTURE(j);
      const int v = g.id(i, j);
      const bool side_u = i == 0 || i == n, side_v = j == 0 || j == n;
      CHECK(bool(s.boundary[v]) == (side_u || side_v));
      CHECK(s.angle_index[v] == (side_u && side_v ? 1 : side_u || side_v ? 2 : 4));
      CHECK(s.is_cone(v) == (side_u && side_v));
      // the isoline's coordinate: u on the sides u = 0, n, v on the sides v = 0, n
      CHECK(s.isoline_axis[v] == (side_u && side_v ? -1 : side_u ? 0 : side_v ? 1 : -1));
      if (s.boundary[v]) {  // the reference corner's outgoing edge is a boundary edge
        CHECK(s.mesh.twin(s.reference_corner[v]) < 0);
        CHECK(s.mesh.origin(s.reference_corner[v]) == v);
      }
    }
  for (const BoundaryIsoline& e : s.boundary_edges) {
    const Point2q &a = igm.corner_uv[e.halfedge / 3][e.halfedge % 3],
                  &b = igm.corner_uv[e.halfedge / 3][TriMesh::next(e.halfedge) % 3];
    CHECK((e.axis == 0 ? a.x : a.y) == Rational(e.value));
    CHECK((e.axis == 0 ? b.x : b.y) == Rational(e.value));
    CHECK((e.value == 0 || e.value == n));
  }
}

TEST_CASE("cylinder, L-shape, slit, pillow with a hole, two components: angles, loops, genus") {
  struct Case {
    const char* name;
    IgmMesh igm;
    int loops, components, genus;
    std::map<int, int> boundary_angles;  // boundary angle index -> vertices
    std::map<int, int> interior_cones;   // interior angle index != 4 -> vertices
  };
  const Case cases[] = {
      {"cylinder 5 x 3", igm_test::tube(5, 3), 2, 1, 0, {{2, 10}}, {}},
      {"L-shape 2", igm_test::lifted(certify_test::l_shape(2).igm, igm_test::bumped), 1, 1, 0,
       {{1, 5}, {2, 10}, {3, 1}}, {}},
      {"slit 4, cut 2 long",
       igm_test::lifted(certify_test::slit_square(4, 2, 2).igm, igm_test::bumped), 1, 1, 0,
       {{1, 6}, {2, 13}, {4, 1}}, {}},
      {"pillow 3 with a hole", igm_test::inflated_pillow_with_hole(3, 1, 1), 1, 1, 0,
       {{3, 4}}, {{2, 4}}},
      {"disk 2 and torus 3", igm_test::disk_and_torus(2, 3), 1, 2, 1, {{1, 4}, {2, 4}}, {}},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const SeamlessStructure s = seamless_structure(c.igm);
    check_definitions(c.igm, s);
    check_against_certifier(c.igm, s);
    CHECK(s.boundary_loops == c.loops);
    CHECK(s.components == c.components);
    CHECK(s.genus == c.genus);
    std::map<int, int> boundary_angles, interior_cones;
    int sliding = 0;
    for (int v = 0; v < s.num_vertices(); ++v) {
      if (s.boundary[v]) ++boundary_angles[s.angle_index[v]];
      if (!s.boundary[v] && s.is_cone(v)) ++interior_cones[s.angle_index[v]];
      sliding += s.slides(v);
      if (s.is_cone(v)) {
        CHECK(s.vertex_uv[v].x.get_den() == 1);
        CHECK(s.vertex_uv[v].y.get_den() == 1);
        CHECK_FALSE(s.slides(v));
      }
    }
    CHECK(boundary_angles == c.boundary_angles);
    CHECK(interior_cones == c.interior_cones);
    CHECK(sliding == (c.boundary_angles.count(2) ? c.boundary_angles.at(2) : 0));
  }
}

TEST_CASE(
    "open IGMs refused with the element: a boundary edge off its isoline, a slit tip off the "
    "grid") {
  SUBCASE("a straight boundary vertex moved off its side: its two boundary edges") {
    certify_test::GridPatch g = certify_test::square_disk(3);
    const int v = g.id(1, 0);
    certify_test::move_vertex(g.igm, v, certify_test::uv(1, mpq_class(1, 10)));
    const IgmMesh igm = igm_test::lifted(g.igm, igm_test::bumped);
    const certify::Report r = certify::certify_igm(g.igm, igm_test::open_options());
    CHECK(certify_test::has_edge_witness(*r.check(3), g.id(0, 0), v));
    const auto e = igm_test::error_of([&] { seamless_structure(igm); });
    REQUIRE(e.has_value());
    CHECK(e->kind() == ErrorKind::InvalidArgument);
    CHECK(std::string(e->what()).find("isoline") != std::string::npos);
    const std::vector<std::int64_t> ids = e->elements();
    CHECK((ids == std::vector<std::int64_t>{g.id(0, 0), v} ||
           ids == std::vector<std::int64_t>{v, g.id(2, 0)}));
  }
  SUBCASE("the tip of a slit (boundary angle 2 pi) half a unit up: not at an integer point") {
    certify_test::GridPatch g = certify_test::slit_square(4, 2, 2);
    const int tip = g.id(2, 2);
    certify_test::move_vertex(g.igm, tip, certify_test::uv(2, mpq_class(5, 2)));
    const certify::Report r = certify::certify_igm(g.igm, igm_test::open_options());
    CHECK(certify_test::has_witness(*r.check(4), "vertex", tip));
    const auto e = igm_test::error_of(
        [&] { seamless_structure(igm_test::lifted(g.igm, igm_test::bumped)); });
    REQUIRE(e.has_value());
    CHECK(e->kind() == ErrorKind::InvalidArgument);
    CHECK(e->elements() == std::vector<std::int64_t>{tip});
    CHECK(std::string(e->what()).find("boundary corner") != std::string::npos);
  }
}
