// The field layout through the pipeline (LayoutKind::Field): certified outputs of closed and open
// surfaces of several genera, the cones where the field put them, the quality it buys, and the
// fallbacks (field, trace) each triggered by a surface made for it, whose outputs are certified
// with the topological layout and say why. Every run ends with the certifier on written files.
#include <doctest/doctest.h>

#include <array>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "certify/certify.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/output/igm_mesh.h"
#include "igm/pipeline/pipeline.h"
#include "generated_mesh.h"
#include "refinement_check.h"
#include "test_data.h"
#include "uv_area.h"

using namespace igm;
using igm_test::refinement_violation;
using igm_test::uv_area2;

namespace {

PipelineOptions field_options(std::int64_t quads) {
  PipelineOptions o;
  o.layout = LayoutKind::Field;
  o.quads = quads;
  o.smooth_iterations = 10;
  return o;
}

// What every run promises, then the certifier on the written artefacts.
void check_certified(const PipelineResult& r, int genus) {
  CHECK(r.igm_report.valid());
  CHECK(r.quad_report.valid());
  REQUIRE(r.quad_report.genus.has_value());
  CHECK(*r.quad_report.genus == genus);
  CHECK(uv_area2(r.igm) == Rational(2 * static_cast<long>(r.quads.quads.size())));
  std::ostringstream exact, quads;
  write_igm_obj(exact, r.igm, true);
  write_quad_obj(quads, r.quads);
  CHECK(certify::certify_igm_text(exact.str()).valid());
  certify::Options qo;
  qo.expected_genus = genus;
  CHECK(certify::certify_quads_text(quads.str(), qo).valid());
}

// A needle: a square pyramid whose apex angles sum to about 0.2 radians; the field turns almost
// once around the apex (index 3/4 at least: a cone of valence 1 or less).
ValidMesh needle() {
  PolygonSoup soup;
  soup.positions = {{-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0.5, 0.5, 0}, {-0.5, 0.5, 0}, {0, 0, 20}};
  for (const auto& t : std::vector<std::array<std::int64_t, 3>>{{0, 2, 1}, {0, 3, 2}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}})
    soup.add_face({t[0], t[1], t[2]});
  return validate(soup);
}

}  // namespace

TEST_CASE("field pipeline: generated closed surfaces of genus 0 to 8 certified with the field layout") {
  for (int genus : {0, 1, 2, 5, 8}) {
    INFO("genus " << genus);
    const ValidMesh mesh = igm_test::generated_mesh(genus, 3000, 4);
    const PipelineResult r = compute_igm(mesh, field_options(2000));
    check_certified(r, genus);
    CHECK(refinement_violation(mesh, r.igm, true) == "");
    CHECK(r.stats.layout == "field");
    CHECK(r.stats.layout_fallback == "");
    // The cones are the field's: every interior cone of the IGM has valence 3..6, and there are
    // as many as the field has (Poincare-Hopf holds in the certificate).
    const certify::CheckResult* cones = r.igm_report.check(4);
    REQUIRE(cones != nullptr);
    int irregular = 0;
    for (const auto& [k, n] : cones->histogram) {
      if (k == 4) continue;
      CHECK(k >= 3);
      CHECK(k <= 6);
      irregular += static_cast<int>(n);
    }
    int field_cones = 0;
    for (int v = 0; v < 9; ++v)
      if (v != 4) field_cones += r.stats.cross_field.valence_count[v];
    CHECK(irregular == field_cones);
    // The point of it: square quads, far better than the schema's layouts at genus >= 3.
    CHECK(r.quad_quality.sj_median >= 0.9);
  }
}

TEST_CASE("field pipeline: open surfaces and several components") {
  GenerateOptions o;
  o.genus = 1;
  o.faces = 3000;
  o.boundaries = 3;
  o.seed = 3;
  PolygonSoup soup = generate_mesh(o);
  // A second surface beside it: a closed genus 2.
  GenerateOptions o2;
  o2.genus = 2;
  o2.faces = 1500;
  o2.seed = 9;
  const PolygonSoup other = generate_closed_mesh(o2);
  const std::int64_t offset = static_cast<std::int64_t>(soup.positions.size());
  for (const Vec3d& p : other.positions) soup.positions.push_back({p.x + 100, p.y, p.z});
  for (std::size_t f = 0; f < other.num_faces(); ++f) {
    for (std::size_t k = other.face_begin[f]; k < other.face_begin[f + 1]; ++k) soup.corners.push_back(other.corners[k] + offset);
    soup.face_begin.push_back(soup.corners.size());
  }
  const SurfaceSet set = validate_surfaces(soup);
  REQUIRE(set.components.size() == 2);
  const SurfacesResult r = compute_igms(set, field_options(3000));
  CHECK(r.certified());
  for (const PipelineResult& c : r.components) {
    CHECK(c.certified());
    CHECK(c.stats.layout == "field");
  }
}

