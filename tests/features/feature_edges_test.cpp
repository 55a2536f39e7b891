#include "igm/features/feature_edges.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <sstream>

#include "igm/core/error.h"
#include "../quality/error_kind.h"
#include "test_surfaces.h"

namespace {

using igm::FeatureEdges;
using igm::FeatureOptions;
using igm_test::Surface;

using igm_test::kind_of;

// Every curve's half-edges are feature half-edges joining its consecutive vertices; its ends are
// corners (or it is a corner-free closed loop); every feature edge is on exactly one curve.
void check_curves(const Surface& s, const FeatureEdges& f) {
  std::vector<int> on_curve(s.mesh.num_halfedges(), 0);
  for (const igm::FeatureCurve& c : f.curves) {
    REQUIRE(c.vertices.size() == c.halfedges.size() + 1);
    for (std::size_t i = 0; i < c.halfedges.size(); ++i) {
      const int h = c.halfedges[i];
      CHECK(s.mesh.origin(h) == c.vertices[i]);
      CHECK(s.mesh.target(h) == c.vertices[i + 1]);
      CHECK(f.halfedge[h] == 1);
      ++on_curve[s.mesh.twin(h) >= 0 && s.mesh.twin(h) < h ? s.mesh.twin(h) : h];
    }
    const bool starts_at_corner = std::binary_search(f.corners.begin(), f.corners.end(), c.vertices.front());
    CHECK((starts_at_corner || c.closed));
    if (starts_at_corner) CHECK(std::binary_search(f.corners.begin(), f.corners.end(), c.vertices.back()));
  }
  for (int h : f.edges) CHECK(on_curve[h] == 1);
  int used = 0;
  for (int n : on_curve) used += n;
  CHECK(used == static_cast<int>(f.edges.size()));
}

// The unit sphere: a subdivided cube pushed out radially (no dihedral angle near 35 degrees).
Surface sphere(int n) {
  Surface s = igm_test::subdivided_cube(n);
  for (igm::Vec3d& p : s.positions) {
    const double r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    p = {p.x / r, p.y / r, p.z / r};
  }
  return s;
}

}  // namespace

TEST_CASE("features: the resolution rule marks the chains shorter than min_quad_edges quads, not followed") {
  // A box 4 x 2 x 2 (the subdivided cube stretched along x): 4 creases of length 4 along x, 8 of
  // length 2. Quads of edge 0.5 need 6 x 0.5 = 3: the 8 short creases are measured, not followed.
  Surface s = igm_test::subdivided_cube(4);
  for (igm::Vec3d& p : s.positions) p.x *= 2;
  FeatureOptions o;
  const FeatureEdges all = igm::detect_features(s.mesh, s.positions, {}, o);
  REQUIRE(all.stats.curves == 12);
  CHECK(all.stats.short_chains == 0);
  for (int h : all.edges) CHECK(all.follow[h] == 1);
  o.quad_size = 0.5;
  const FeatureEdges f = igm::detect_features(s.mesh, s.positions, {}, o);
  check_curves(s, f);
  CHECK(f.edges == all.edges);  // still features: measured
  CHECK(f.stats.curves == 12);
  CHECK(f.stats.short_chains == 8);
  CHECK(f.stats.short_edges == 8 * 4);
  int followed = 0;
  for (int h = 0; h < s.mesh.num_halfedges(); ++h) {
    if (!f.halfedge[h]) {
      CHECK(f.follow[h] == 0);
      continue;
    }
    const igm::Vec3d& a = s.positions[s.mesh.origin(h)];
    const igm::Vec3d& b = s.positions[s.mesh.target(h)];
    const bool along_x = a.y == b.y && a.z == b.z;
    CHECK(f.follow[h] == (along_x ? 1 : 0));
    followed += f.follow[h];
  }
  CHECK(followed == 2 * 4 * 4);  // 4 creases of 4 edges, both half-edges
  // A user edge on a short crease: that crease is followed.
  int short_h = -1;
  for (int h : f.edges)
    if (!f.follow[h] && short_h < 0) short_h = h;
  REQUIRE(short_h >= 0);
  const FeatureEdges u =
      igm::detect_features(s.mesh, s.positions, {{s.mesh.origin(short_h), s.mesh.target(short_h)}}, o);
  CHECK(u.stats.short_chains == 7);
  CHECK(u.follow[short_h] == 1);
  // 0 for either disables the rule; bad values are typed errors.
  o.min_quad_edges = 0;
  CHECK(igm::detect_features(s.mesh, s.positions, {}, o).stats.short_chains == 0);
  o.quad_size = -1;
  CHECK_THROWS_AS(igm::detect_features(s.mesh, s.positions, {}, o), igm::Error);
}

