// generate_mesh with boundary loops (the closed meshes are tested in trimesh_test.cpp and
// validate_test.cpp).
#include "igm/mesh/generate.h"

#include <doctest/doctest.h>

#include <map>
#include <set>
#include <string>

#include "igm/core/error.h"
#include "igm/mesh/validate_surfaces.h"
#include "test_data.h"

using namespace igm;

namespace {

std::map<std::array<double, 3>, int> face_keys(const PolygonSoup& s) {  // faces by corner positions
  std::map<std::array<double, 3>, int> keys;
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    std::array<double, 3> k{};
    for (int i = 0; i < 3; ++i) {
      const Vec3d& p = s.positions[static_cast<std::size_t>(s.corners[3 * f + i])];
      k[static_cast<std::size_t>(i)] =
          p.x + 1e3 * p.y + 1e6 * p.z;  // distinct per grid vertex and sheet
    }
    std::sort(k.begin(), k.end());
    ++keys[k];
  }
  return keys;
}

}  // namespace

TEST_CASE("boundaries = 0 is the closed mesh, generate_closed_mesh refuses boundaries") {
  const GenerateOptions o{.genus = 2, .faces = 800, .seed = 9};
  const PolygonSoup a = generate_closed_mesh(o), b = generate_mesh(o);
  CHECK(a.corners == b.corners);
  CHECK(a.positions.size() == b.positions.size());
  GenerateOptions open = o;
  open.boundaries = 1;
  CHECK_THROWS_AS(generate_closed_mesh(open), Error);
  open.boundaries = -1;
  CHECK_THROWS_AS(generate_mesh(open), Error);
}

TEST_CASE("generated holes: one surface of genus g with B separated square loops") {
  struct Case {
    int genus;
    std::int64_t faces;
    int boundaries;
  };
  const Case cases[] = {{0, 100, 1},  {0, 100, 2},   {0, 1000, 50},  {1, 2000, 7},
                        {2, 3000, 3}, {3, 5000, 12}, {5, 20000, 50}, {0, 100000, 4}};
  for (const Case& c : cases) {
    CAPTURE(c.genus);
    CAPTURE(c.faces);
    CAPTURE(c.boundaries);
    GenerateOptions o{.genus = c.genus, .faces = c.faces, .seed = 3, .shuffle = false};
    const PolygonSoup closed = generate_mesh(o);
    o.boundaries = c.boundaries;
    const PolygonSoup open = generate_mesh(o);
    const SurfaceSet s = validate_surfaces(open);
    REQUIRE(s.components.size() == 1);
    const SurfaceComponent& m = s.components[0];
    CHECK(s.warnings.empty());  // no repair, no unreferenced vertex
    CHECK(m.genus == c.genus);
    REQUIRE(m.boundary_loops.size() == static_cast<std::size_t>(c.boundaries));
    // Each hole is a k x k square of cells: a loop of 4k edges and 2 k^2 faces removed, and the
    // open mesh's faces are the closed one's minus those.
    std::int64_t removed = 0;
    std::set<std::size_t> sizes;
    for (const auto& loop : m.boundary_loops) {
      REQUIRE(loop.size() % 4 == 0);
      const auto k = static_cast<std::int64_t>(loop.size() / 4);
      removed += 2 * k * k;
      sizes.insert(loop.size());
    }
    CHECK(sizes.size() == 1);  // one size k for all holes
    CHECK(static_cast<std::int64_t>(closed.num_faces()) - removed ==
          static_cast<std::int64_t>(open.num_faces()));
    const auto ck = face_keys(closed), ok = face_keys(open);
    for (const auto& [key, n] : ok) CHECK(ck.count(key) == 1);
    // Well separated: no triangle has vertices on two loops.
    std::vector<int> loop_of(m.positions.size(), -1);
    for (std::size_t l = 0; l < m.boundary_loops.size(); ++l)
      for (int v : m.boundary_loops[l]) loop_of[static_cast<std::size_t>(v)] = static_cast<int>(l);
    int touching = 0;
    for (const auto& t : m.triangles) {
      std::set<int> loops;
      for (int v : t)
        if (loop_of[static_cast<std::size_t>(v)] >= 0)
          loops.insert(loop_of[static_cast<std::size_t>(v)]);
      touching += loops.size() > 1;
    }
    CHECK(touching == 0);
  }
}

TEST_CASE("generated holes: deterministic per seed, shuffled like the closed meshes") {
  const GenerateOptions o{.genus = 1, .faces = 3000, .seed = 5, .boundaries = 6};
  const PolygonSoup a = generate_mesh(o), b = generate_mesh(o);
  CHECK(a.corners == b.corners);
  GenerateOptions other = o;
  other.seed = 6;
  CHECK(generate_mesh(other).corners != a.corners);
  const SurfaceSet s = validate_surfaces(a);
  REQUIRE(s.components.size() == 1);
  CHECK(s.components[0].boundary_loops.size() == 6);
  CHECK(s.components[0].genus == 1);
}

TEST_CASE("too many holes for the mesh: a typed error naming the capacity") {
  // Genus 0 at 100 faces: a 5 x 5 grid per sheet, inner cells 1..3: lattice pitch 3 fits one
  // 1 x 1 hole per sheet.
  const GenerateOptions o{.genus = 0, .faces = 100, .seed = 1, .boundaries = 3};
  try {
    generate_mesh(o);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::InvalidArgument);
    CHECK(std::string(e.what()).find("at most 2 well-separated holes") != std::string::npos);
  }
  // Genus 1 at 100 faces: every cell touches the seam.
  CHECK_THROWS_AS(generate_mesh({.genus = 1, .faces = 100, .seed = 1, .boundaries = 1}), Error);
}

TEST_CASE("a million faces with 50 holes") {
  if (igm_test::kSanitized) {
    MESSAGE("skipped under the sanitizers (about 20 s there); the Release run covers it");
    return;
  }
  const PolygonSoup s =
      generate_mesh({.genus = 4, .faces = 1'000'000, .seed = 2, .boundaries = 50});
  const SurfaceSet set = validate_surfaces(s);
  REQUIRE(set.components.size() == 1);
  CHECK(set.components[0].genus == 4);
  CHECK(set.components[0].boundary_loops.size() == 50);
  CHECK(set.components[0].triangles.size() > 800'000);
}
