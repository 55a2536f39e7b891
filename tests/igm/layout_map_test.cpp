#include <doctest/doctest.h>

#include <sstream>

#include "certify/certify.h"
#include "generated_mesh.h"
#include "igm/core/error.h"
#include "igm/igm/layout_map.h"
#include "igm/layout/quantize.h"
#include "layout_builder.h"
#include "patch_fixture.h"

using namespace igm;
using namespace igm_test;

namespace {

auto bumpy = [](int i, int j) { return Vec3d{double(i), double(j), 0.3 * std::sin(i * 0.9) * std::cos(j * 0.7)}; };

certify::Report certify_map(const LayoutMap& m, bool boundary) {
  certify::Options o;
  o.allow_boundary = boundary;
  return certify::certify_igm(certify_input(m.igm, m.igm.corner_uv), o);
}

Rational uv_area2(const std::vector<std::array<Point2q, 3>>& uv) {
  Rational sum = 0;
  for (const auto& t : uv) sum += cross(t[0], t[1], t[2]);
  return sum;
}

// Quantized at edge length H, mapped, certified; the UV areas add up to the quads; every arc end
// (node) at an integer point.
LayoutMap quantize_map_certify(const SurfaceLayout& L, double H, bool boundary) {
  QuantizeOptions qo;
  qo.edge_length = H;
  const Quantization q = quantize_layout(L, qo);
  REQUIRE(q.ok());
  LayoutMap m = map_layout(L, q.arc_length);
  const certify::Report r = certify_map(m, boundary);
  CHECK_MESSAGE(r.valid(), certify::summary(r));
  CHECK(uv_area2(m.igm.corner_uv) == Rational(2 * q.quads));
  std::vector<char> node(m.igm.positions.size(), 0);
  for (const LayoutArc& a : L.arcs) node[a.vertices.front()] = node[a.vertices.back()] = 1;
  int off_grid = 0;
  for (std::size_t t = 0; t < m.igm.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i)
      if (node[m.igm.triangles[t][i]] &&
          (m.igm.corner_uv[t][i].x.get_den() != 1 || m.igm.corner_uv[t][i].y.get_den() != 1))
        ++off_grid;
  CHECK(off_grid == 0);
  CHECK(m.patch_size == q.patch_size);
  return m;
}

std::string exact_obj(const IgmMesh& igm) {
  std::ostringstream s;
  write_igm_obj(s, igm, true);
  return s.str();
}

}  // namespace

TEST_CASE("layout map: the cube, the cube with a split face (T-junctions), certified") {
  for (bool split : {false, true}) {
    CAPTURE(split);
    const SurfaceLayout L = build_layout(cube_spec(4, split));
    const LayoutMap m = quantize_map_certify(L, 0.7, false);
    CHECK(m.stats.patches == static_cast<int>(L.patches.size()));
  }
}

TEST_CASE("layout map: a torus as one patch, and random T-meshes on a torus, certified") {
  quantize_map_certify(build_layout(grid_spec(6, 5, true, true, {Rect{0, 0, 6, 5}}, torus_embedding(6, 5))), 0.5, false);
  for (int seed : {1, 2}) {
    CAPTURE(seed);
    const SurfaceLayout L =
        build_layout(grid_spec(16, 12, true, true, igm_test::random_t_mesh(16, 12, 2, 12, seed), torus_embedding(16, 12)));
    quantize_map_certify(L, 0.3, false);
  }
}

TEST_CASE("layout map: open surfaces: a bumpy square in 2 x 2 patches, a cylinder as one patch, certified with boundary") {
  quantize_map_certify(
      build_layout(grid_spec(4, 6, false, false, {Rect{0, 0, 2, 3}, Rect{2, 0, 4, 3}, Rect{0, 3, 2, 6}, Rect{2, 3, 4, 6}}, bumpy)),
      0.4, true);
  quantize_map_certify(build_layout(grid_spec(8, 3, true, false, {Rect{0, 0, 8, 3}}, cylinder_embedding(8, 0.7))), 0.3, true);
}

