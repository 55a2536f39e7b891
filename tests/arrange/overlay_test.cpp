#include <doctest/doctest.h>

#include <set>

#include "arrange_fixture.h"
#include "igm/core/error.h"

using namespace igm;

namespace {

Point2q P(long x, long y) { return {Rational(x), Rational(y)}; }

// An n x n grid on [0,n]^2, each cell split along the diagonal (+1: lower-left to upper-right,
// -1: the other one).
PlanarTriangulation grid(int n, int diag = 1) {
  PlanarTriangulation m;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) m.positions.push_back(P(x, y));
  auto id = [&](int x, int y) { return y * (n + 1) + x; };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = id(x, y), b = id(x + 1, y), c = id(x + 1, y + 1), d = id(x, y + 1);
      if (diag > 0) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, c, d});
      }
    }
  return m;
}

OverlayResult checked(const PlanarTriangulation& m, const std::vector<Segment2>& s) {
  OverlayResult r = overlay_segments(m, s);
  const std::string err = check_overlay(m, s, r);
  CHECK(err == "");
  return r;
}

ErrorKind kind_of(const PlanarTriangulation& m, const std::vector<Segment2>& s) {
  try {
    overlay_segments(m, s);
  } catch (const Error& e) {
    return e.kind();
  }
  return ErrorKind::Internal;  // "no error" is reported as Internal so the CHECK fails
}

}  // namespace

TEST_CASE("overlay: degenerate single segments on a grid") {
  const PlanarTriangulation g2 = grid(2), g2b = grid(2, -1);
  SUBCASE("along edges through a vertex") {
    auto r = checked(g2, {{P(0, 0), P(2, 2)}});
    CHECK(r.chains[0] == std::vector<int>{0, 4, 8});
    CHECK(r.mesh.triangles.size() == g2.triangles.size());
  }
  SUBCASE("across faces through a vertex") {
    auto r = checked(g2b, {{P(0, 0), P(2, 2)}});
    CHECK(r.chains[0].size() == 5);  // 2 crossings + the middle vertex
    CHECK(r.chains[0][2] == 4);
    CHECK(r.stats.crossings == 2);
  }
  SUBCASE("end points inside an edge, along it") {
    auto r = checked(grid(1), {{{Rational(1, 4), Rational(1, 4)}, {Rational(3, 4), Rational(3, 4)}}});
    CHECK(r.chains[0].size() == 2);
    CHECK(r.mesh.triangles.size() == 6);
  }
  SUBCASE("end points inside triangles, generic crossing") {
    auto r = checked(grid(1), {{{Rational(1, 5), Rational(3, 5)}, {Rational(4, 5), Rational(1, 3)}}});
    CHECK(r.chains[0].size() == 3);
    CHECK(r.stats.crossings == 1);
  }
  SUBCASE("end points on the boundary, crossing at an edge point") {
    auto r = checked(g2b, {{{Rational(0), Rational(1, 2)}, {Rational(2), Rational(1, 2)}}});
    CHECK(r.chains[0].size() == 5);
    auto s = checked(g2b, {{P(0, 1), P(2, 1)}});  // along edges
    CHECK(s.chains[0] == std::vector<int>{3, 4, 5});
  }
  SUBCASE("boundary side as a segment") {
    auto r = checked(g2, {{P(2, 0), P(2, 2)}});
    CHECK(r.chains[0] == std::vector<int>{2, 5, 8});
  }
  SUBCASE("a segment inside one triangle") {
    auto r = checked(grid(1), {{{Rational(1, 2), Rational(1, 8)}, {Rational(7, 8), Rational(1, 4)}}});
    CHECK(r.chains[0].size() == 2);
  }
}

TEST_CASE("overlay: many segments meeting at a point inside a triangle, at a vertex, on an edge") {
  for (const Point2q& c : {Point2q{Rational(3, 10), Rational(7, 10)}, P(1, 1), Point2q{Rational(1), Rational(1, 2)}}) {
    std::vector<Segment2> segs;
    for (int k = 0; k <= 8; ++k) segs.push_back({c, {make_rational(k, 4), Rational(0)}});
    for (int k = 1; k <= 8; ++k) segs.push_back({c, {Rational(2), make_rational(k, 4)}});
    for (int k = 0; k < 8; ++k) segs.push_back({c, {make_rational(k, 4), Rational(2)}});
    for (int k = 1; k < 8; ++k) segs.push_back({c, {Rational(0), make_rational(k, 4)}});
    for (int diag : {1, -1}) checked(grid(2, diag), segs);
  }
}