TEST_CASE("field pipeline: a surface whose field has a cone of valence 1 falls back to the topological layout") {
  const ValidMesh mesh = needle();
  PipelineOptions o = field_options(500);
  const PipelineResult r = compute_igm(mesh, o);
  check_certified(r, 0);
  CHECK(r.stats.layout == "orbifold");
  CHECK(r.stats.layout_fallback.rfind("field: a cone of valence 1", 0) == 0);
  // The attempt's stages come first, then the fallback's.
  REQUIRE(!r.stats.stages.empty());
  CHECK(r.stats.stages.front().stage == "field");
  bool said = false;
  for (const StageEvent& e : r.stats.stages) said = said || e.stage == "fallback";
  CHECK(said);
}

TEST_CASE("field pipeline: a layout that cannot be built falls back, and says which stage") {
  // This surface's smoothest field gives a layout only after rounds that leave rays out (the
  // patches' side lengths contradict each other at first); with no such round it falls back.
  const ValidMesh mesh = igm_test::generated_mesh(1, 2000, 2);
  PipelineOptions o = field_options(800);
  o.field.alignment = 0;
  o.field_attempts.clear();
  o.field_layout.max_seed_rounds = 0;
  o.field_layout.max_ban_rounds = 0;
  const PipelineResult r = compute_igm(mesh, o);
  check_certified(r, 1);
  CHECK(r.stats.layout == "spread");
  CHECK(r.stats.layout_fallback.rfind("trace: ", 0) == 0);
  CHECK(r.stats.field_layout.rounds == 1);
  // With the defaults (rounds, other alignments) the field layout is built.
  const PipelineResult rounds = compute_igm(mesh, field_options(800));
  check_certified(rounds, 1);
  CHECK(rounds.stats.layout == "field");
}

TEST_CASE("field pipeline: the same input gives the same output") {
  const ValidMesh mesh = igm_test::generated_mesh(3, 2500, 8);
  PipelineOptions o = field_options(1500);
  o.smooth = false;
  const PipelineResult a = compute_igm(mesh, o), b = compute_igm(mesh, o);
  std::ostringstream ea, eb;
  write_igm_obj(ea, a.igm, true);
  write_igm_obj(eb, b.igm, true);
  CHECK(ea.str() == eb.str());
  CHECK(a.quads.quads == b.quads.quads);
}

TEST_CASE("field pipeline: the shared meshes with creases and extremities") {
  IGM_REQUIRE_DATA(dir);
  for (const std::string name : {"fandisk.off", "elk.off", "anchor.off", "helmet.off"}) {
    INFO(name);
    if (igm_test::kSanitized && (name == "anchor.off" || name == "helmet.off")) continue;  // Release only
    const ValidMesh mesh = load_mesh(dir / "meshes/clean" / name);
    const PipelineResult r = compute_igm(mesh, field_options(3000));
    check_certified(r, mesh.genus);
    CHECK(r.stats.layout == "field");
    CHECK(r.quad_quality.sj_median >= 0.9);
  }
}

TEST_CASE("field pipeline: regression: the elk's field without curvature alignment (map_layout splits a chord of a split triangle)") {
  // map_layout splits every edge joining two vertices of one patch side; the edges a split made were
  // not indexed, and a second split in the same triangle threw std::out_of_range (map::at).
  IGM_REQUIRE_DATA(dir);
  const ValidMesh mesh = load_mesh(dir / "meshes/clean/elk.off");
  PipelineOptions o = field_options(10000);
  o.field.alignment = 0;
  o.field_attempts.clear();
  const PipelineResult r = compute_igm(mesh, o);
  check_certified(r, mesh.genus);
  CHECK(r.stats.layout == "field");
}
