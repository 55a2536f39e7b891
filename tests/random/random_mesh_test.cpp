// Randomized property tests of the whole pipeline (issue 7): random closed meshes of genus 0..12
// (and open ones of genus 0..8 with 1..12 boundary loops, issue 39)
// (1..12 if kGenus0Certifies in check_pipeline.h is false),
// 16 to ~3000 faces (4 for the genus-0 tetrahedron), random refinements, random root, random
// vertex/face order and near-degenerate or extreme geometry must all certify (both certifier
// reports); permuting vertex or face order and re-rooting keep the genus and the quad count.
//
// Seeded: IGM_RANDOM_SEED (default below) overrides the seed and IGM_RANDOM_SCALE (a factor on
// every count, default 1; e.g. 10 for a long run, 0.25 in the sanitizer pass of scripts/test.sh)
// the number of meshes; every check names the seed and the mesh spec on failure.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>

#include "check_pipeline.h"
#include "random_mesh.h"
#include "test_data.h"

using namespace igm;
using igm_test::Geometry;
using igm_test::RandomMeshSpec;
using igm_test::Outcome;
using igm_test::run_pipeline;

namespace {

std::uint64_t env_u64(const char* name, std::uint64_t fallback) {
  const char* s = std::getenv(name);
  return s && *s ? std::strtoull(s, nullptr, 10) : fallback;
}
std::uint64_t base_seed() { return env_u64("IGM_RANDOM_SEED", 20261201); }
// The lowest genus drawn: 0 once the genus-0 stage has landed (check_pipeline.h).
constexpr int kMinGenus = igm_test::kGenus0Certifies ? 0 : 1;

double scale() {
  const char* s = std::getenv("IGM_RANDOM_SCALE");
  const double f = s && *s ? std::strtod(s, nullptr) : 1.0;
  return f > 0 && f <= 1e6 ? f : 1.0;
}
int scaled(int n) { return std::max(1, static_cast<int>(std::lround(n * scale()))); }

// A random spec: genus in [g_lo, g_hi], faces log-uniform in [16, max_faces], a random geometry
// (plain half the time), up to 40 random splits, jitter in [0, 0.45].
RandomMeshSpec draw(std::mt19937_64& rng, int g_lo, int g_hi, double max_faces) {
  RandomMeshSpec s;
  s.genus = g_lo + static_cast<int>(rng() % static_cast<unsigned>(g_hi - g_lo + 1));
  const double u = std::uniform_real_distribution<double>(0, 1)(rng);
  s.faces = static_cast<std::int64_t>(16 * std::pow(max_faces / 16, u));
  s.seed = rng();
  s.jitter = std::uniform_real_distribution<double>(0, 0.45)(rng);
  s.edge_splits = static_cast<int>(rng() % 21);
  s.face_splits = static_cast<int>(rng() % 21);
  const int k = static_cast<int>(rng() % (2 * static_cast<unsigned>(Geometry::Count)));
  s.geometry = k < static_cast<int>(Geometry::Count) ? static_cast<Geometry>(k) : Geometry::Plain;
  return s;
}

}  // namespace

TEST_CASE("random closed meshes of genus up to 12 with random roots, refinements and geometry certify") {
  // Count: 150 meshes (IGM_RANDOM_SCALE scales it), 16..3000 faces log-uniform.
  const std::uint64_t seed = base_seed();
  std::mt19937_64 rng(seed);
  const int n = scaled(150);
  int certified = 0;
  for (int i = 0; i < n; ++i) {
    const RandomMeshSpec s = draw(rng, kMinGenus, 12, 3000);
    const int root = static_cast<int>(rng() % 1000000);
    CAPTURE(seed);
    CAPTURE(i);
    INFO(igm_test::describe(s) << ", root " << root);
    certified += run_pipeline(igm_test::random_closed_mesh(s), s.genus, root).certified;
  }
  MESSAGE("seed " << seed << ": " << certified << " of " << n << " random meshes certified");
  CHECK(certified == n);
}

TEST_CASE("random open meshes of genus up to 8 with 1..12 boundary loops, random roots, refinements and geometry certify") {
  // Count: 12 meshes (IGM_RANDOM_SCALE scales it); faces log-uniform from what the generator
  // needs for the holes (200 + 250 g + 40 b) to 8 times that.
  const std::uint64_t seed = base_seed() + 39;
  std::mt19937_64 rng(seed);
  const int n = scaled(40);
  int certified = 0;
  for (int i = 0; i < n; ++i) {
    const int g = static_cast<int>(rng() % 9), b = 1 + static_cast<int>(rng() % 12);
    RandomMeshSpec s = draw(rng, g, g, 16);
    s.boundaries = b;
    const double least = 200.0 + 250.0 * g + 40.0 * b;
    s.faces = static_cast<std::int64_t>(least * std::pow(8.0, std::uniform_real_distribution<double>(0, 1)(rng)));
    s.permute = rng() % 2 == 0;
    const int root = static_cast<int>(rng() % 1000000);
    CAPTURE(seed);
    CAPTURE(i);
    INFO(igm_test::describe(s) << ", root " << root);
    certified += igm_test::run_open_pipeline(igm_test::random_mesh(s), g, b, root).certified;
  }
  MESSAGE("seed " << seed << ": " << certified << " of " << n << " random open meshes certified");
  CHECK(certified == n);
}

