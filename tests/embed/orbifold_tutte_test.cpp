// Tests of the orbifold Tutte embedding, re-checked exactly from the raw output: cone copies at
// their corners, transitions exact, every triangle positive, the disk tiles a domain of area 2.
#include <doctest/doctest.h>

#include <sstream>

#include "igm/core/error.h"
#include "igm/embed/orbifold_tutte.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "generated_mesh.h"
#include "test_data.h"

using namespace igm;

namespace {

ValidMesh generated_sphere(std::int64_t faces, std::uint64_t seed) { return igm_test::generated_mesh(0, faces, seed); }

// Returns "" or the first broken promise.
std::string verify(const SphereCut& c, const OrbifoldTutteResult& r) {
  const int nd = static_cast<int>(c.disk_to_surface.size());
  if (static_cast<int>(r.uv.size()) != nd) return "uv size";
  const int corner_xy[6][2] = {{1, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}, {0, 0}};
  for (int s = 0; s < 6; ++s) {
    const Point2q& p = r.uv[c.boundary[c.corners[s]]];
    if (p.x != corner_xy[s][0] || p.y != corner_xy[s][1]) return "cone copy " + std::to_string(s) + " not at its corner";
  }
  // copy 2 = rotation by pi about A (leg A-B), translation by -2 (B-C), rotation about D (C-D)
  const int k = static_cast<int>(c.path.size()) - 1, iB = c.cone_index[1], iC = c.cone_index[2];
  for (int i = 1; i < k; ++i) {
    if (i == iB || i == iC) continue;
    const Point2q& p1 = r.uv[c.path[i]];
    const Point2q& p2 = r.uv[c.copy2(i)];
    Rational ex, ey;
    if (i < iB) {
      ex = 2 - p1.x;
      ey = -p1.y;
    } else if (i < iC) {
      ex = p1.x - 2;
      ey = p1.y;
    } else {
      ex = 2 - p1.x;
      ey = 2 - p1.y;
    }
    if (p2.x != ex || p2.y != ey) return "transition of path vertex " + std::to_string(i) + " not exact";
  }
  Rational area = 0;
  for (const auto& t : c.disk_triangles) {
    const Point2q &a = r.uv[t[0]], &b = r.uv[t[1]], &d = r.uv[t[2]];
    if (orient2d(a, b, d) != Sign::Positive) return "a triangle is not positive";
    area += (b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x);
  }
  if (area != 4) return "twice the disk area is " + to_string(area) + ", not 4 (the domain has area 2)";
  return "";
}

}  // namespace

TEST_CASE("orbifold Tutte: shared genus-0 meshes are certified onto the pillowcase") {
  IGM_REQUIRE_DATA(dir);
  for (const char* name : {"tetrahedron.off", "icosahedron.off", "cube.off", "sphere.off", "bull.off", "armadillo.off"}) {
    INFO(name);
    const ValidMesh in = load_mesh(dir / "meshes" / "clean" / name);
    const SphereCut c = cut_sphere(in.mesh, in.positions);
    const OrbifoldTutteResult r = orbifold_tutte_embed(c);
    CHECK(verify(c, r) == "");
    CHECK(r.stats.free_vertices == c.surface.mesh.num_vertices() - 4);
    CHECK(r.stats.max_bits > 0);
  }
}

TEST_CASE("orbifold Tutte: generated spheres, user cones, forced refinement steps") {
  for (std::int64_t faces : {16, 300, 5000, 60000}) {
    INFO(faces);
    const ValidMesh in = generated_sphere(faces, std::uint64_t(faces) + 1);
    const SphereCut c = cut_sphere(in.mesh, in.positions);
    CHECK(verify(c, orbifold_tutte_embed(c)) == "");
  }
  const ValidMesh in = generated_sphere(2000, 9);
  SphereCutOptions o;
  o.cones = {0, 1, 2, 3};  // close together: long thin triangles near the cones
  const SphereCut c = cut_sphere(in.mesh, in.positions, o);
  RefinementOptions ro;
  ro.min_iterations = 3;
  const OrbifoldTutteResult r = orbifold_tutte_embed(c, ro);
  CHECK(verify(c, r) == "");
  CHECK(r.stats.refinement.iterations >= 3);
  CHECK(r.stats.refinement.grid_exponent > 60);
  CHECK(r.stats.refinement.flips_per_iteration.back() == 0);
}

TEST_CASE("orbifold Tutte: the pillowcase maps are rotations by pi about the cones or a translation") {
  // each transition is x -> s x + t with s = +-1; it maps B1 to B2 and C1 to C2 and fixes A and D
  auto apply = [](const PillowcaseMap& m, std::array<int, 2> p) {
    return std::array<int, 2>{m.s * p[0] + m.tx, m.s * p[1] + m.ty};
  };
  CHECK(apply(pillowcase_transition(0), pillowcase_corner(0)) == pillowcase_corner(0));
  CHECK(apply(pillowcase_transition(0), pillowcase_corner(1)) == pillowcase_corner(5));
  CHECK(apply(pillowcase_transition(1), pillowcase_corner(1)) == pillowcase_corner(5));
  CHECK(apply(pillowcase_transition(1), pillowcase_corner(2)) == pillowcase_corner(4));
  CHECK(apply(pillowcase_transition(2), pillowcase_corner(2)) == pillowcase_corner(4));
  CHECK(apply(pillowcase_transition(2), pillowcase_corner(3)) == pillowcase_corner(3));
  CHECK_THROWS_AS(pillowcase_transition(3), Error);
  CHECK_THROWS_AS(pillowcase_corner(6), Error);
}