TEST_CASE("features: a subdivided cube has 12 curves of n edges meeting 3 at each of 8 corners") {
  for (int n : {1, 4}) {
    const Surface s = igm_test::subdivided_cube(n);
    const FeatureEdges f = igm::detect_features(s.mesh, s.positions);
    CHECK(f.stats.edges == 12 * n);
    CHECK(f.stats.curves == 12);
    CHECK(f.stats.closed_curves == 0);
    CHECK(f.stats.corners == 8);
    CHECK(f.stats.length == doctest::Approx(24.0));
    CHECK(f.stats.dropped_chains == 0);
    check_curves(s, f);
    for (const igm::FeatureCurve& c : f.curves) {
      CHECK(c.halfedges.size() == static_cast<std::size_t>(n));
      CHECK(c.length == doctest::Approx(2.0));
    }
    for (int v : f.corners) {  // the cube's corners, each on 3 curves
      const igm::Vec3d& p = s.positions[v];
      CHECK(std::fabs(p.x) == 1.0);
      CHECK(std::fabs(p.y) == 1.0);
      CHECK(std::fabs(p.z) == 1.0);
      int ends = 0;
      for (const igm::FeatureCurve& c : f.curves) ends += (c.vertices.front() == v) + (c.vertices.back() == v);
      CHECK(ends == 3);
    }
    // The cube's creases are 90 degrees: none above 91, all at 89.
    FeatureOptions o;
    o.angle_degrees = 91;
    CHECK(igm::detect_features(s.mesh, s.positions, {}, o).stats.edges == 0);
    o.angle_degrees = 89;
    CHECK(igm::detect_features(s.mesh, s.positions, {}, o).stats.edges == 12 * n);
    o.enabled = false;
    o.angle_degrees = 89;
    CHECK(igm::detect_features(s.mesh, s.positions, {}, o).stats.edges == 0);
  }
}

TEST_CASE("features: smooth sphere and torus have none at 35 degrees (and many at 5)") {
  const Surface ball = sphere(8);
  const Surface ring = igm_test::torus(3, 1, 48, 24);
  for (const Surface* s : {&ball, &ring}) {
    const FeatureEdges f = igm::detect_features(s->mesh, s->positions);
    CHECK(f.stats.edges == 0);
    CHECK(f.curves.empty());
    CHECK(f.corners.empty());
    FeatureOptions o;
    o.angle_degrees = 5;
    o.noise_min_edges = 0;
    const FeatureEdges g = igm::detect_features(s->mesh, s->positions, {}, o);
    CHECK(g.stats.edges > 10);
    check_curves(*s, g);
  }
}