TEST_CASE("layout map: edges joining two vertices of one side are split at exact midpoints, the output a refinement") {
  // A 2 x 2 square as one patch with corners (0,0), (2,0), (2,2), (1,2): side 3 bends at (0,2), so
  // the triangle there has three vertices on side 3 and its edge (0,1)-(1,2) joins two of them.
  igm_test::LayoutSpec spec = grid_spec(2, 2, false, false, {}, bumpy);
  auto id = [](int i, int j) { return i + 3 * j; };
  spec.corners.push_back({std::pair{id(0, 0), id(1, 0)}, std::pair{id(2, 0), id(2, 1)}, std::pair{id(2, 2), id(1, 2)},
                          std::pair{id(1, 2), id(0, 2)}});
  const SurfaceLayout L = build_layout(spec);
  REQUIRE(check_surface_layout(L) == "");
  const LayoutMap m = quantize_map_certify(L, 0.5, true);
  CHECK(m.stats.splits == 1);
  CHECK(m.igm.positions.size() == L.positions.size() + 1);
  CHECK(m.igm.triangles.size() == L.triangles.size() + 2);
  const SurfacePoint& mid = m.igm.locations.back();
  CHECK(mid.size() == 2);
  CHECK(mid.v[0] == id(0, 1));
  CHECK(mid.v[1] == id(1, 2));
  CHECK(mid.w[0] == Rational(1, 2));
  // A larger square, side 3 bending at (0, 6): the splits stay at the bend.
  igm_test::LayoutSpec big = grid_spec(6, 6, false, false, {}, bumpy);
  auto jd = [](int i, int j) { return i + 7 * j; };
  big.corners.push_back({std::pair{jd(0, 0), jd(1, 0)}, std::pair{jd(6, 0), jd(6, 1)}, std::pair{jd(6, 6), jd(5, 6)},
                         std::pair{jd(3, 6), jd(2, 6)}});
  const LayoutMap bm = quantize_map_certify(build_layout(big), 0.5, true);
  CHECK(bm.stats.splits == 1);
}

TEST_CASE("layout map: the canonical layouts through the converter: valid surface layouts, nothing split, certified") {
  for (int g : {1, 3})
    for (LayoutKind kind : {LayoutKind::Spread, LayoutKind::Paper}) {
      CAPTURE(g);
      CAPTURE(to_string(kind));
      const ValidMesh mesh = igm_test::generated_mesh(g, 250 * g, 4);
      igm_test::PatchSetup s = igm_test::patch_setup(mesh, kind, false);
      const std::size_t triangles = s.mesh.triangles.size();
      const SurfaceLayout L = to_surface_layout(s.layout, s.mesh, mesh.mesh.num_vertices());
      CHECK(check_surface_layout(L) == "");
      CHECK(L.triangles.size() == triangles);
      CHECK(L.arcs.size() == static_cast<std::size_t>(s.layout.num_surface_edges));
      const LayoutMap m = quantize_map_certify(L, 0.2, false);
      CHECK(m.stats.splits == 0);
    }
}

TEST_CASE("layout map: the same bytes twice") {
  const SurfaceLayout L =
      build_layout(grid_spec(16, 12, true, true, igm_test::random_t_mesh(16, 12, 2, 10, 5), torus_embedding(16, 12)));
  QuantizeOptions qo;
  qo.quads = 300;
  const Quantization q = quantize_layout(L, qo);
  REQUIRE(q.ok());
  CHECK(exact_obj(map_layout(L, q.arc_length).igm) == exact_obj(map_layout(L, q.arc_length).igm));
}

TEST_CASE("layout map: lengths that break a patch, and an invalid layout, are typed errors") {
  const SurfaceLayout L = build_layout(cube_spec(2, true));
  QuantizeOptions qo;
  qo.resolution = 2;
  const Quantization q = quantize_layout(L, qo);
  REQUIRE(q.ok());
  std::vector<int> wrong = q.arc_length;
  ++wrong[0];
  CHECK_THROWS_AS(map_layout(L, wrong), Error);
  CHECK_THROWS_AS(map_layout(L, {1, 2, 3}), Error);
  SurfaceLayout bad = L;
  std::swap(bad.patches[0].sides[0], bad.patches[0].sides[1]);
  try {
    map_layout(bad, q.arc_length);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::InvalidArgument);
  }
}
