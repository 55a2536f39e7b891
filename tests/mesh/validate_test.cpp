#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "igm/core/error.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"

using namespace igm;

namespace {

PolygonSoup soup_of(std::vector<Vec3d> pos, const std::vector<std::vector<std::int64_t>>& faces) {
  PolygonSoup s;
  s.positions = std::move(pos);
  for (const auto& f : faces) s.add_face(f.begin(), f.end());
  return s;
}
std::vector<Vec3d> points(int n) {
  std::vector<Vec3d> p;
  for (int i = 0; i < n; ++i) p.push_back({double(i), double(i * i % 7), double(i % 3)});
  return p;
}
// Tetrahedron on vertices a..a+3.
std::vector<std::vector<std::int64_t>> tetra(std::int64_t a) {
  return {{a, a + 2, a + 1}, {a, a + 1, a + 3}, {a, a + 3, a + 2}, {a + 1, a + 2, a + 3}};
}
std::vector<std::vector<std::int64_t>> join(std::vector<std::vector<std::int64_t>> a,
                                            const std::vector<std::vector<std::int64_t>>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}
std::vector<ErrorKind> kinds(const MeshReport& r) {
  std::vector<ErrorKind> k;
  for (const MeshProblem& p : r.problems) k.push_back(p.kind);
  return k;
}
ErrorKind thrown(const PolygonSoup& s, const ValidateOptions& o = {}) {
  try {
    validate(s, o);
  } catch (const Error& e) {
    return e.kind();
  }
  return ErrorKind::Internal;  // "nothing thrown"
}
// Every face of the validated mesh is its input polygon's triangle, possibly reversed.
void check_faces_match(const PolygonSoup& s, const ValidMesh& m) {
  REQUIRE(m.input_face.size() == static_cast<std::size_t>(m.mesh.num_faces()));
  for (int f = 0; f < m.mesh.num_faces(); ++f) {
    const auto fv = m.mesh.face_vertices(f);
    const std::size_t pf = static_cast<std::size_t>(m.input_face[f]);
    std::set<std::int64_t> poly(s.corners.begin() + std::ptrdiff_t(s.face_begin[pf]),
                                s.corners.begin() + std::ptrdiff_t(s.face_begin[pf + 1]));
    for (int v : fv) CHECK(poly.count(m.input_vertex[v]) == 1);
  }
}

}  // namespace

TEST_CASE("element problems: empty, no faces, few corners, out of range, repeated, non-finite") {
  CHECK(kinds(inspect(PolygonSoup{})) == std::vector<ErrorKind>{ErrorKind::Empty});
  CHECK(thrown(PolygonSoup{}) == ErrorKind::Empty);
  CHECK(kinds(inspect(soup_of(points(5), {}))) == std::vector<ErrorKind>{ErrorKind::NoFaces});

  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  auto pos = points(8);
  pos[2].y = nan;
  pos[5].z = -inf;
  auto faces = tetra(0);
  faces.push_back({0, 1});           // face 4: 2 corners
  faces.push_back({0, 1, 8});        // face 5: out of range
  faces.push_back({0, -1, 2});       // face 6: negative
  faces.push_back({3, 1, 3});        // face 7: repeated
  faces.push_back({0, 1, 2, 3, 1});  // face 8: repeated in a polygon
  const MeshReport r = inspect(soup_of(pos, faces));
  REQUIRE(kinds(r) == std::vector<ErrorKind>{ErrorKind::InvalidArgument, ErrorKind::IndexOutOfRange,
                                             ErrorKind::RepeatedVertex, ErrorKind::NonFinite});
  CHECK(r.problems[0].elements == std::vector<std::int64_t>{4});
  CHECK(r.problems[1].elements == std::vector<std::int64_t>{5, 6});
  CHECK(r.problems[1].count == 2);
  CHECK(r.problems[2].elements == std::vector<std::int64_t>{7, 8});
  CHECK(r.problems[3].elements == std::vector<std::int64_t>{2});  // vertex 5 is unreferenced: dropped, not fatal
  CHECK_FALSE(r.topology_checked);
  CHECK(thrown(soup_of(pos, faces)) == ErrorKind::InvalidArgument);

  // NonFinite alone does not stop the topology checks.
  auto p2 = points(4);
  p2[1].x = inf;
  const MeshReport r2 = inspect(soup_of(p2, tetra(0)));
  CHECK(kinds(r2) == std::vector<ErrorKind>{ErrorKind::NonFinite});
  CHECK(r2.topology_checked);
  CHECK(r2.edges == 6);
  CHECK(thrown(soup_of(p2, tetra(0))) == ErrorKind::NonFinite);
}

