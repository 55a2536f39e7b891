#pragma once
// The property every random mesh must have (tests/random): validate accepts it with its genus, and
// compute_igm returns outputs that both certifier reports accept.
#include <doctest/doctest.h>

#include <array>
#include <set>
#include <sstream>
#include <vector>
#include <string>

#include "certify/certify.h"
#include "igm/core/error.h"
#include "igm/mesh/soup.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/output/igm_mesh.h"
#include "igm/pipeline/pipeline.h"
#include "uv_area.h"

namespace igm_test {

// Genus 0 (orbifold embedding) has landed: every sphere must certify too. (Before it landed this
// was false, and spheres had to give exactly Unsupported.)
constexpr bool kGenus0Certifies = true;

struct Outcome {
  bool certified = false;
  bool growth_bound = false;  // normal form only: the typed error of CutOptions::max_normal_form_growth
  int genus = -1;
  int quads = -1;
};

// validate -> compute_igm with `root` (-1: default) -> both certifier reports must be valid, with
// the expected genus and N x N quads per layout quad (layout_quad_count; 2 cells for a sphere). Genus 0: see kGenus0Certifies.
// With `files`, the written exact IGM and quad OBJ are also certified through the certifier's reader.
// With `normal_form`, the one error accepted is Unsupported naming max_normal_form_growth.
inline Outcome run_pipeline(const igm::PolygonSoup& soup, int expected_genus, int root, bool files = false, int resolution = 3,
                            bool normal_form = false) {
  Outcome out;
  const igm::ValidMesh mesh = igm::validate(soup);  // the geometry never changes the combinatorics: must pass
  REQUIRE(mesh.genus == expected_genus);
  igm::PipelineOptions o;
  o.layout = igm::LayoutKind::Spread;  // the topological layout (the field one has its own tests)
  o.resolution = resolution;
  o.quality = false;  // hundreds of meshes: the certificates are the subject here
  o.smooth_iterations = 3;  // every smoothed iterate is certified: a few are enough here
  o.root = root < 0 ? -1 : root % mesh.mesh.num_vertices();
  o.normal_form = normal_form;
  if (expected_genus == 0 && !kGenus0Certifies) {
    try {
      igm::compute_igm(mesh, o);
      FAIL("genus 0 accepted: set kGenus0Certifies = true");
    } catch (const igm::Error& e) {
      CHECK_MESSAGE(e.kind() == igm::ErrorKind::Unsupported, std::string(e.what()));
    }
    return out;
  }
  igm::PipelineResult r;
  try {
    r = igm::compute_igm(mesh, o);
  } catch (const igm::Error& e) {
    if (normal_form && e.kind() == igm::ErrorKind::Unsupported &&
        std::string(e.what()).find("max_normal_form_growth") != std::string::npos) {
      out.growth_bound = true;
      return out;
    }
    FAIL("compute_igm threw on a valid closed mesh: " << std::string(e.what()));
    return out;
  }
  CHECK_MESSAGE(r.igm_report.valid(), igm::certify::summary(r.igm_report));
  CHECK_MESSAGE(r.quad_report.valid(), igm::certify::summary(r.quad_report));
  REQUIRE(r.igm_report.genus.has_value());
  REQUIRE(r.quad_report.genus.has_value());
  CHECK(*r.igm_report.genus == expected_genus);
  CHECK(*r.quad_report.genus == expected_genus);
  // Layout quads: the 2 cells of [0,2] x [0,1] for a sphere, else the default layout's.
  const int layout = expected_genus == 0 ? 2 : igm::layout_quad_count(o.layout, 4 * expected_genus);
  CHECK(static_cast<int>(r.quads.quads.size()) == layout * resolution * resolution);
  // The IGM is on the quads' grid: its exact UV area is their number.
  CHECK(uv_area2(r.igm) == igm::Rational(2 * static_cast<long>(r.quads.quads.size())));
  if (files) {
    std::ostringstream exact, quads;
    igm::write_igm_obj(exact, r.igm, true);
    igm::write_quad_obj(quads, r.quads);
    const igm::certify::Report re = igm::certify::certify_igm_text(exact.str());
    CHECK_MESSAGE(re.valid(), igm::certify::summary(re));
    igm::certify::Options qo;
    qo.expected_genus = expected_genus;
    const igm::certify::Report rq = igm::certify::certify_quads_text(quads.str(), qo);
    CHECK_MESSAGE(rq.valid(), igm::certify::summary(rq));
  }
  out.certified = r.certified();
  out.genus = *r.igm_report.genus;
  out.quads = static_cast<int>(r.quads.quads.size());
  return out;
}

// An open random mesh (boundary loops): validate_surfaces -> one component of genus g with
// `loops` loops -> compute_igm with `root` -> both certifier reports valid in boundary mode, with
// that genus and those loops; the IGM on its quads' grid; the written files through the
// certifier's reader in boundary mode.
inline Outcome run_open_pipeline(const igm::PolygonSoup& soup, int expected_genus, int loops, int root) {
  Outcome out;
  const igm::SurfaceSet set = igm::validate_surfaces(soup);  // the geometry never changes the combinatorics
  REQUIRE(set.components.size() == 1);
  const igm::SurfaceComponent& s = set.components[0];
  REQUIRE(s.genus == expected_genus);
  REQUIRE(static_cast<int>(s.boundary_loops.size()) == loops);
  igm::PipelineOptions o;
  o.layout = igm::LayoutKind::Spread;  // the topological layout (the field one has its own tests)
  o.quads = 600;
  o.quality = false;
  o.smooth_iterations = 3;
  o.smooth_seconds = 0;
  // A root off the boundary (a boundary root is a typed error of cut_open_surface): the first
  // interior vertex from root on, or the default when there is none.
  {
    std::vector<char> on_boundary(s.positions.size(), 0);
    for (const auto& loop : s.boundary_loops)
      for (int v : loop) on_boundary[v] = 1;
    const int nv = static_cast<int>(s.positions.size());
    o.root = -1;
    for (int k = 0; k < nv && o.root < 0; ++k)
      if (!on_boundary[(root + k) % nv]) o.root = (root + k) % nv;
  }
  igm::PipelineResult r;
  try {
    r = igm::compute_igm(s, o);
  } catch (const igm::Error& e) {
    FAIL("compute_igm threw on a valid open mesh: " << std::string(e.what()));
    return out;
  }
  CHECK_MESSAGE(r.igm_report.valid(), igm::certify::summary(r.igm_report));
  CHECK_MESSAGE(r.quad_report.valid(), igm::certify::summary(r.quad_report));
  REQUIRE(r.quad_report.genus.has_value());
  REQUIRE(r.quad_report.boundary_loops.has_value());
  CHECK(*r.quad_report.genus == expected_genus);
  CHECK(*r.quad_report.boundary_loops == loops);
  CHECK(uv_area2(r.igm) == igm::Rational(2 * static_cast<long>(r.quads.quads.size())));
  std::ostringstream exact, quads;
  igm::write_igm_obj(exact, r.igm, false);  // the doubles file: smoothed, so exact doubles
  igm::write_quad_obj(quads, r.quads);
  igm::certify::Options co;
  co.allow_boundary = true;
  co.expected_genus = expected_genus;
  co.expected_boundary_loops = loops;
  if (r.stats.uv_doubles) {
    const igm::certify::Report re = igm::certify::certify_igm_text(exact.str(), co);
    CHECK_MESSAGE(re.valid(), igm::certify::summary(re));
  }
  const igm::certify::Report rq = igm::certify::certify_quads_text(quads.str(), co);
  CHECK_MESSAGE(rq.valid(), igm::certify::summary(rq));
  out.certified = r.certified();
  out.genus = *r.quad_report.genus;
  out.quads = static_cast<int>(r.quads.quads.size());
  return out;
}

// Several components (random_surfaces): validate_surfaces finds them with their (genus, loops),
// compute_igms with a quad count `quads` shared among them certifies every one and the merged
// outputs in components (and boundary) mode, with their (genus, loops) as a multiset; every surface
// has at least its floor; the written merged files certify through the certifier's reader too.
inline Outcome run_surfaces(const igm::PolygonSoup& soup, const std::vector<std::array<int, 2>>& topology,
                            std::int64_t quads) {
  Outcome out;
  const igm::SurfaceSet set = igm::validate_surfaces(soup);
  REQUIRE(set.components.size() == topology.size());
  std::multiset<std::array<int, 2>> expected(topology.begin(), topology.end()), found;
  for (const igm::SurfaceComponent& c : set.components) found.insert({c.genus, static_cast<int>(c.boundary_loops.size())});
  REQUIRE(found == expected);
  igm::PipelineOptions o;
  o.layout = igm::LayoutKind::Spread;  // the topological layout (the field one has its own tests)
  o.quads = quads;
  o.quality = false;
  o.smooth_iterations = 3;
  o.smooth_seconds = 0;
  igm::SurfacesResult r;
  try {
    r = igm::compute_igms(set, o);
  } catch (const igm::Error& e) {
    FAIL("compute_igms threw on valid surfaces: " << std::string(e.what()));
    return out;
  }
  REQUIRE(r.components.size() == topology.size());
  bool loops = false;
  for (std::size_t c = 0; c < r.components.size(); ++c) {
    const igm::PipelineResult& rc = r.components[c];
    CAPTURE(c);
    CHECK_MESSAGE(rc.certified(), igm::certify::summary(rc.igm_report) << " | " << igm::certify::summary(rc.quad_report));
    CHECK(rc.stats.quads >= rc.stats.floor_quads);
    loops = loops || rc.stats.boundary_loops > 0;
  }
  CHECK_MESSAGE(r.igm_report.valid(), igm::certify::summary(r.igm_report));
  CHECK_MESSAGE(r.quad_report.valid(), igm::certify::summary(r.quad_report));
  found.clear();
  for (const auto& c : r.quad_report.components)
    found.insert({static_cast<int>(c.genus.value_or(-1)), static_cast<int>(c.boundary_loops.value_or(-1))});
  CHECK(found == expected);
  CHECK(r.quads_total == static_cast<std::int64_t>(r.quads.quads.size()));
  CHECK(uv_area2(r.igm) == igm::Rational(2 * static_cast<long>(r.quads.quads.size())));
  std::ostringstream exact, quad_text;
  igm::write_igm_obj(exact, r.igm, true);
  igm::write_quad_obj(quad_text, r.quads);
  igm::certify::Options co;
  co.allow_components = true;
  co.allow_boundary = loops;
  const igm::certify::Report re = igm::certify::certify_igm_text(exact.str(), co);
  CHECK_MESSAGE(re.valid(), igm::certify::summary(re));
  co.expected_components.clear();
  for (const auto& t : topology) co.expected_components.push_back({t[0], t[1]});
  const igm::certify::Report rq = igm::certify::certify_quads_text(quad_text.str(), co);
  CHECK_MESSAGE(rq.valid(), igm::certify::summary(rq));
  out.certified = r.certified() && re.valid() && rq.valid();
  out.quads = static_cast<int>(r.quads.quads.size());
  return out;
}

}  // namespace igm_test
