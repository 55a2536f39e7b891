// Tests of the open surfaces' cut: check_open_cut on every result (it recomputes the
// post-conditions from the arrays), the side counts predicted by hand from genus and loops, and the
// typed errors.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "igm/core/error.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/generate.h"
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