TEST_CASE("non-manifold edge names its faces") {
  // Three triangles on edge (0,1) closed into two tetrahedra sharing a triangle? Simpler: a book.
  const auto s = soup_of(points(5), {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const MeshReport r = inspect(s);
  REQUIRE(!r.problems.empty());
  CHECK(r.problems[0].kind == ErrorKind::NonManifoldEdge);
  CHECK(r.problems[0].count == 1);
  CHECK(r.problems[0].elements == std::vector<std::int64_t>{0, 1, 2});
  CHECK(r.non_manifold_edges == 1);
  CHECK(r.problems[0].message.find("edge (0, 1) has 3 faces") != std::string::npos);
  CHECK(thrown(s) == ErrorKind::NonManifoldEdge);
}

TEST_CASE("non-manifold vertex: two closed tetrahedra sharing one vertex") {
  auto faces = tetra(0);
  for (auto f : tetra(3)) faces.push_back(f);  // vertex 3 is in both
  const auto s = soup_of(points(7), faces);
  const MeshReport r = inspect(s);
  CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::NonManifoldVertex});
  CHECK(r.problems[0].elements == std::vector<std::int64_t>{3});
  CHECK(r.components == 1);
  CHECK(r.boundary_loops == 0);
  CHECK(thrown(s) == ErrorKind::NonManifoldVertex);
}

TEST_CASE("non-orientable: the 6-vertex projective plane and a Moebius strip") {
  const auto rp2 = soup_of(
      points(6),
      {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1}, {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}});
  const MeshReport r = inspect(rp2);
  CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::NonOrientable});
  CHECK_FALSE(r.orientable);
  CHECK(r.euler_characteristic == 1);
  CHECK(r.boundary_loops == 0);
  CHECK(thrown(rp2) == ErrorKind::NonOrientable);
  // Moebius strip: a band of 3 quads with a half twist.
  const auto mob = soup_of(points(6), {{0, 1, 4, 3}, {1, 2, 5, 4}, {2, 3, 0, 5}});
  const MeshReport m = inspect(mob);
  CHECK(kinds(m) == std::vector<ErrorKind>{ErrorKind::NonOrientable, ErrorKind::Boundary});
  CHECK(m.boundary_loops == 1);  // a Moebius strip has one boundary circle
  CHECK(thrown(mob) == ErrorKind::NonOrientable);
}

TEST_CASE("boundary loops and components are counted exactly") {
  CHECK(inspect(soup_of(points(3), {{0, 1, 2}})).boundary_loops == 1);
  // An open cylinder: 2 loops.
  std::vector<std::vector<std::int64_t>> cyl;
  for (int i = 0; i < 5; ++i) cyl.push_back({i, (i + 1) % 5, 5 + (i + 1) % 5, 5 + i});
  const MeshReport c = inspect(soup_of(points(10), cyl));
  CHECK(kinds(c) == std::vector<ErrorKind>{ErrorKind::Boundary});
  CHECK(c.boundary_loops == 2);
  CHECK(c.boundary_edges == 10);
  CHECK(c.problems[0].count == 2);
  // Three tetrahedra and one triangle: 4 components, one boundary loop; boundary comes first.
  auto f = join(join(tetra(0), tetra(4)), tetra(8));
  f.push_back({12, 13, 14});
  const auto s = soup_of(points(15), f);
  const MeshReport r = inspect(s);
  CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::Boundary, ErrorKind::SeveralComponents});
  CHECK(r.components == 4);
  CHECK(r.problems[1].count == 4);
  CHECK(r.problems[1].elements == std::vector<std::int64_t>{0, 4, 8, 12});
  CHECK(thrown(s) == ErrorKind::Boundary);
  const auto two = soup_of(points(8), join(tetra(0), tetra(4)));
  CHECK(thrown(two) == ErrorKind::SeveralComponents);
  CHECK(inspect(two).euler_characteristic == 4);
}

