#include <doctest/doctest.h>

#include <cmath>

#include "generated_mesh.h"
#include "igm/core/error.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/scale.h"
#include "patch_fixture.h"
#include "random_mesh.h"

using namespace igm;
using igm_test::certify_patch_maps;
using igm_test::patch_setup;
using igm_test::PatchSetup;

namespace {

// Exact sum of the UV areas (twice the area, summed over every triangle).
Rational uv_area2(const std::vector<std::array<Point2q, 3>>& uv) {
  Rational sum = 0;
  for (const auto& t : uv) sum += (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[1].y - t[0].y) * (t[2].x - t[0].x);
  return sum;
}

bool integer_point(const Point2q& p) { return p.x.get_den() == 1 && p.y.get_den() == 1; }

// The corners of every triangle at a layout point sit at integer points of its chart.
int layout_corners_off_grid(const PatchSetup& s, const std::vector<std::array<Point2q, 3>>& uv) {
  std::vector<char> is_point(s.mesh.vertex_of.size(), 0);
  for (int v : s.mesh.point_vertex) is_point[v] = 1;
  int off = 0;
  for (std::size_t t = 0; t < s.mesh.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i)
      if (is_point[s.mesh.triangles[t][i]] && !integer_point(uv[t][i])) ++off;
  return off;
}

}  // namespace

TEST_CASE("patch maps: every layout and both maps certify on generated genus 1-3 meshes, areas add up to the quads") {
  for (int g = 1; g <= 3; ++g)
    for (LayoutKind kind : {LayoutKind::Paper, LayoutKind::Kite, LayoutKind::Spread})
      for (bool affine : {false, true}) {
        CAPTURE(g);
        CAPTURE(to_string(kind));
        CAPTURE(affine);
        const ValidMesh mesh = igm_test::generated_mesh(g, 250 * g, 3);
        const PatchSetup s = patch_setup(mesh, kind, affine);
        SizingOptions so;
        so.quads = 400;
        const Sizing sizing = size_layout(s.layout, layout_edge_lengths(s.layout, s.mesh), so);
        const PatchMaps maps = affine ? map_patches(s.layout, s.mesh, sizing, s.overlay.mesh.positions)
                                      : PatchMaps{igm_test::tutte_maps(s, sizing).igm.corner_uv, {}};
        const certify::Report r = certify_patch_maps(s.mesh, maps.corner_uv);
        CHECK_MESSAGE(r.valid(), certify::summary(r));
        // Every patch fills its a x b rectangle: the UV areas add up to the quad count exactly.
        CHECK(uv_area2(maps.corner_uv) == Rational(2 * sizing.quads));
        CHECK(layout_corners_off_grid(s, maps.corner_uv) == 0);
        if (affine) CHECK(maps.stats.patches == static_cast<int>(s.layout.quads.size()));
      }
}

TEST_CASE("patch maps: a layout quad sized against its chord breaks a transition, and the certifier says so") {
  const ValidMesh mesh = igm_test::generated_mesh(2, 1200, 5);
  const PatchSetup s = patch_setup(mesh, LayoutKind::Spread, true);  // the affine maps take any sizing
  SizingOptions so;
  so.resolution = 3;
  Sizing sizing = size_layout(s.layout, layout_edge_lengths(s.layout, s.mesh), so);
  {
    const PatchMaps maps = map_patches(s.layout, s.mesh, sizing, s.overlay.mesh.positions);
    CHECK(certify_patch_maps(s.mesh, maps.corner_uv).valid());
  }
  // One inner quad gets 4 along its side 0, where its chord says 3: the seams along it no longer
  // glue by a rigid map with an integer translation.
  const int q = static_cast<int>(s.layout.quads.size()) - 1;
  sizing.quad_size[q][0] = 4;
  const PatchMaps maps = map_patches(s.layout, s.mesh, sizing, s.overlay.mesh.positions);
  const certify::Report r = certify_patch_maps(s.mesh, maps.corner_uv);
  CHECK(!r.valid());
  const certify::CheckResult* transitions = r.check(3);
  REQUIRE(transitions != nullptr);
  CHECK(!transitions->passed());
  CHECK(transitions->offending > 0);
}

TEST_CASE("patch maps: hostile geometry (coincident, collinear, 1e300, 1e-300) still maps with positive weights") {
  for (igm_test::Geometry geometry : {igm_test::Geometry::Collapse, igm_test::Geometry::Coincident,
                                      igm_test::Geometry::Collinear, igm_test::Geometry::Huge, igm_test::Geometry::Tiny}) {
    CAPTURE(igm_test::to_string(geometry));
    igm_test::RandomMeshSpec spec;
    spec.genus = 2;
    spec.faces = 300;
    spec.seed = 11;
    spec.edge_splits = 20;
    spec.geometry = geometry;
    const ValidMesh mesh = validate(igm_test::random_closed_mesh(spec));
    const PatchSetup s = patch_setup(mesh, LayoutKind::Spread, false);
    SizingOptions so;
    so.quads = 200;
    // Lengths on positions scaled to about 1 (mesh/scale.h), as the pipeline measures them.
    const double scale = unit_scale(s.input_positions);
    const Sizing sizing = size_layout(s.layout, layout_edge_lengths(s.layout, s.mesh, scale), so);
    const LayoutMap maps = igm_test::tutte_maps(s, sizing, scale);
    const certify::Report r = certify_patch_maps(s.mesh, maps.igm.corner_uv);
    CHECK_MESSAGE(r.valid(), certify::summary(r));
  }
}

TEST_CASE("patch maps: a sizing for another layout is refused") {
  const ValidMesh mesh = igm_test::generated_mesh(2, 800, 1);
  const PatchSetup s = patch_setup(mesh, LayoutKind::Kite, false);
  Sizing wrong;
  wrong.quad_size.resize(3, {1, 1});
  CHECK_THROWS_AS(map_patches(s.layout, s.mesh, wrong, s.overlay.mesh.positions), Error);
}
