#include <doctest/doctest.h>

#include <set>

#include "igm/arrange/quad_template.h"
#include "igm/core/error.h"

using namespace igm;

namespace {
Point2q P(long x, long y) { return {Rational(x), Rational(y)}; }
const Point2q kOrigin{Rational(0), Rational(0)};
}  // namespace

TEST_CASE("template: every quad strictly convex, counts and corners, genus 2..300") {
  for (int g = 2; g <= 300; g += (g < 40 ? 1 : 13)) {
    CAPTURE(g);
    const auto corners = rational_circle_polygon(4 * g);
    const QuadTemplate t = make_quad_template(corners, kOrigin);
    REQUIRE(t.genus == g);
    CHECK(t.quads.size() == static_cast<std::size_t>(5 * g));
    CHECK(t.points.size() == static_cast<std::size_t>(7 * g + 1));
    CHECK(t.num_layout_vertices() == 2 + 3 * g);
    std::set<int> layout(t.layout_vertex.begin(), t.layout_vertex.end());
    CHECK(layout.size() == static_cast<std::size_t>(2 + 3 * g));
    for (int k = 0; k < 4 * g; ++k) {
      CHECK(same_point(t.points[k], corners[k]));  // template corners are the polygon corners
      CHECK(t.layout_vertex[k] == 0);
    }
    for (const auto& Q : t.quads)  // independent exact convexity check
      for (int i = 0; i < 4; ++i)
        CHECK(orient2d(t.points[Q[i]], t.points[Q[(i + 1) % 4]], t.points[Q[(i + 2) % 4]]) == Sign::Positive);
    // every side is the edge of its quad, in the same direction
    for (int s = 0; s < 4 * g; ++s) {
      const auto [q, e] = t.side_quad[s];
      CHECK(t.quads[q][e] == s);
      CHECK(t.quads[q][(e + 1) % 4] == (s + 1) % (4 * g));
    }
    // Template regions tile the polygon: areas add up exactly.
    Rational area = 0, poly = 0;
    for (const auto& r : template_regions(t)) {
      REQUIRE(r.corners.size() == 3);
      area += cross(t.points[r.corners[0]], t.points[r.corners[1]], t.points[r.corners[2]]);
    }
    for (int k = 0; k < 4 * g; ++k) poly += cross(kOrigin, corners[k], corners[(k + 1) % (4 * g)]);
    CHECK(area == poly);
    // Segments: 4g sides on the boundary, the rest interior, one diagonal per quad.
    const auto segs = template_segments(t);
    int boundary = 0, diagonals = 0;
    for (const auto& s : segs) {
      boundary += s.right < 0;
      diagonals += s.diagonal;
    }
    CHECK(boundary == 4 * g);
    CHECK(diagonals == 5 * g);
    CHECK(segs.size() == static_cast<std::size_t>(4 * g + 8 * g + 5 * g));
  }
}

TEST_CASE("template: every genus 2..300 gives strictly convex quads (independent exact check)") {
  for (int g = 2; g <= 300; ++g) {
    CAPTURE(g);
    const QuadTemplate t = make_quad_template(rational_circle_polygon(4 * g), kOrigin);
    int convex = 0;
    for (const auto& Q : t.quads) {
      bool ok = true;
      for (int i = 0; i < 4; ++i)
        ok = ok && orient2d(t.points[Q[i]], t.points[Q[(i + 1) % 4]], t.points[Q[(i + 2) % 4]]) == Sign::Positive;
      convex += ok;
    }
    CHECK(convex == 5 * g);
  }
}

TEST_CASE("template: odd and even genus on a rotated polygon (corners still coincide)") {
  for (int g : {3, 4, 7, 8}) {
    auto corners = rational_circle_polygon(4 * g);
    std::rotate(corners.begin(), corners.begin() + 1, corners.end());  // a different first corner
    const QuadTemplate t = make_quad_template(corners, kOrigin);
    for (int k = 0; k < 4 * g; ++k) CHECK(same_point(t.points[k], corners[k]));
  }
}