TEST_CASE("random closed meshes with the normal form certify") {
  // Count: 12 meshes (IGM_RANDOM_SCALE scales it), genus 1..12, 16..2000 faces log-uniform, random
  // roots. Any error (the growth bound CutOptions::max_normal_form_growth included: coarse meshes
  // of high genus take the crosses construction, well within it), an invalid certificate or a
  // crash fails.
  const std::uint64_t seed = base_seed() + 7;
  std::mt19937_64 rng(seed);
  const int n = scaled(40);
  int certified = 0, bounded = 0;
  for (int i = 0; i < n; ++i) {
    const RandomMeshSpec s = draw(rng, 1, 12, 2000);
    const int root = static_cast<int>(rng() % 1000000);
    CAPTURE(seed);
    CAPTURE(i);
    INFO(igm_test::describe(s) << ", root " << root);
    const Outcome r = run_pipeline(igm_test::random_closed_mesh(s), s.genus, root, false, 3, true);
    certified += r.certified;
    bounded += r.growth_bound;
  }
  MESSAGE("seed " << seed << ": " << certified << " of " << n << " certified with the normal form, " << bounded
                  << " at its growth bound");
  CHECK(bounded == 0);
  CHECK(certified == n);
}

TEST_CASE("every hostile geometry on every genus up to 12: topology does not depend on coordinates") {
  // Count: 8 geometries x 12 genera = 96 small meshes (~30 faces per genus), random roots; the
  // written files are certified too (positions at 1e300 or 1e-300 must still be written and read).
  // IGM_RANDOM_SCALE < 1 keeps scaled(12) genera spread over 1..12; > 1 repeats the rounds.
  const std::uint64_t seed = base_seed() + 1;
  std::mt19937_64 rng(seed);
  int certified = 0, n = 0;
  const int span = 13 - kMinGenus;  // genera kMinGenus..12
  const int genera = std::min(span, scaled(span)), rounds = std::max(1, scaled(span) / span);
  for (int round = 0; round < rounds; ++round)  // rounds x 8 geometries x genera meshes
    for (int k = 0; k < static_cast<int>(Geometry::Count); ++k)
      for (int j = 0; j < genera; ++j) {
        const int g = kMinGenus + j * span / genera;
        RandomMeshSpec s;
        s.genus = g;
        s.faces = 30 * std::max(g, 1);
        s.seed = rng();
        s.edge_splits = static_cast<int>(rng() % 6);
        s.face_splits = static_cast<int>(rng() % 6);
        s.geometry = static_cast<Geometry>(k);
        const int root = static_cast<int>(rng() % 1000000);
        CAPTURE(seed);
        INFO(igm_test::describe(s) << ", root " << root);
        certified += run_pipeline(igm_test::random_closed_mesh(s), g, root, true).certified;
        ++n;
      }
  MESSAGE("seed " << seed << ": " << certified << " of " << n << " hostile-geometry meshes certified");
  CHECK(certified == n);
}

TEST_CASE("metamorphic: vertex order, face order and root do not change genus or quad count") {
  // Count: 40 meshes x 4 runs (as generated, vertices permuted, faces permuted, another root).
  const std::uint64_t seed = base_seed() + 2;
  std::mt19937_64 rng(seed);
  const int n = scaled(40);
  for (int i = 0; i < n; ++i) {
    RandomMeshSpec s = draw(rng, kMinGenus, 12, 1500);
    s.permute = false;
    CAPTURE(seed);
    CAPTURE(i);
    INFO(igm_test::describe(s));
    const PolygonSoup soup = igm_test::random_closed_mesh(s);
    const Outcome base = run_pipeline(soup, s.genus, -1);
    REQUIRE(base.certified);
    const Outcome by_vertices = run_pipeline(igm_test::permute_soup(soup, rng, true, false, false), s.genus, -1);
    const Outcome by_faces = run_pipeline(igm_test::permute_soup(soup, rng, false, true, true), s.genus, -1);
    const Outcome rerooted = run_pipeline(soup, s.genus, static_cast<int>(rng() % 1000000));
    for (const Outcome& o : {by_vertices, by_faces, rerooted}) {
      CHECK(o.certified);
      CHECK(o.genus == base.genus);
      CHECK(o.quads == base.quads);
    }
  }
}

