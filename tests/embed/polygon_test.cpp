#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "igm/core/error.h"
#include "igm/embed/polygon.h"

using namespace igm;

namespace {
Rational q(long a, long b = 1) { return make_rational(Integer(a), Integer(b)); }
bool same(const Point2q& a, const Point2q& b) { return a.x == b.x && a.y == b.y; }
}  // namespace

TEST_CASE("genus 1: exactly the unit square, ccw, corner 0 at the origin") {
  const auto c = canonical_polygon(1);
  REQUIRE(c.size() == 4);
  CHECK(same(c[0], {q(0), q(0)}));
  CHECK(same(c[1], {q(1), q(0)}));
  CHECK(same(c[2], {q(1), q(1)}));
  CHECK(same(c[3], {q(0), q(1)}));
  CHECK(is_strictly_convex_ccw(c));
  CHECK(same(polygon_centre(c), {q(1, 2), q(1, 2)}));
}

TEST_CASE("genus 2..300: strictly convex rational 4g-gons on the unit circle") {
  for (int g = 2; g <= 300; g += (g < 20 ? 1 : 7)) {
    CAPTURE(g);
    const auto c = canonical_polygon(g);
    REQUIRE(c.size() == static_cast<std::size_t>(4 * g));
    CHECK(same(c[0], {q(1), q(0)}));
    bool all_on_circle = true, all_positive = true;
    for (std::size_t i = 0; i < c.size(); ++i) {
      // Rational by type; exactly on the unit circle; every consecutive triple turns left.
      if (c[i].x * c[i].x + c[i].y * c[i].y != 1) all_on_circle = false;
      if (orient2d(c[i], c[(i + 1) % c.size()], c[(i + 2) % c.size()]) != Sign::Positive) all_positive = false;
    }
    CHECK(all_on_circle);
    CHECK(all_positive);
    CHECK(is_strictly_convex_ccw(c));
    // Counter-clockwise: positive signed area (shoelace, exact).
    Rational area2 = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const auto& a = c[i];
      const auto& b = c[(i + 1) % c.size()];
      area2 += a.x * b.y - a.y * b.x;
    }
    CHECK(sgn(area2) > 0);
    // Close to regular: corner k near angle 2 pi k / 4g (doubles only compare, never decide
    // geometry of the output).
    for (int k = 0; k < 4 * g; k += std::max(1, g / 3)) {
      const double th = 2 * 3.14159265358979323846 * k / (4.0 * g);
      CHECK(std::abs(to_double(c[k].x) - std::cos(th)) < 0.2 / g);
      CHECK(std::abs(to_double(c[k].y) - std::sin(th)) < 0.2 / g);
    }
    const Point2q o = polygon_centre(c);
    CHECK(o.x == 0);
    CHECK(o.y == 0);
  }
}

TEST_CASE("odd and even genus up to 1000 stay strictly convex") {
  for (int g : {299, 300, 511, 512, 999, 1000}) {
    CAPTURE(g);
    const auto c = canonical_polygon(g);
    CHECK(c.size() == static_cast<std::size_t>(4 * g));
    CHECK(is_strictly_convex_ccw(c));
  }
}

TEST_CASE("invalid genus is a typed error") {
  for (int g : {0, -1, 100001}) {
    try {
      canonical_polygon(g);
      FAIL("no error");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::InvalidArgument);
    }
  }
}

TEST_CASE("is_strictly_convex_ccw rejects clockwise, collinear, non-simple and twice-winding polygons") {
  const std::vector<Point2q> sq = canonical_polygon(1);
  CHECK(is_strictly_convex_ccw(sq));
  CHECK_FALSE(is_strictly_convex_ccw({sq[3], sq[2], sq[1], sq[0]}));                      // clockwise
  CHECK_FALSE(is_strictly_convex_ccw({sq[0], {q(1, 2), q(0)}, sq[1], sq[2], sq[3]}));      // collinear
  CHECK_FALSE(is_strictly_convex_ccw({sq[0], sq[1]}));
  // A pentagram: all left turns but winds twice.
  std::vector<Point2q> penta = canonical_polygon(2);  // 8 corners; take every third: winds 3 times
  std::vector<Point2q> star;
  for (int k = 0; k < 8; ++k) star.push_back(penta[(3 * k) % 8]);
  CHECK_FALSE(is_strictly_convex_ccw(star));
}

