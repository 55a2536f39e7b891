// Regression tests for the bugs the randomized tests and the fuzz targets found, each on the
// smallest mesh that shows it (issue 7).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "igm/core/error.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/topology/cut_to_canonical_disk.h"
#include "check_pipeline.h"
#include "random_mesh.h"

using namespace igm;

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
