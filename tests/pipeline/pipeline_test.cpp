#include <doctest/doctest.h>

#include <map>
#include <sstream>

#include "certify/certify.h"
#include "igm/core/error.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/output/igm_mesh.h"
#include "igm/pipeline/pipeline.h"
#include "test_data.h"

using namespace igm;

namespace {

ValidMesh generated(int genus, std::int64_t faces, std::uint64_t seed) {
  GenerateOptions o;
  o.genus = genus;
  o.faces = faces;
  o.seed = seed;
  return validate(generate_closed_mesh(o));
}

// Independent re-check of what a run promises, ending with the certifier on the written files.
void check_run(const ValidMesh& mesh, int resolution, bool normal_form = false) {
  PipelineOptions options;
  options.resolution = resolution;
  options.normal_form = normal_form;
  const PipelineResult r = compute_igm(mesh, options);
  const int g = mesh.genus;
  INFO("genus " << g << ", resolution " << resolution);
  CHECK(r.stats.genus == g);
  CHECK(r.igm_report.valid());
  CHECK(r.quad_report.valid());
  const int layout_quads = g == 1 ? 1 : 5 * g;
  CHECK(r.stats.layout_quads == layout_quads);
  CHECK(static_cast<int>(r.quads.quads.size()) == layout_quads * resolution * resolution);
  REQUIRE(r.igm_report.genus.has_value());
  CHECK(*r.igm_report.genus == g);
  REQUIRE(r.quad_report.genus.has_value());
  CHECK(*r.quad_report.genus == g);
  // The IGM is a refinement of the input: every input vertex is kept at its position.
  REQUIRE(r.igm.positions.size() >= mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    CHECK(r.igm.positions[v].x == mesh.positions[v].x);
    CHECK(r.igm.positions[v].z == mesh.positions[v].z);
  }
  // Cones: Poincare-Hopf is part of the certificate; count them from the report's histogram.
  const certify::CheckResult* cones = r.igm_report.check(4);
  REQUIRE(cones != nullptr);
  CHECK(cones->passed());
  // The written exact artefact and the double one read back through the certifier's own reader.
  std::ostringstream exact, quads;
  write_igm_obj(exact, r.igm, true);
  write_quad_obj(quads, r.quads);
  CHECK(certify::certify_igm_text(exact.str()).valid());
  certify::Options qo;
  qo.expected_genus = g;
  CHECK(certify::certify_quads_text(quads.str(), qo).valid());
}

}  // namespace

TEST_CASE("genus 1 generated tori: certified IGM and N x N quads") {
  for (std::uint64_t seed : {1, 2, 3}) check_run(generated(1, 600 * seed, seed), 2 + int(seed));
}

TEST_CASE("genus 2..6 generated meshes, odd and even: certified, 5g N^2 quads") {
  for (int g = 2; g <= 6; ++g) check_run(generated(g, 400 * g, std::uint64_t(g)), 3 + g % 2);
}

TEST_CASE("generated genus 12, 25 and 50 (odd and even): certified") {
  for (int g : {12, 25, 50}) check_run(generated(g, 200 * g, std::uint64_t(g)), 3);
}

TEST_CASE("with the gluing word in normal form (handle slides) the outputs are certified too") {
  for (int g = 2; g <= 4; ++g) check_run(generated(g, 500 * g, std::uint64_t(40 + g)), 3, true);
}

TEST_CASE("resolution 1 layout: 5g quads, 2+3g vertices, valences 8g, 3g and 3g vertices of valence 3") {
  for (int g : {2, 3, 7}) {
    const ValidMesh mesh = generated(g, 300 * g, 11);
    PipelineOptions o;
    o.resolution = 1;
    const PipelineResult r = compute_igm(mesh, o);
    INFO("genus " << g);
    CHECK(r.igm_report.valid());
    // At N = 1 every polygon corner is the root: quads repeat it, so the certifier (edges by end
    // points) must reject the quad mesh; the counts below are the paper's.
    CHECK_FALSE(r.quad_report.valid());
    CHECK(static_cast<int>(r.quads.quads.size()) == 5 * g);
    CHECK(static_cast<int>(r.quads.positions.size()) == 2 + 3 * g);
    std::map<int, int> valence;  // vertex -> number of quads around it (= edges on a closed quad mesh)
    for (const auto& q : r.quads.quads)
      for (int v : q) ++valence[v];
    std::map<int, int> histogram;
    for (const auto& [v, k] : valence) ++histogram[k];
    CHECK(histogram[8 * g] == 1);
    CHECK(histogram[3 * g] == 1);
    CHECK(histogram[3] == 3 * g);
    CHECK(histogram.size() == 3);
  }
}

TEST_CASE("bad options and genus 0 give typed errors") {
  const ValidMesh torus = generated(1, 200, 5);
  PipelineOptions o;
  o.resolution = 0;
  CHECK_THROWS_AS(compute_igm(torus, o), Error);
  o.resolution = 1;
  o.root = torus.mesh.num_vertices();
  try {
    compute_igm(torus, o);
    FAIL("accepted an out-of-range root");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::InvalidArgument);
  }
  try {
    compute_igm(generated(0, 200, 5), {});
    FAIL("genus 0 accepted");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Unsupported);
  }
}

TEST_CASE("shared clean meshes of genus >= 1 are certified") {
  IGM_REQUIRE_DATA(dir);
  for (const char* name : {"mpi_triang.off", "pipe.off", "knot.off", "eight.off", "joint.off", "helmet.off",
                           "anchor.off", "elephant.off", "couplingdown.off"}) {
    INFO(name);
    check_run(load_mesh(dir / "meshes" / "clean" / name), 3);
  }
  for (const char* name : {"3torus.off", "double-torus-example.off", "hole.off"}) {
    INFO(name);
    check_run(load_mesh(dir / "meshes" / "polygonal" / name), 3);
  }
}

TEST_CASE("cheese (genus 133 with 17.8k faces) is certified" * doctest::test_suite("asan_slow")) {
  IGM_REQUIRE_DATA(dir);
  check_run(load_mesh(dir / "meshes" / "clean" / "cheese.off"), 3);
}

TEST_CASE("a generated 1M-face torus: every triangle certified and N x N quads" * doctest::test_suite("asan_slow")) {
  const ValidMesh torus = generated(1, 1000000, 77);
  REQUIRE(torus.mesh.num_faces() >= 1000000);
  PipelineOptions o;
  o.resolution = 3;
  const PipelineResult r = compute_igm(torus, o);
  CHECK(r.stats.tutte.interior_vertices > 490000);
  CHECK(r.igm_report.valid());
  const certify::CheckResult* flips = r.igm_report.check(2);
  REQUIRE(flips != nullptr);
  CHECK(flips->passed());
  CHECK(r.quad_report.valid());
  CHECK(r.quads.quads.size() == 9);
}