namespace {
// The exact parameter of p along the segment a -> b (p is known to lie on it).
Rational param(const Point2q& a, const Point2q& b, const Point2q& p) {
  if (a.x != b.x) return (p.x - a.x) / (b.x - a.x);
  return (p.y - a.y) / (b.y - a.y);
}
}  // namespace

TEST_CASE("place_boundary: exact parameters i/n, collinear, equal on paired sides a b a^-1 b^-1") {
  for (int g : {1, 2, 3, 7}) {
    CAPTURE(g);
    const auto c = canonical_polygon(g);
    const int S = 4 * g;
    std::vector<int> counts(S);
    for (int grp = 0; grp < g; ++grp) {
      const int na = 1 + (5 * grp + 2) % 7, nb = 1 + (3 * grp + 4) % 5;
      counts[4 * grp + 0] = counts[4 * grp + 2] = na;
      counts[4 * grp + 1] = counts[4 * grp + 3] = nb;
    }
    const auto pts = place_boundary(c, counts);
    std::vector<int> start(S + 1, 0);
    for (int s = 0; s < S; ++s) start[s + 1] = start[s] + counts[s];
    REQUIRE(pts.size() == static_cast<std::size_t>(start[S]));
    for (int s = 0; s < S; ++s) {
      const Point2q& a = c[s];
      const Point2q& b = c[(s + 1) % S];
      CHECK(same(pts[start[s]], a));
      for (int i = 0; i < counts[s]; ++i) {
        const Point2q& p = pts[start[s] + i];
        CHECK(orient2d(a, b, p) == Sign::Zero);
        CHECK(param(a, b, p) == q(i, counts[s]));
      }
    }
    // Paired sides: s and s+2 in each group of four, the second traversed backwards. The copy at
    // parameter i/n on side s (from corner s) and the copy at (n-i)/n on side s+2, i.e. at
    // parameter i/n measured backwards from corner s+3, must agree.
    for (int grp = 0; grp < g; ++grp)
      for (int off : {0, 1}) {
        const int s = 4 * grp + off, t = s + 2;
        const int n = counts[s];
        REQUIRE(counts[t] == n);
        for (int i = 1; i < n; ++i) {
          const Point2q& p = pts[start[s] + i];
          const Point2q& r = pts[start[t] + (n - i)];
          const Rational ps = param(c[s], c[(s + 1) % S], p);
          const Rational pt = param(c[(t + 1) % S], c[t], r);  // measured from corner t+1 back
          CHECK(ps == pt);
        }
      }
    // The boundary polygon as a whole is convex ccw (corners strictly, side points collinear).
    std::vector<Point2q> corners;
    for (int s = 0; s < S; ++s) corners.push_back(pts[start[s]]);
    CHECK(is_strictly_convex_ccw(corners));
  }
}

TEST_CASE("place_boundary: unit square with 1/3 steps, exact") {
  const auto pts = place_boundary(canonical_polygon(1), {3, 3, 3, 3});
  REQUIRE(pts.size() == 12);
  CHECK(same(pts[1], {q(1, 3), q(0)}));
  CHECK(same(pts[2], {q(2, 3), q(0)}));
  CHECK(same(pts[4], {q(1), q(1, 3)}));
  CHECK(same(pts[7], {q(2, 3), q(1)}));
  CHECK(same(pts[8], {q(1, 3), q(1)}));
  CHECK(same(pts[11], {q(0), q(1, 3)}));
  // Torus seams: side 0 vs side 2 differ by the translation (0, 1), side 1 vs side 3 by (1, 0).
  for (int i = 1; i < 3; ++i) {
    CHECK(pts[0 + i].x == pts[6 + 3 - i].x);
    CHECK(pts[0 + i].y + 1 == pts[6 + 3 - i].y);
    CHECK(pts[3 + i].y == pts[9 + 3 - i].y);
    CHECK(pts[3 + i].x - 1 == pts[9 + 3 - i].x);
  }
}

TEST_CASE("place_boundary: bad arguments are typed errors") {
  const auto c = canonical_polygon(1);
  CHECK_THROWS_AS(place_boundary(c, {1, 2, 3}), Error);
  try {
    place_boundary(c, {1, 0, 1, 1});
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::InvalidArgument);
    CHECK(e.elements() == std::vector<std::int64_t>{1});
  }
}