TEST_CASE("overlay: invalid segments give typed errors") {
  const PlanarTriangulation m = grid(2);
  CHECK(kind_of(m, {{P(0, 0), P(2, 2)}, {P(0, 2), P(2, 0)}}) == ErrorKind::InvalidArgument);  // cross at a vertex
  CHECK(kind_of(m, {{P(0, 1), P(2, 1)}, {P(1, 0), {Rational(1, 2), Rational(2)}}}) == ErrorKind::InvalidArgument);
  CHECK(kind_of(m, {{{Rational(1, 5), Rational(1, 2)}, {Rational(3, 5), Rational(1, 2)}},
                    {{Rational(2, 5), Rational(1, 3)}, {Rational(2, 5), Rational(2, 3)}}}) == ErrorKind::InvalidArgument);
  CHECK(kind_of(m, {{P(0, 0), P(2, 2)}, {P(1, 1), P(2, 1)}}) == ErrorKind::InvalidArgument);   // through an end point
  CHECK(kind_of(m, {{P(0, 0), P(2, 2)}, {{Rational(1, 2), Rational(1, 2)}, P(2, 2)}}) == ErrorKind::InvalidArgument);  // overlap
  CHECK(kind_of(m, {{{Rational(1, 5), Rational(1, 5)}, {Rational(3, 5), Rational(3, 5)}},
                    {{Rational(2, 5), Rational(2, 5)}, {Rational(4, 5), Rational(4, 5)}}}) == ErrorKind::InvalidArgument);
  PlanarTriangulation tri;  // one triangle: chords between boundary points only
  tri.positions = {P(0, 0), P(4, 0), P(0, 4)};
  tri.triangles = {{0, 1, 2}};
  CHECK(kind_of(tri, {{P(1, 0), P(0, 3)}, {P(3, 0), P(0, 1)}}) == ErrorKind::InvalidArgument);  // chords cross
  CHECK(kind_of(tri, {{P(2, 0), P(0, 2)}, {P(0, 2), P(2, 0)}}) == ErrorKind::InvalidArgument);  // same chord twice
  checked(tri, {{P(1, 0), P(0, 1)}, {P(2, 0), P(0, 2)}, {P(3, 0), P(0, 3)}, {P(3, 0), P(3, 1)}, {P(0, 3), P(1, 3)}});
  CHECK(kind_of(m, {{P(0, 0), P(3, 1)}}) == ErrorKind::InvalidArgument);  // leaves the polygon
  CHECK(kind_of(m, {{P(5, 5), P(1, 1)}}) == ErrorKind::InvalidArgument);  // starts outside
  CHECK(kind_of(m, {{P(1, 1), P(1, 1)}}) == ErrorKind::InvalidArgument);  // zero length
  PlanarTriangulation flipped = m;
  std::swap(flipped.triangles[3][0], flipped.triangles[3][1]);
  CHECK_THROWS_AS(overlay_segments(flipped, {}), Error);
  PlanarTriangulation concave = grid(2);
  concave.triangles.erase(concave.triangles.begin() + 6, concave.triangles.begin() + 8);  // remove a corner cell
  CHECK(kind_of(concave, {}) == ErrorKind::InvalidArgument);
}

TEST_CASE("overlay: the paper layout and its diagonals on synthetic disks, exact and degenerate (genus 2..12)") {
  for (int g = 2; g <= 12; ++g) {
    CAPTURE(g);
    SyntheticDiskOptions o;
    o.subdivisions = g <= 4 ? 3 : 2;
    o.insertions = 50 * g;
    o.seed = static_cast<std::uint64_t>(g);
    auto p = igm_test::run_overlay(g, o);
    CHECK(check_overlay(p.disk, p.geometry, p.overlay) == "");
    o.perturb = 0.7;
    auto q = igm_test::run_overlay(g, o);
    CHECK(check_overlay(q.disk, q.geometry, q.overlay) == "");
    CHECK(q.overlay.stats.crossings > 0);
  }
}