TEST_CASE("orientation repair flips the minority and warns, off, it is fatal") {
  const PolygonSoup g = generate_closed_mesh({.genus = 2, .faces = 600, .seed = 5});
  std::mt19937_64 rng(11);
  PolygonSoup s = g;
  std::vector<char> flipped(s.num_faces(), 0);
  std::int64_t nflip = 0;
  for (std::size_t f = 0; f < s.num_faces(); ++f)
    if (rng() % 5 == 0) {
      std::swap(s.corners[s.face_begin[f] + 1], s.corners[s.face_begin[f] + 2]);
      flipped[f] = 1;
      ++nflip;
    }
  REQUIRE(nflip > 0);
  // Independent count: edges whose two faces differ in flip status.
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>> edge_faces;
  for (std::size_t f = 0; f < g.num_faces(); ++f)
    for (int i = 0; i < 3; ++i) {
      std::int64_t a = g.corners[3 * f + i], b = g.corners[3 * f + (i + 1) % 3];
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  std::int64_t expect = 0;
  for (auto& [e, fs] : edge_faces) {
    REQUIRE(fs.size() == 2);
    expect += flipped[fs[0]] != flipped[fs[1]];
  }
  const MeshReport r = inspect(s);
  CHECK(r.problems.empty());
  CHECK(r.inconsistently_oriented_edges == expect);
  CHECK(r.flipped_faces == nflip);  // the minority is exactly the faces we flipped
  CHECK(r.genus == 2);
  const ValidMesh m = validate(s);
  REQUIRE(m.warnings.size() == 1);
  CHECK(m.warnings[0].find("re-oriented " + std::to_string(nflip)) == 0);
  CHECK(m.mesh.check_invariants() == "");
  // The repaired mesh has the original orientation: face f's corners equal g's face f's.
  for (int f = 0; f < m.mesh.num_faces(); ++f) {
    const auto fv = m.mesh.face_vertices(f);
    const std::size_t pf = static_cast<std::size_t>(m.input_face[f]);
    std::array<std::int64_t, 3> want = {g.corners[3 * pf], g.corners[3 * pf + 1], g.corners[3 * pf + 2]};
    std::array<std::int64_t, 3> got = {m.input_vertex[fv[0]], m.input_vertex[fv[1]], m.input_vertex[fv[2]]};
    while (got[0] != want[0]) std::rotate(got.begin(), got.begin() + 1, got.end());
    CHECK(got == want);
  }
  ValidateOptions strict;
  strict.repair_orientation = false;
  CHECK(thrown(s, strict) == ErrorKind::NonManifoldEdge);
  CHECK(thrown(g, strict) == ErrorKind::Internal);  // consistent input: nothing thrown
}

TEST_CASE("unreferenced vertices are dropped with a warning, input ids kept") {
  auto pos = points(7);
  const auto s = soup_of(pos, {{1, 3, 2}, {1, 2, 5}, {1, 5, 3}, {2, 3, 5}});  // 0, 4, 6 unused
  const ValidMesh m = validate(s);
  CHECK(m.mesh.num_vertices() == 4);
  CHECK(m.input_vertex == std::vector<std::int64_t>{1, 2, 3, 5});
  CHECK(m.positions[3].x == pos[5].x);
  REQUIRE(m.warnings.size() == 1);
  CHECK(m.warnings[0] == "dropped 3 unreferenced vertices (0, 4, 6)");
  CHECK(m.genus == 0);
  ValidateOptions keep;
  keep.drop_unreferenced = false;
  const MeshReport r = inspect(s, keep);
  CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::SeveralComponents});
  CHECK(r.components == 4);
  CHECK(thrown(s, keep) == ErrorKind::SeveralComponents);
}

TEST_CASE("polygons: fan triangulation avoids diagonals that exist, reports those it cannot avoid") {
  // Cube of quads.
  const std::vector<Vec3d> cube = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0},
                                   {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}};
  const auto quads =
      soup_of(cube, {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}});
  const ValidMesh m = validate(quads);
  CHECK(m.mesh.num_faces() == 12);
  CHECK(m.genus == 0);
  check_faces_match(quads, m);
  for (int f = 0; f < 12; ++f) CHECK(m.input_face[f] == f / 2);

  // Apex 0 of the quad would make diagonal (0,2), an edge of the triangle: apex 1 is used.
  const auto s1 = soup_of(points(5), {{0, 1, 2, 3}, {0, 2, 4}});
  const MeshReport r1 = inspect(s1);
  CHECK(r1.non_manifold_edges == 0);
  // Both diagonals exist: the triangulation must create a non-manifold edge and says so.
  const auto s2 = soup_of(points(6), {{0, 1, 2, 3}, {0, 2, 4}, {1, 3, 5}});
  const MeshReport r2 = inspect(s2);
  REQUIRE(!r2.problems.empty());
  CHECK(r2.problems[0].kind == ErrorKind::NonManifoldEdge);
  CHECK(r2.problems[0].message.find("fan triangulation of polygon 0") != std::string::npos);
}

TEST_CASE("generated meshes of genus 0..6 validate with the right genus") {
  for (int g = 0; g <= 6; ++g) {
    CAPTURE(g);
    const PolygonSoup s = generate_closed_mesh({.genus = g, .faces = 400 + 100 * g, .seed = std::uint64_t(g + 1)});
    const MeshReport r = inspect(s);
    CHECK(r.problems.empty());
    CHECK(r.warnings.empty());
    CHECK(r.genus == g);
    CHECK(r.euler_characteristic == 2 - 2 * g);
    CHECK(r.edges * 2 == r.triangles * 3);
    const ValidMesh m = validate(s);
    CHECK(m.genus == g);
    CHECK(m.mesh.check_invariants() == "");
    CHECK(m.mesh.num_faces() == static_cast<int>(s.num_faces()));
  }
}

TEST_CASE("malformed soups are reported, not crashed on") {
  PolygonSoup s = soup_of(points(4), tetra(0));
  s.face_begin.back() = 100;
  CHECK(thrown(s) == ErrorKind::InvalidArgument);
  PolygonSoup t = soup_of(points(4), tetra(0));
  t.face_begin[2] = 1;
  CHECK(thrown(t) == ErrorKind::InvalidArgument);
}