TEST_CASE("arc_length_parameters: fractions of the length, rounded, distinct, uniform when lengths are unusable") {
  const auto t = igm::arc_length_parameters({1, 1, 2}, 8);
  REQUIRE(t.size() == 4);
  CHECK(t[0] == 0);
  CHECK(t[1] == q(1, 4));
  CHECK(t[2] == q(1, 2));
  CHECK(t[3] == 1);
  // Zero-length edges still get distinct parameters, one grid step apart.
  const auto z = igm::arc_length_parameters({0, 0, 1}, 4);
  CHECK(z[1] == q(1, 16));
  CHECK(z[2] == q(2, 16));
  const auto e = igm::arc_length_parameters({1, 0, 0}, 4);
  CHECK(e[1] == q(14, 16));
  CHECK(e[2] == q(15, 16));
  // All zero, negative or infinite: i / n, rounded.
  const auto u = igm::arc_length_parameters({0, 0, 0, 0}, 10);
  CHECK(u[1] == q(1, 4));
  const auto inf = igm::arc_length_parameters({1, std::numeric_limits<double>::infinity()}, 10);
  CHECK(inf[1] == q(1, 2));
  CHECK_THROWS_AS(igm::arc_length_parameters({}, 10), igm::Error);
  CHECK_THROWS_AS(igm::arc_length_parameters({1, 1, 1}, 1), igm::Error);  // 3 edges need 2 bits
}

TEST_CASE("place_boundary_at: points at the given parameters, bad parameter lists are typed errors") {
  const auto sq = igm::canonical_polygon(1);
  const std::vector<std::vector<Rational>> params = {{0, q(1, 4)}, {0}, {0, q(3, 4)}, {0}};
  const auto p = igm::place_boundary_at(sq, params);
  REQUIRE(p.size() == 6);
  CHECK((p[1].x == q(1, 4) && p[1].y == 0));
  CHECK((p[4].x == q(1, 4) && p[4].y == 1));  // 3/4 along the top side, which runs right to left
  CHECK_THROWS_AS(igm::place_boundary_at(sq, {{q(1, 2)}, {0}, {0}, {0}}), igm::Error);
  CHECK_THROWS_AS(igm::place_boundary_at(sq, {{0, q(1, 2), q(1, 2)}, {0}, {0}, {0}}), igm::Error);
  CHECK_THROWS_AS(igm::place_boundary_at(sq, {{0, 1}, {0}, {0}, {0}}), igm::Error);
}

TEST_CASE("schema_polygon: every n from 3 to 600 (and 1022, 4098) strictly convex, even n symmetric with small corners") {
  std::vector<int> ns;
  for (int n = 3; n <= 600; ++n) ns.push_back(n);
  for (int n : {1022, 4098}) ns.push_back(n);
  for (int n : ns) {
    CAPTURE(n);
    const std::vector<Point2q> c = schema_polygon(n);
    REQUIRE(static_cast<int>(c.size()) == n);
    CHECK(is_strictly_convex_ccw(c));
    if (n % 2 == 0 && n > 4) {
      // the half-turn construction: corner k + n/2 is minus corner k, on the unit circle, and its
      // denominators are N^2 + p^2 with N <= 32 n, p <= N: at most 2 log2(32 n) + 2 bits
      std::size_t max_bits = 0;
      int off = 0;
      for (int k = 0; k < n / 2; ++k) {
        off += c[k + n / 2].x != -c[k].x || c[k + n / 2].y != -c[k].y || c[k].x * c[k].x + c[k].y * c[k].y != 1;
        max_bits = std::max({max_bits, mpz_sizeinbase(c[k].x.get_den_mpz_t(), 2), mpz_sizeinbase(c[k].y.get_den_mpz_t(), 2)});
      }
      CHECK(off == 0);
      CHECK(max_bits <= static_cast<std::size_t>(2 * std::ceil(std::log2(32.0 * n)) + 2));
      CHECK(same(polygon_centre(c), Point2q{Rational(0), Rational(0)}));
    }
  }
  CHECK_THROWS_AS(schema_polygon(2), Error);
  CHECK_THROWS_AS(schema_polygon(400001), Error);
}
