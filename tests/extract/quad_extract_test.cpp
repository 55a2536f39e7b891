#include <doctest/doctest.h>

#include <map>
#include <set>

#include "../arrange/arrange_fixture.h"
#include "igm/core/error.h"
#include "igm/extract/quad_extract.h"

using namespace igm;

namespace {

// Closed, oriented 2-manifold check of a quad mesh given as a cell complex (darts = quad sides,
// glued by edge id, so loops and multi-edges at the root are fine). Returns the Euler
// characteristic; fills the valence (dart orbit size) per vertex.
int closed_manifold_euler(const PlanarQuadMesh& m, std::vector<int>* valence = nullptr) {
  const int nq = static_cast<int>(m.quads.size());
  REQUIRE(static_cast<int>(m.quad_edges.size()) == nq);
  std::vector<std::vector<int>> darts_of_edge(m.num_edges);
  for (int f = 0; f < nq; ++f)
    for (int k = 0; k < 4; ++k) darts_of_edge.at(m.quad_edges[f][k]).push_back(4 * f + k);
  std::vector<int> twin(4 * nq, -1);
  auto origin = [&](int d) { return m.quads[d / 4][d % 4]; };
  auto target = [&](int d) { return m.quads[d / 4][(d % 4 + 1) % 4]; };
  for (const auto& ds : darts_of_edge) {
    REQUIRE(ds.size() == 2);  // closed: every edge has two quad sides
    REQUIRE(origin(ds[0]) == target(ds[1]));  // oriented consistently
    REQUIRE(target(ds[0]) == origin(ds[1]));
    twin[ds[0]] = ds[1];
    twin[ds[1]] = ds[0];
  }
  // Rotation around the origin of dart d: twin of the previous side of the same quad.
  std::vector<char> seen(4 * nq, 0);
  std::vector<int> orbits(m.vertices.size(), 0);
  if (valence) valence->assign(m.vertices.size(), 0);
  for (int d0 = 0; d0 < 4 * nq; ++d0) {
    if (seen[d0]) continue;
    const int v = origin(d0);
    int d = d0, n = 0;
    do {
      REQUIRE(origin(d) == v);
      seen[d] = 1;
      d = twin[4 * (d / 4) + (d % 4 + 3) % 4];
      ++n;
    } while (d != d0 && n <= 4 * nq);
    ++orbits[v];
    if (valence) (*valence)[v] = n;
  }
  for (int c : orbits) REQUIRE(c == 1);  // one fan per vertex: manifold
  return static_cast<int>(m.vertices.size()) - m.num_edges + nq;
}

}  // namespace

TEST_CASE("extract: counts, closed manifold of genus g, valences at N = 1") {
  for (int g : {1, 2, 3, 4, 7, 12}) {
    SyntheticDiskOptions o;
    o.subdivisions = 2;
    o.insertions = 20 * g;
    o.perturb = 0.5;
    o.seed = 3 + g;
    auto p = igm_test::run_overlay(g, o);
    const QuadCharts ch = compute_quad_charts(p.tmpl, p.overlay);
    const int nq = g == 1 ? 1 : 5 * g;
    for (int N : {1, 2, 3}) {
      CAPTURE(g);
      CAPTURE(N);
      const PlanarQuadMesh qm = extract_quads(p.tmpl, p.overlay, ch, N, SidePairing::canonical(g));
      CHECK(qm.quads.size() == static_cast<std::size_t>(nq * N * N));
      CHECK(closed_manifold_euler(qm) == 2 - 2 * g);
      if (N >= 3) {  // from N = 3 on, edges are determined by their end vertices (no loops or multi-edges)
        std::map<int, std::pair<int, int>> ends;
        for (std::size_t f = 0; f < qm.quads.size(); ++f)
          for (int k = 0; k < 4; ++k) {
            const int a = qm.quads[f][k], b = qm.quads[f][(k + 1) % 4];
            ends[qm.quad_edges[f][k]] = {std::min(a, b), std::max(a, b)};
          }
        std::set<std::pair<int, int>> pairs;
        for (const auto& [e, ab] : ends) {
          CHECK(ab.first != ab.second);
          pairs.insert(ab);
        }
        CHECK(pairs.size() == ends.size());
      }
      // Locations: non-negative barycentrics summing to 1, reproducing the position, and the
      // position maps through its triangle's chart onto the grid (1/N) Z^2.
      for (const auto& v : qm.vertices) {
        const auto& T = p.overlay.mesh.triangles[v.triangle];
        Rational x = 0, y = 0, s = 0, u = 0, w = 0;
        for (int i = 0; i < 3; ++i) {
          CHECK(sign(v.barycentric[i]) != Sign::Negative);
          s += v.barycentric[i];
          x += v.barycentric[i] * p.overlay.mesh.positions[T[i]].x;
          y += v.barycentric[i] * p.overlay.mesh.positions[T[i]].y;
          u += v.barycentric[i] * ch.uv[v.triangle][i].x;
          w += v.barycentric[i] * ch.uv[v.triangle][i].y;
        }
        CHECK(s == 1);
        CHECK(same_point(v.position, {x, y}));
        const InputPoint ip = to_input(p.disk, p.overlay, v.triangle, v.barycentric);
        const auto& I = p.disk.triangles[ip.input_triangle];
        Rational ix = 0, iy = 0;
        for (int i = 0; i < 3; ++i) {
          CHECK(sign(ip.barycentric[i]) != Sign::Negative);
          ix += ip.barycentric[i] * p.disk.positions[I[i]].x;
          iy += ip.barycentric[i] * p.disk.positions[I[i]].y;
        }
        CHECK(same_point(v.position, {ix, iy}));
        CHECK(Rational(u * N).get_den() == 1);
        CHECK(Rational(w * N).get_den() == 1);
      }
      if (N == 1) {
        CHECK(qm.vertices.size() == static_cast<std::size_t>(g == 1 ? 1 : 2 + 3 * g));
        std::vector<int> valence;
        closed_manifold_euler(qm, &valence);
        if (g == 1) {
          CHECK(valence[0] == 4);
        } else {
          int root = -1, centre = -1, three = 0;
          for (std::size_t v = 0; v < qm.vertices.size(); ++v) {
            if (qm.vertices[v].layout_vertex == 0) root = static_cast<int>(v);
            if (qm.vertices[v].layout_vertex == 1) centre = static_cast<int>(v);
            three += valence[static_cast<int>(v)] == 3;
          }
          REQUIRE(root >= 0);
          REQUIRE(centre >= 0);
          CHECK(valence[root] == 8 * g);
          CHECK(valence[centre] == 3 * g);
          CHECK(three == 3 * g);
        }
      }
    }
  }
}

