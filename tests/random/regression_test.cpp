// Regression tests for the bugs the randomized tests and the fuzz targets found, each on the
// smallest mesh that shows it (issue 7).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "igm/core/error.h"
#include "igm/layout/sizing.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/pipeline/pipeline.h"
#include "igm/mesh/validate.h"
#include "igm/topology/cut_to_canonical_disk.h"
#include "check_pipeline.h"
#include "random_mesh.h"

using namespace igm;
using igm_test::RandomMeshSpec;

namespace {

// The smallest generated torus (the generator's minimum, 2x2 cells per macro cell).
ValidMesh small_torus() {
  GenerateOptions o;
  o.genus = 1;
  o.faces = 16;
  o.seed = 3;
  return validate(generate_closed_mesh(o));
}

void check_certified(const ValidMesh& m) {
  CHECK(igm_test::run_pipeline(igm_test::to_soup(m.mesh, m.positions), m.genus, -1, true).certified);
}

}  // namespace

TEST_CASE("regression: coordinates at 1e300 (squared lengths overflow to inf) still give a certified IGM") {
  // Was: the loop basis's Dijkstra summed inf lengths, reached no vertex, and the topology stage
  // threw several_components "vertex 0 is not connected to the root" on a valid torus.
  ValidMesh m = small_torus();
  for (Vec3d& p : m.positions) p = {p.x * 1e300, p.y * 1e300, p.z * 1e300};
  check_certified(m);
  for (Vec3d& p : m.positions)  // differences of +-1e308 overflow already
    p = {std::copysign(1e308, p.x - 1), std::copysign(1e308, p.y - 1), std::copysign(1e308, p.z)};
  check_certified(m);
}

TEST_CASE("regression: coordinates at 1e-300 (squared lengths underflow to 0) and one point for all") {
  ValidMesh m = small_torus();
  for (Vec3d& p : m.positions) p = {p.x * 1e-300, p.y * 1e-300, p.z * 1e-300};
  check_certified(m);
  for (Vec3d& p : m.positions) p = {0.0, 0.0, 0.0};
  check_certified(m);
}

TEST_CASE("cut_to_canonical_disk names a non-finite coordinate instead of computing with it") {
  ValidMesh m = small_torus();
  m.positions[5].y = std::numeric_limits<double>::quiet_NaN();
  try {
    cut_to_canonical_disk(m.mesh, m.positions, {});
    FAIL("NaN accepted");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::NonFinite);
    CHECK(e.elements() == std::vector<std::int64_t>{5});
  }
}

TEST_CASE("regression (issue 47): the tetrahedron at 4..6 quads (a 2 x 1 grid: 4 quads, 6 vertices, a double edge) certifies at its floor") {
  // Was: 2 x 1 quads per unit of the pillowcase, a quad mesh with two edges between two vertices,
  // refused by the certifier (exit 1). Now the grid is 1 x 1 or 2 x 2 (pillowcase_grid_floor).
  RandomMeshSpec s;
  s.genus = 0;
  s.faces = 4;
  s.permute = false;
  const ValidMesh tetra = validate(igm_test::random_mesh(s));
  REQUIRE(tetra.mesh.num_faces() == 4);
  for (std::int64_t quads : {1, 4, 5, 6, 7}) {
    CAPTURE(quads);
    PipelineOptions o;
    o.layout = LayoutKind::Spread;  // the topological layout (the field one has its own tests)
    o.quads = quads;
    o.quality = false;
    const PipelineResult r = compute_igm(tetra, o);
    CHECK(r.certified());
    CHECK(pillowcase_grid_floor(r.stats.grid) == r.stats.grid);
    CHECK(r.stats.quads == 2 * r.stats.grid[0] * r.stats.grid[1]);
  }
}

TEST_CASE("regression (issue 47): a genus-10 surface beside a 48-face box whose share of the quads is 4: every surface certified") {
  // Was: the box's share by area, 4 quads, gave it the 2 x 1 pillowcase (a double edge): the
  // genus-10 part certified, the box and so the run not (18 of 1,148 files of Debian packages).
  // The box: a cube with every side a 2 x 2 grid of squares (48 triangles).
  PolygonSoup soup;
  GenerateOptions g;
  g.genus = 10;
  g.faces = 3000;
  g.seed = 1;
  soup = generate_mesh(g);
  // The box's side h: its area 6 h^2 is 1/1000 of the total, so that its share of 4000 quads is 4.
  double area = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const Vec3d &a = soup.positions[soup.corners[soup.face_begin[f]]], &b = soup.positions[soup.corners[soup.face_begin[f] + 1]],
                &c = soup.positions[soup.corners[soup.face_begin[f] + 2]];
    const Vec3d u{b.x - a.x, b.y - a.y, b.z - a.z}, v{c.x - a.x, c.y - a.y, c.z - a.z};
    area += 0.5 * std::sqrt(std::pow(u.y * v.z - u.z * v.y, 2) + std::pow(u.z * v.x - u.x * v.z, 2) + std::pow(u.x * v.y - u.y * v.x, 2));
  }
  const double h = std::sqrt(area / 999 / 6);
  const auto base = static_cast<std::int64_t>(soup.positions.size());
  auto at = [&](int i, int j, int k) { return base + i + 3 * j + 9 * k; };  // 3 x 3 x 3 grid points
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) soup.positions.push_back({100 + 0.5 * h * i, 0.5 * h * j, 0.5 * h * k});
  auto square = [&](std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d) {  // counter-clockwise from outside
    soup.add_face({a, b, c});
    soup.add_face({a, c, d});
  };
  for (int u = 0; u < 2; ++u)
    for (int v = 0; v < 2; ++v) {
      square(at(u, v, 0), at(u, v + 1, 0), at(u + 1, v + 1, 0), at(u + 1, v, 0));  // z = 0, outward -z
      square(at(u, v, 2), at(u + 1, v, 2), at(u + 1, v + 1, 2), at(u, v + 1, 2));  // z = 1
      square(at(u, 0, v), at(u + 1, 0, v), at(u + 1, 0, v + 1), at(u, 0, v + 1));  // y = 0
      square(at(u, 2, v), at(u, 2, v + 1), at(u + 1, 2, v + 1), at(u + 1, 2, v));  // y = 1
      square(at(0, u, v), at(0, u, v + 1), at(0, u + 1, v + 1), at(0, u + 1, v));  // x = 0
      square(at(2, u, v), at(2, u + 1, v), at(2, u + 1, v + 1), at(2, u, v + 1));  // x = 1
    }
  const SurfaceSet set = validate_surfaces(soup);
  REQUIRE(set.components.size() == 2);
  REQUIRE(set.components[1].triangles.size() == 48);
  REQUIRE(set.components[1].genus == 0);
  PipelineOptions o;
  o.layout = LayoutKind::Spread;  // the topological layout (the field one has its own tests)
  o.quality = false;
  o.smooth_iterations = 3;
  // The box's area share of the quad count: 4 quads.
  o.quads = 4000;
  const SurfacesResult r = compute_igms(set, o);
  REQUIRE(r.components.size() == 2);
  CHECK(r.components[1].stats.quads_asked == 4);
  CHECK(r.components[1].certified());
  CHECK(r.components[0].certified());
  CHECK(r.certified());
  CHECK(r.quads_total == static_cast<std::int64_t>(r.quads.quads.size()));
}
