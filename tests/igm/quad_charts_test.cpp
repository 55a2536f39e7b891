#include <doctest/doctest.h>

#include <map>

#include "../arrange/arrange_fixture.h"
#include "igm/core/error.h"
#include "igm/igm/quad_charts.h"

using namespace igm;

namespace {

bool is_integer(const Rational& q) { return q.get_den() == 1; }

// Is there k in 0..3 and an integer translation with b_i = R^k a_i + t for both i?
bool rigid_integer(const Point2q& a0, const Point2q& a1, const Point2q& b0, const Point2q& b1) {
  for (int k = 0; k < 4; ++k) {
    auto rot = [&](const Point2q& p) {
      Point2q r = p;
      for (int i = 0; i < k; ++i) r = {Rational(-r.y), r.x};
      return r;
    };
    const Point2q r0 = rot(a0), r1 = rot(a1);
    const Rational tx = b0.x - r0.x, ty = b0.y - r0.y;
    if (is_integer(tx) && is_integer(ty) && b1.x - r1.x == tx && b1.y - r1.y == ty) return true;
  }
  return false;
}

void check_charts(int g, const SyntheticDiskOptions& o) {
  CAPTURE(g);
  auto p = igm_test::run_overlay(g, o);
  const QuadCharts ch = compute_quad_charts(p.tmpl, p.overlay);
  const auto& F = p.overlay.mesh.triangles;
  const auto& X = p.overlay.mesh.positions;
  const auto regions = template_regions(p.tmpl);
  REQUIRE(ch.uv.size() == F.size());
  int n_pos = 0, n_inside = 0;
  for (std::size_t t = 0; t < F.size(); ++t) {
    n_pos += orient2d(ch.uv[t][0], ch.uv[t][1], ch.uv[t][2]) == Sign::Positive;
    // Independent label check: the centroid lies in the closed template region named.
    const Point2q c{Rational((X[F[t][0]].x + X[F[t][1]].x + X[F[t][2]].x) / 3),
                    Rational((X[F[t][0]].y + X[F[t][1]].y + X[F[t][2]].y) / 3)};
    const auto& rc = regions[ch.region[t]].corners;
    bool in = true;
    for (std::size_t i = 0; i < rc.size(); ++i)
      in = in && orient2d(p.tmpl.points[rc[i]], p.tmpl.points[rc[(i + 1) % rc.size()]], c) == Sign::Positive;
    n_inside += in;
  }
  CHECK(n_pos == static_cast<int>(F.size()));
  CHECK(n_inside == static_cast<int>(F.size()));
  // Corners map to integer points; points on side s at parameter u map to parameter u along the
  // unit-square edge of the side's quad.
  const int n = 4 * g;
  int side_points = 0;
  const Point2q U[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const PlanarAdjacency adj = PlanarAdjacency::build(static_cast<int>(X.size()), F);
  std::vector<char> on_boundary(X.size(), 0);
  for (std::size_t t = 0; t < F.size(); ++t)
    for (int i = 0; i < 3; ++i)
      if (adj.neighbor[t][i] < 0) on_boundary[F[t][i]] = on_boundary[F[t][(i + 1) % 3]] = 1;
  for (std::size_t t = 0; t < F.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int v = F[t][i];
      if (!on_boundary[v]) continue;
      const Point2q& uv = ch.uv[t][i];
      if (v < n) CHECK((is_integer(uv.x) && is_integer(uv.y)));
      for (int s = 0; s < n; ++s) {
        const Point2q &a = p.tmpl.points[s], &b = p.tmpl.points[(s + 1) % n];
        if (orient2d(a, b, X[v]) != Sign::Zero) continue;
        const auto [q, e] = p.tmpl.side_quad[s];
        if (ch.quad[t] != q) continue;
        const Rational u = dot(a, X[v], b) / dot(a, b, b);
        const Point2q expect{Rational(U[e].x + u * (U[(e + 1) % 4].x - U[e].x)), Rational(U[e].y + u * (U[(e + 1) % 4].y - U[e].y))};
        CHECK(same_point(uv, expect));
        ++side_points;
      }
    }
  CHECK(side_points > 0);
  // Across every interior edge: same UV inside a quad, a rigid integer transition between quads.
  int seams = 0, bad = 0;
  for (std::size_t t = 0; t < F.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int nb = adj.neighbor[t][i];
      if (nb < 0) continue;
      const int j = adj.neighbor_edge[t][i];
      const Point2q &a0 = ch.uv[t][i], &a1 = ch.uv[t][(i + 1) % 3];
      const Point2q &b0 = ch.uv[nb][(j + 1) % 3], &b1 = ch.uv[nb][j];  // same vertices as a0, a1
      if (ch.quad[t] == ch.quad[nb]) {
        bad += !(same_point(a0, b0) && same_point(a1, b1));
      } else {
        ++seams;
        bad += !rigid_integer(a0, a1, b0, b1);
      }
    }
  CHECK(bad == 0);
  CHECK(seams > 0);
  MESSAGE("g=" << g << ": " << F.size() << " triangles, max UV bits " << ch.max_uv_bits);
}

}  // namespace

TEST_CASE("charts: piecewise-affine UV, positive, integer corners, side parameters, rigid seams") {
  for (int g : {2, 3, 4, 5, 8, 12}) {
    SyntheticDiskOptions o;
    o.subdivisions = 2;
    o.insertions = 30 * g;
    o.seed = 7 + g;
    check_charts(g, o);
    o.perturb = 0.6;
    check_charts(g, o);
  }
  SyntheticDiskOptions o;
  o.subdivisions = 2;
  o.insertions = 500;
  o.perturb = 0.3;
  check_charts(50, o);
  check_charts(51, o);
}

TEST_CASE("charts: genus 1 on the unit square is the identity (no diagonal inserted)") {
  SyntheticDiskOptions o;
  o.subdivisions = 4;
  o.insertions = 100;
  o.perturb = 0.5;
  auto p = igm_test::run_overlay(1, o);
  CHECK(p.overlay.mesh.triangles.size() == p.disk.triangles.size());  // sides only: nothing to split
  const QuadCharts ch = compute_quad_charts(p.tmpl, p.overlay);
  for (std::size_t t = 0; t < p.overlay.mesh.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) CHECK(same_point(ch.uv[t][i], p.overlay.mesh.positions[p.overlay.mesh.triangles[t][i]]));
  // A general convex quadrilateral (genus 1) gets a diagonal and a piecewise-affine map.
  const std::vector<Point2q> quad = {{0, 0}, {3, 0}, {2, 2}, {0, 1}};
  const Point2q c{1, 1};
  auto disk = make_synthetic_disk(quad, c, o);
  auto t = make_quad_template(quad, c);
  auto segs = template_segments(t);
  auto ov = overlay_segments(disk, template_geometry(t, segs));
  const QuadCharts k = compute_quad_charts(t, ov);
  for (std::size_t f = 0; f < ov.mesh.triangles.size(); ++f) CHECK(orient2d(k.uv[f][0], k.uv[f][1], k.uv[f][2]) == Sign::Positive);
}

TEST_CASE("charts: an overlay made with other segments is rejected") {
  SyntheticDiskOptions o;
  o.subdivisions = 1;
  auto p = igm_test::run_overlay(2, o);
  OverlayResult wrong = p.overlay;
  wrong.chains.pop_back();
  CHECK_THROWS_AS(compute_quad_charts(p.tmpl, wrong), Error);
}