TEST_CASE("features: user edges are merged, a pair that is not an edge throws naming it") {
  const Surface s = igm_test::subdivided_cube(4);
  // A face-diagonal-free edge inside the face z = 1: two vertices of one grid square's side.
  int a = -1, b = -1;
  for (int h = 0; h < s.mesh.num_halfedges() && a < 0; ++h) {
    const igm::Vec3d &p = s.positions[s.mesh.origin(h)], &q = s.positions[s.mesh.target(h)];
    if (p.z == 1 && q.z == 1 && std::fabs(p.x) < 1 && std::fabs(p.y) < 1 && std::fabs(q.x) < 1 && std::fabs(q.y) < 1)
      a = s.mesh.origin(h), b = s.mesh.target(h);
  }
  REQUIRE(a >= 0);
  const FeatureEdges f = igm::detect_features(s.mesh, s.positions, {{a, b}, {b, a}});
  CHECK(f.stats.edges == 49);
  CHECK(f.stats.user_edges == 1);
  CHECK(f.stats.curves == 13);
  CHECK(f.stats.corners == 10);  // the lone edge's two ends
  check_curves(s, f);
  // Only the user's: --no-features --features FILE.
  FeatureOptions only;
  only.enabled = false;
  CHECK(igm::detect_features(s.mesh, s.positions, {{a, b}}, only).stats.edges == 1);

  // Two vertices of the top face far apart: no edge.
  int far = -1;
  for (int v = 0; v < s.mesh.num_vertices(); ++v)
    if (s.positions[v].z == -1) far = v;
  REQUIRE(far >= 0);
  try {
    igm::detect_features(s.mesh, s.positions, {{a, far}});
    FAIL("no error");
  } catch (const igm::Error& e) {
    CHECK(e.kind() == igm::ErrorKind::InvalidArgument);
    CHECK(std::string(e.what()).find("(" + std::to_string(a) + ", " + std::to_string(far) + ")") != std::string::npos);
    CHECK(std::string(e.what()).find("not an edge") != std::string::npos);
  }
  CHECK(kind_of([&] { igm::detect_features(s.mesh, s.positions, {{a, a}}); }) == igm::ErrorKind::InvalidArgument);
  CHECK(kind_of([&] { igm::detect_features(s.mesh, s.positions, {{a, s.mesh.num_vertices()}}); }) ==
        igm::ErrorKind::InvalidArgument);
  for (double bad : {-1.0, 180.5, std::nan("")}) {
    FeatureOptions o;
    o.angle_degrees = bad;
    CHECK(kind_of([&] { igm::detect_features(s.mesh, s.positions, {}, o); }) == igm::ErrorKind::InvalidArgument);
  }
  // Through input ids (the pipeline's path): a pair found on no surface is named.
  std::vector<std::int64_t> input_vertex(s.mesh.num_vertices());
  for (int v = 0; v < s.mesh.num_vertices(); ++v) input_vertex[v] = 1000 + v;
  const std::vector<std::array<std::int64_t, 2>> pairs{{1000 + a, 1000 + b}, {1000 + a, 1000 + far}};
  std::vector<std::uint8_t> found;
  const auto mapped = igm::input_feature_edges(s.mesh, input_vertex, pairs, found);
  REQUIRE(mapped.size() == 1);
  CHECK(mapped[0] == std::array<int, 2>{a, b});
  CHECK(found == std::vector<std::uint8_t>{1, 0});
  CHECK(kind_of([&] { igm::check_feature_edges_found(pairs, found); }) == igm::ErrorKind::InvalidArgument);
}

TEST_CASE("features: the turn rule makes corners where a curve turns") {
  const Surface s = igm_test::subdivided_cube(1);
  // The 4 edges around the cube's face z = 1, given by the user only.
  std::vector<int> top;
  for (int v = 0; v < s.mesh.num_vertices(); ++v)
    if (s.positions[v].z == 1) top.push_back(v);
  REQUIRE(top.size() == 4);
  std::vector<std::array<int, 2>> loop;
  for (int u : top)
    for (int w : top)
      if (u < w && s.positions[u].x != s.positions[w].x && s.positions[u].y != s.positions[w].y) continue;
      else if (u < w) loop.push_back({u, w});
  REQUIRE(loop.size() == 4);
  FeatureOptions o;
  o.enabled = false;
  FeatureEdges f = igm::detect_features(s.mesh, s.positions, loop, o);
  CHECK(f.stats.corners == 4);  // 90-degree turns >= 60
  CHECK(f.stats.curves == 4);
  CHECK(f.stats.closed_curves == 0);
  check_curves(s, f);
  o.corner_angle_degrees = 120;
  f = igm::detect_features(s.mesh, s.positions, loop, o);
  CHECK(f.stats.corners == 0);
  CHECK(f.stats.curves == 1);
  CHECK(f.stats.closed_curves == 1);
  CHECK(f.curves[0].vertices.size() == 5);
  check_curves(s, f);
}

TEST_CASE("features: the noise rule drops a bump's short chains and keeps the creases") {
  Surface s = igm_test::subdivided_cube(8);
  // A spike on the face z = 1 at its centre vertex (0, 0, 1): the ring around it becomes sharp.
  int centre = -1;
  for (int v = 0; v < s.mesh.num_vertices(); ++v)
    if (s.positions[v].x == 0 && s.positions[v].y == 0 && s.positions[v].z == 1) centre = v;
  REQUIRE(centre >= 0);
  s.positions[centre].z = 1.3;
  FeatureOptions off;
  off.noise_min_edges = 0;
  const FeatureEdges all = igm::detect_features(s.mesh, s.positions, {}, off);
  CHECK(all.stats.edges > 96);
  CHECK(all.stats.dropped_chains == 0);
  // Chains of fewer than 12 edges shorter than half the diagonal (1.73) go; the cube's creases
  // (8 edges, length 2) stay.
  FeatureOptions rule;
  rule.noise_min_edges = 12;
  rule.noise_min_length = 0.5;
  const FeatureEdges kept = igm::detect_features(s.mesh, s.positions, {}, rule);
  CHECK(kept.stats.edges == 96);
  CHECK(kept.stats.curves == 12);
  CHECK(kept.stats.corners == 8);
  CHECK(kept.stats.dropped_chains >= 1);
  CHECK(kept.stats.dropped_edges == all.stats.edges - 96);
  check_curves(s, kept);
  // The default rule (fewer than 5 edges and below 2 % of the diagonal) keeps this large bump.
  CHECK(igm::detect_features(s.mesh, s.positions).stats.edges == all.stats.edges);
}