TEST_CASE("random spheres from the 4-face tetrahedron up with hostile geometry certify") {
  // Count: 100 spheres, from the 4-face tetrahedron to ~3000 faces, with hostile geometry.
  const std::uint64_t seed = base_seed() + 3;
  std::mt19937_64 rng(seed);
  const int n = scaled(100);
  int certified = 0;
  for (int i = 0; i < n; ++i) {
    RandomMeshSpec s = draw(rng, 0, 0, 3000);
    if (i % 3 == 0) s.faces = 4;  // the tetrahedron, refined
    CAPTURE(seed);
    INFO(igm_test::describe(s));
    certified += run_pipeline(igm_test::random_closed_mesh(s), 0, static_cast<int>(rng() % 1000000)).certified ||
                 !igm_test::kGenus0Certifies;
  }
  MESSAGE("seed " << seed << ": " << certified << " of " << n << " random spheres certified");
  CHECK(certified == n);
}

TEST_CASE("random closed and open meshes with hostile geometry through the field layout certify") {
  // Count: 12 meshes (IGM_RANDOM_SCALE scales it; 1 under the sanitizers): genus 0..8, closed or with 1..6 boundary
  // loops, random refinements and geometry. Every output must certify, from the field layout or
  // its fallback; how many took the field layout is reported (docs/field.md).
  const std::uint64_t seed = base_seed() + 46;
  std::mt19937_64 rng(seed);
  const int n = igm_test::kSanitized ? 1 : scaled(12);  // the sanitizers' run: one (30 s there)
  int certified = 0, field = 0;
  for (int i = 0; i < n; ++i) {
    const int g = static_cast<int>(rng() % 9), b = rng() % 2 == 0 ? 0 : 1 + static_cast<int>(rng() % 6);
    RandomMeshSpec s = draw(rng, g, g, 16);
    s.boundaries = b;
    const double least = 200.0 + 250.0 * g + 40.0 * b;
    s.faces = static_cast<std::int64_t>(least * std::pow(4.0, std::uniform_real_distribution<double>(0, 1)(rng)));
    CAPTURE(seed);
    CAPTURE(i);
    INFO(igm_test::describe(s));
    const SurfaceSet set = validate_surfaces(igm_test::random_mesh(s));
    REQUIRE(set.components.size() == 1);
    PipelineOptions o;
    o.layout = LayoutKind::Field;
    o.quads = 600;
    o.quality = false;
    o.smooth_iterations = 3;
    const PipelineResult r = compute_igm(set.components[0], o);
    CHECK(r.igm_report.valid());
    CHECK(r.quad_report.valid());
    certified += r.certified();
    field += r.stats.layout == "field";
    CHECK((r.stats.layout == "field") == r.stats.layout_fallback.empty());
    if (std::getenv("IGM_FIELD_VERBOSE")) MESSAGE(igm_test::describe(s) << ": " << r.stats.layout << " " << r.stats.layout_fallback);
  }
  MESSAGE("seed " << seed << ": " << certified << " of " << n << " certified, " << field << " with the field layout");
  CHECK(certified == n);
}

TEST_CASE("random meshes of 2..300 components up to four orders of magnitude apart in size certify, each surface at least at its floor") {
  // Count: 4 meshes (IGM_RANDOM_SCALE scales it), the first of 300 components, the others 2..300
  // log-uniform: 4-face tetrahedra, 12-face boxes and generated surfaces of genus 0..10 (closed, or
  // open with 1..3 loops) of up to 300 faces, sizes 10^[0, 4]; 2000 quads shared by area, so most
  // get shares far below their floor.
  const std::uint64_t seed = base_seed() + 47;
  std::mt19937_64 rng(seed);
  const int n = scaled(4);
  int certified = 0;
  for (int i = 0; i < n; ++i) {
    const double u = std::uniform_real_distribution<double>(0, 1)(rng);
    const int components = i == 0 ? 300 : static_cast<int>(std::lround(2 * std::pow(150.0, u)));
    const igm_test::RandomSurfaces m = igm_test::random_surfaces(rng(), components, 10, 300);
    CAPTURE(seed);
    CAPTURE(i);
    INFO(components << " components:\n" << m.description);
    certified += igm_test::run_surfaces(m.soup, m.topology, 2000).certified;
  }
  MESSAGE("seed " << seed << ": " << certified << " of " << n << " random multi-component meshes certified");
  CHECK(certified == n);
}