TEST_CASE("template: genus 1 is the square itself with no diagonal") {
  const QuadTemplate t = make_quad_template({P(0, 0), P(1, 0), P(1, 1), P(0, 1)}, {Rational(1, 2), Rational(1, 2)});
  CHECK(t.quads.size() == 1);
  CHECK(t.diagonal[0] == -1);
  CHECK(t.num_layout_vertices() == 1);
  CHECK(template_segments(t).size() == 4);
  const QuadTemplate k = make_quad_template({P(0, 0), P(3, 0), P(2, 2), P(0, 1)}, {Rational(1), Rational(1)});
  CHECK(k.diagonal[0] >= 0);
  CHECK(template_segments(k).size() == 5);
}

TEST_CASE("template: bad polygons are rejected with typed errors") {
  CHECK_THROWS_AS(make_quad_template({P(0, 0), P(1, 0), P(1, 1)}, P(0, 0)), Error);
  // clockwise
  try {
    make_quad_template({P(0, 0), P(0, 1), P(1, 1), P(1, 0)}, {Rational(1, 2), Rational(1, 2)});
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::InvalidArgument);
  }
  // centre outside
  CHECK_THROWS_AS(make_quad_template({P(0, 0), P(1, 0), P(1, 1), P(0, 1)}, P(2, 2)), Error);
  // a reflex corner
  CHECK_THROWS_AS(make_quad_template({P(0, 0), P(2, 0), P(1, 1), P(2, 2), P(0, 2), P(-1, 2), P(-2, 1), P(-1, 0)}, P(0, 1)),
                  Error);
}

TEST_CASE("template: an eccentric centre that breaks convexity is an Internal error, never a bad template") {
  // Centres on a grid inside the octagon; the test recomputes the inner points itself and
  // expects an Internal error exactly when one of its quads is not strictly convex.
  const auto c = rational_circle_polygon(8);
  int broken = 0, fine = 0;
  for (int i = -9; i <= 9; ++i)
    for (int j = -9; j <= 9; ++j) {
      const Point2q C{make_rational(i, 10), make_rational(j, 10)};
      bool inside = true;
      for (int k = 0; k < 8; ++k) inside = inside && orient2d(c[k], c[(k + 1) % 8], C) == Sign::Positive;
      if (!inside) continue;
      bool convex = true;
      for (int g = 0; g < 2; ++g) {
        const Point2q &P0 = c[4 * g], &P1 = c[4 * g + 1], &P2 = c[4 * g + 2], &P3 = c[4 * g + 3], &P4 = c[(4 * g + 4) % 8];
        const Point2q A0{Rational((P1.x + P2.x + C.x) / 3), Rational((P1.y + P2.y + C.y) / 3)};
        const Point2q A1{Rational((5 * P2.x + C.x) / 6), Rational((5 * P2.y + C.y) / 6)};
        const Point2q A2{Rational((P2.x + P3.x + C.x) / 3), Rational((P2.y + P3.y + C.y) / 3)};
        const std::vector<std::array<Point2q, 4>> quads = {
            {P0, P1, A0, C}, {P1, P2, A1, A0}, {P2, P3, A2, A1}, {P3, P4, C, A2}, {A0, A1, A2, C}};
        for (const auto& Q : quads)
          for (int k = 0; k < 4; ++k) convex = convex && orient2d(Q[k], Q[(k + 1) % 4], Q[(k + 2) % 4]) == Sign::Positive;
      }
      if (convex) {
        ++fine;
        CHECK_NOTHROW(make_quad_template(c, C));
      } else {
        ++broken;
        try {
          make_quad_template(c, C);
          FAIL("a non-convex template was returned");
        } catch (const Error& e) {
          CHECK(e.kind() == ErrorKind::Internal);
        }
      }
    }
  CHECK(broken > 0);
  CHECK(fine > 0);
}