TEST_CASE("features: the default noise rule drops a small bump on a long prism") {
  // [-1, 1]^2 x [-30, 30] (diagonal 60.1: 2 % is 1.2), cap z = 30 in 16 x 16 squares; a valence-4
  // vertex of the cap raised by 0.3: the 4 edges around it (length 4 x 0.18) turn sharp.
  Surface s = igm_test::subdivided_cube(16);
  for (igm::Vec3d& p : s.positions) p.z *= 30;
  int bump = -1;
  for (int v = 0; v < s.mesh.num_vertices() && bump < 0; ++v) {
    const igm::Vec3d& p = s.positions[v];
    if (p.z == 30 && std::fabs(p.x) < 0.5 && std::fabs(p.y) < 0.5 && s.mesh.valence(v) == 4) bump = v;
  }
  REQUIRE(bump >= 0);
  s.positions[bump].z += 0.3;
  FeatureOptions off;
  off.noise_min_edges = 0;
  const FeatureEdges all = igm::detect_features(s.mesh, s.positions, {}, off);
  CHECK(all.stats.edges >= 12 * 16 + 4);
  const FeatureEdges f = igm::detect_features(s.mesh, s.positions);
  CHECK(f.stats.edges == 12 * 16);
  CHECK(f.stats.curves == 12);
  CHECK(f.stats.corners == 8);
  CHECK(f.stats.dropped_chains >= 1);
  CHECK(f.stats.dropped_edges == all.stats.edges - 12 * 16);
  check_curves(s, f);
}

TEST_CASE("features: the same result on every call") {
  Surface s = igm_test::subdivided_cube(6);
  for (std::size_t v = 0; v < s.positions.size(); ++v)  // a deterministic wobble
    s.positions[v].x += 0.01 * std::sin(3.0 * static_cast<double>(v));
  FeatureOptions o;
  o.angle_degrees = 20;
  const FeatureEdges f = igm::detect_features(s.mesh, s.positions, {}, o), g = igm::detect_features(s.mesh, s.positions, {}, o);
  CHECK(f.halfedge == g.halfedge);
  CHECK(f.edges == g.edges);
  CHECK(f.corners == g.corners);
  REQUIRE(f.curves.size() == g.curves.size());
  for (std::size_t i = 0; i < f.curves.size(); ++i) {
    CHECK(f.curves[i].halfedges == g.curves[i].halfedges);
    CHECK(std::memcmp(&f.curves[i].length, &g.curves[i].length, sizeof(double)) == 0);
  }
  check_curves(s, f);
}

TEST_CASE("features: the features file reader") {
  std::istringstream good("# creases\n0 1\n\n  2 3   # trailing\n4\t5\n");
  const auto pairs = igm::parse_feature_edges(good, "f.txt");
  CHECK(pairs == std::vector<std::array<std::int64_t, 2>>{{0, 1}, {2, 3}, {4, 5}});
  for (const char* bad : {"0 1\n2\n", "0 1\n1 2 3\n", "0 1\nx 2\n", "0 1\n-1 2\n", "0 1\n1.5 2\n"}) {
    std::istringstream in(bad);
    try {
      igm::parse_feature_edges(in, "f.txt");
      FAIL("no error for " << bad);
    } catch (const igm::Error& e) {
      CHECK(e.kind() == igm::ErrorKind::Parse);
      CHECK(e.elements() == std::vector<std::int64_t>{2});
      CHECK(std::string(e.what()).find("f.txt: line 2") != std::string::npos);
    }
  }
  CHECK(kind_of([] { igm::read_feature_edges("/nonexistent/features.txt"); }) == igm::ErrorKind::Io);
}