TEST_CASE("overlay: larger genus, odd and even, up to ~50k triangles") {
  for (int g : {50, 51}) {
    CAPTURE(g);
    SyntheticDiskOptions o;
    o.subdivisions = 3;
    o.insertions = 2000;
    o.perturb = g % 2 ? 0.5 : 0.0;
    auto p = igm_test::run_overlay(g, o);
    CHECK(check_overlay(p.disk, p.geometry, p.overlay) == "");
  }
  SyntheticDiskOptions o;
  o.subdivisions = 6;
  o.insertions = 3000;
  o.perturb = 0.5;
  auto p = igm_test::run_overlay(3, o);
  MESSAGE("g=3: " << p.disk.triangles.size() << " -> " << p.overlay.mesh.triangles.size() << " triangles, max bits "
                  << p.overlay.stats.max_coordinate_bits);
  CHECK(p.disk.triangles.size() > 40000);
  CHECK(check_overlay(p.disk, p.geometry, p.overlay) == "");
}

TEST_CASE("overlay: the edges of another triangulation of the same polygon (massively degenerate)") {
  // Both disks share corners, side midpoints and (unperturbed) many edges; the segments are the
  // edges of disk B, pairwise meeting only at shared end points by construction.
  for (int g : {2, 3}) {
    const auto corners = igm_test::schema_polygon(g);
    const Point2q c = igm_test::schema_centre(g);
    for (int variant = 0; variant < 4; ++variant) {
      CAPTURE(g);
      CAPTURE(variant);
      SyntheticDiskOptions a, b;
      a.subdivisions = 3;
      a.insertions = 40;
      a.perturb = variant & 1 ? 0.5 : 0.0;
      a.seed = 11 + variant;
      b.subdivisions = 2;
      b.insertions = 25;
      b.perturb = variant & 2 ? 0.5 : 0.0;
      b.seed = 97 + variant;
      const PlanarTriangulation A = make_synthetic_disk(corners, c, a), B = make_synthetic_disk(corners, c, b);
      std::set<std::pair<int, int>> edges;
      for (const auto& T : B.triangles)
        for (int i = 0; i < 3; ++i) edges.emplace(std::min(T[i], T[(i + 1) % 3]), std::max(T[i], T[(i + 1) % 3]));
      std::vector<Segment2> segs;
      for (const auto& [u, v] : edges) segs.push_back({B.positions[u], B.positions[v]});
      const OverlayResult r = overlay_segments(A, segs);
      CHECK(check_overlay(A, segs, r) == "");
      if (variant == 0) CHECK(r.stats.crossings > 0);  // different refinement levels still cross
    }
  }
}

TEST_CASE("overlay: max_triangles caps the output, stopping the walk as soon as its lower bound passes") {
  // A 6 x 6 grid crossed by two disjoint segments that meet no vertex: T output triangles.
  const PlanarTriangulation g = grid(6);
  const std::vector<Segment2> s = {{Point2q{Rational(1, 3), Rational(1, 7)}, Point2q{Rational(17, 3), Rational(40, 7)}},
                                   {Point2q{Rational(1, 5), Rational(3, 2)}, Point2q{Rational(3, 2), Rational(29, 5)}}};
  const OverlayResult full = checked(g, s);
  const std::size_t T = full.mesh.triangles.size();
  const std::size_t points = full.stats.crossings + full.stats.endpoint_vertices;
  REQUIRE(points > 2);
  REQUIRE(T > g.triangles.size() + points);  // the bound is a bound, not the count
  auto capped = [&](std::size_t cap) {
    OverlayOptions o;
    o.max_triangles = cap;
    try {
      const OverlayResult r = overlay_segments(g, s, o);
      if (cap > 0) CHECK(r.mesh.triangles.size() <= cap);
      CHECK(check_overlay(g, s, r) == "");
      return std::string("ok");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Unsupported);
      CHECK(std::string(e.what()).find("max_triangles = " + std::to_string(cap)) != std::string::npos);
      return std::string(e.what());
    }
  };
  CHECK(capped(T) == "ok");
  CHECK(capped(0) == "ok");  // 0: no cap
  // One short: the walk passes (its bound is below the cap), the output does not.
  CHECK(capped(T - 1).find("would have " + std::to_string(T) + " triangles") != std::string::npos);
  // Below input triangles + points: the walk stops at a lower bound ("at least").
  const std::string early = capped(g.triangles.size() + points - 1);
  CHECK(early.find("at least " + std::to_string(g.triangles.size() + points) + " triangles") != std::string::npos);
  CHECK(capped(1).find("at least " + std::to_string(g.triangles.size() + full.stats.endpoint_vertices)) !=
        std::string::npos);  // before any crossing
}