TEST_CASE("extract: grid points on polygon sides sit at their parameter, glued sides share vertices") {
  const int g = 3, N = 4;
  SyntheticDiskOptions o;
  o.subdivisions = 3;
  o.perturb = 0.5;
  auto p = igm_test::run_overlay(g, o);
  const QuadCharts ch = compute_quad_charts(p.tmpl, p.overlay);
  const SidePairing pairing = SidePairing::canonical(g);
  const PlanarQuadMesh qm = extract_quads(p.tmpl, p.overlay, ch, N, pairing);
  const int n = 4 * g;
  // The m-th grid point of side s, read from the quads of its layout quad (edge 0 of side quads).
  auto side_vertex = [&](int s, int m) {
    const int q = p.tmpl.side_quad[s][0];
    REQUIRE(p.tmpl.side_quad[s][1] == 0);
    int row = 0;
    for (std::size_t k = 0; k < qm.quads.size(); ++k)
      if (qm.layout_quad[k] == q) {
        if (row == std::min(m, N - 1)) return m < N ? qm.quads[k][0] : qm.quads[k][1];
        ++row;
      }
    return -1;
  };
  for (int s = 0; s < n; ++s)
    for (int m = 0; m <= N; ++m) {
      const int v = side_vertex(s, m), pv = side_vertex(pairing.partner[s], N - m);
      CHECK(v == pv);  // the glued copies are one vertex
      const Point2q &a = p.tmpl.points[s], &b = p.tmpl.points[(s + 1) % n];
      const Rational u = make_rational(m, N);
      const Point2q on_s{Rational(a.x + u * (b.x - a.x)), Rational(a.y + u * (b.y - a.y))};
      const int ps = pairing.partner[s];
      const Point2q &c = p.tmpl.points[ps], &d = p.tmpl.points[(ps + 1) % n];
      const Point2q on_p{Rational(c.x + (1 - u) * (d.x - c.x)), Rational(c.y + (1 - u) * (d.y - c.y))};
      if (m > 0 && m < N) CHECK((same_point(qm.vertices[v].position, on_s) || same_point(qm.vertices[v].position, on_p)));
      else CHECK(qm.vertices[v].layout_vertex == 0);
    }
}

TEST_CASE("extract: bad resolution or pairing are typed errors") {
  SyntheticDiskOptions o;
  o.subdivisions = 1;
  auto p = igm_test::run_overlay(2, o);
  const QuadCharts ch = compute_quad_charts(p.tmpl, p.overlay);
  CHECK_THROWS_AS(extract_quads(p.tmpl, p.overlay, ch, 0, SidePairing::canonical(2)), Error);
  CHECK_THROWS_AS(extract_quads(p.tmpl, p.overlay, ch, 2, SidePairing::canonical(3)), Error);
  SidePairing bad = SidePairing::canonical(2);
  bad.partner[0] = 1;
  CHECK_THROWS_AS(extract_quads(p.tmpl, p.overlay, ch, 2, bad), Error);
}
