// Tests of the genus-0 quad extraction: the orbit reduction against the group it encodes, the quad
// mesh against the certifier, and every located vertex re-checked exactly in its triangle.
#include <doctest/doctest.h>

#include <map>
#include <set>

#include "certify/certify.h"
#include "igm/core/error.h"
#include "igm/embed/orbifold_tutte.h"
#include "igm/extract/orbifold_quads.h"
#include "igm/layout/sizing.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "generated_mesh.h"

using namespace igm;

namespace {

struct Embedded {
  SphereCut cut;
  OrbifoldTutteResult map;
};

Embedded embed(std::int64_t faces, std::uint64_t seed) {
  const ValidMesh in = igm_test::generated_mesh(0, faces, seed);
  Embedded e{cut_sphere(in.mesh, in.positions), {}};
  e.map = orbifold_tutte_embed(e.cut);
  return e;
}

}  // namespace

TEST_CASE("grid orbits: invariant under the group, 2N^2 + 2 of them, the domain's cells cover them") {
  for (int N = 1; N <= 7; ++N) {
    CAPTURE(N);
    std::set<int> seen;
    for (int i = 0; i <= 2 * N; ++i)
      for (int j = 0; j <= N; ++j) {
        const int o = orbifold_grid_orbit(N, i, j);
        CHECK(o >= 0);
        CHECK(o < orbifold_grid_orbits(N));
        seen.insert(o);
        // generators: translations by (2, 0), (0, 2) and rotations by pi about (0,0), (1,0), (0,1)
        CHECK(orbifold_grid_orbit(N, i + 2 * N, j) == o);
        CHECK(orbifold_grid_orbit(N, i, j - 2 * N) == o);
        CHECK(orbifold_grid_orbit(N, -i, -j) == o);
        CHECK(orbifold_grid_orbit(N, 2 * N - i, -j) == o);
        CHECK(orbifold_grid_orbit(N, -i, 2 * N - j) == o);
      }
    CHECK(static_cast<int>(seen.size()) == 2 * N * N + 2);
    // points of the open domain are never identified with each other
    std::set<int> inner;
    for (int i = 1; i < 2 * N; ++i)
      for (int j = 1; j < N; ++j) inner.insert(orbifold_grid_orbit(N, i, j));
    CHECK(static_cast<int>(inner.size()) == (2 * N - 1) * (N - 1));
  }
}

TEST_CASE("orbifold quads: 2N^2 quads, 2N^2+2 vertices, four of valence 2, certified closed genus 0") {
  const Embedded e = embed(3000, 5);
  for (int N : {1, 2, 3, 4, 7}) {
    CAPTURE(N);
    const OrbifoldQuadMesh q = extract_orbifold_quads(e.cut.disk_triangles, e.map.uv, N);
    CHECK(static_cast<int>(q.quads.size()) == 2 * N * N);
    REQUIRE(static_cast<int>(q.triangle.size()) == 2 * N * N + 2);
    std::map<int, int> valence;
    for (const auto& quad : q.quads)
      for (int v : quad) ++valence[v];
    int two = 0;
    for (const auto& [v, k] : valence) {
      CHECK((k == 2 || k == 4));
      two += k == 2;
    }
    CHECK(two == 4);
    for (int v : q.cone_vertices) CHECK(valence[v] == 2);
    // every vertex: exact barycentric coordinates in its triangle whose UV point is in its orbit
    for (std::size_t v = 0; v < q.triangle.size(); ++v) {
      const auto& t = e.cut.disk_triangles[q.triangle[v]];
      const auto& w = q.barycentric[v];
      CHECK(w[0] + w[1] + w[2] == 1);
      CHECK((sgn(w[0]) >= 0 && sgn(w[1]) >= 0 && sgn(w[2]) >= 0));
      const Rational u = (w[0] * e.map.uv[t[0]].x + w[1] * e.map.uv[t[1]].x + w[2] * e.map.uv[t[2]].x) * N;
      const Rational vv = (w[0] * e.map.uv[t[0]].y + w[1] * e.map.uv[t[1]].y + w[2] * e.map.uv[t[2]].y) * N;
      REQUIRE(u.get_den() == 1);
      REQUIRE(vv.get_den() == 1);
      CHECK(orbifold_grid_orbit(N, u.get_num().get_si(), vv.get_num().get_si()) == static_cast<int>(v));
    }
    certify::QuadInput in;
    in.quads = q.quads;
    certify::Options o;
    o.expected_genus = 0;
    const certify::Report r = certify::certify_quads(in, o);
    CHECK(r.valid());
    REQUIRE(r.check(5) != nullptr);
    CHECK(r.check(5)->histogram.at(2) == 4);
  }
}

TEST_CASE("genus-0 floor: the nx x ny pillowcase is a manifold quad mesh iff 1 x 1 or both >= 2 (pillowcase_grid_floor)") {
  // Swept on the maps of generated spheres of 16 and 300 faces: a single row or column around the
  // pillowcase (one count 1, the other >= 2) joins two vertices by two edges.
  for (std::int64_t faces : {16, 300}) {
    const Embedded e = embed(faces, 3);
    for (int nx = 1; nx <= 4; ++nx)
      for (int ny = 1; ny <= 4; ++ny) {
        CAPTURE(faces);
        CAPTURE(nx);
        CAPTURE(ny);
        const OrbifoldQuadMesh q = extract_orbifold_quads(e.cut.disk_triangles, e.map.uv, nx, ny);
        certify::QuadInput in;
        in.quads = q.quads;
        in.num_vertices = static_cast<std::int64_t>(q.triangle.size());
        certify::Options o;
        o.expected_genus = 0;
        const bool floor = pillowcase_grid_floor({nx, ny}) == std::array<int, 2>{nx, ny};
        CHECK(certify::certify_quads(in, o).valid() == floor);
        CHECK(floor == ((nx == 1 && ny == 1) || (nx >= 2 && ny >= 2)));
      }
  }
  CHECK(pillowcase_grid_floor({5, 1}) == std::array<int, 2>{5, 2});
  CHECK(pillowcase_grid_floor({1, 3}) == std::array<int, 2>{2, 3});
}

TEST_CASE("orbifold quads: typed errors for a bad resolution and for orbits no triangle holds") {
  const Embedded e = embed(400, 2);
  CHECK_THROWS_AS(extract_orbifold_quads(e.cut.disk_triangles, e.map.uv, 0), Error);
  std::vector<std::array<int, 3>> half(e.cut.disk_triangles.begin(),
                                       e.cut.disk_triangles.begin() + e.cut.disk_triangles.size() / 2);
  try {
    extract_orbifold_quads(half, e.map.uv, 8);
    FAIL("half a disk covered every orbit");
  } catch (const Error& err) {
    CHECK(err.kind() == ErrorKind::Internal);
  }
}
