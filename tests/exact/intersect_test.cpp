#include <doctest/doctest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <vector>

#include "igm/core/error.h"
#include "igm/exact/intersect.h"

using namespace igm;

namespace {

Point2q P(long x, long y) { return {Rational(x), Rational(y)}; }
Point2q Pq(long xn, long xd, long yn, long yd) { return {make_rational(xn, xd), make_rational(yn, yd)}; }
bool same(const Point2q& p, const Point2q& q) { return p.x == q.x && p.y == q.y; }

// Independent reference by linear algebra: solve a + s (b - a) = c + t (d - c) with Cramer's rule;
// parallel/collinear cases by projecting onto the direction with dot products. Returns the relation
// and, when the intersection is a single point, that point.
struct RefResult {
  SegmentRelation rel;
  std::optional<Point2q> point;
};

mpq_class dot(const mpq_class& ux, const mpq_class& uy, const mpq_class& vx, const mpq_class& vy) { return ux * vx + uy * vy; }
mpq_class cross(const mpq_class& ux, const mpq_class& uy, const mpq_class& vx, const mpq_class& vy) { return ux * vy - uy * vx; }

// p on closed segment ab, by parameters: (p - a) x (b - a) == 0 and 0 <= (p-a).(b-a) <= |b-a|^2.
bool ref_on_segment(const Point2q& p, const Point2q& a, const Point2q& b) {
  const mpq_class ux = b.x - a.x, uy = b.y - a.y, wx = p.x - a.x, wy = p.y - a.y;
  if (ux == 0 && uy == 0) return wx == 0 && wy == 0;
  if (cross(wx, wy, ux, uy) != 0) return false;
  const mpq_class s = dot(wx, wy, ux, uy);
  return s >= 0 && s <= dot(ux, uy, ux, uy);
}

RefResult reference(const Point2q& a, const Point2q& b, const Point2q& c, const Point2q& d) {
  const bool ab0 = same(a, b), cd0 = same(c, d);
  if (ab0 && cd0) return same(a, c) ? RefResult{SegmentRelation::Touching, a} : RefResult{SegmentRelation::Disjoint, {}};
  if (ab0) return ref_on_segment(a, c, d) ? RefResult{SegmentRelation::Touching, a} : RefResult{SegmentRelation::Disjoint, {}};
  if (cd0) return ref_on_segment(c, a, b) ? RefResult{SegmentRelation::Touching, c} : RefResult{SegmentRelation::Disjoint, {}};
  const mpq_class ux = b.x - a.x, uy = b.y - a.y, vx = d.x - c.x, vy = d.y - c.y, wx = c.x - a.x, wy = c.y - a.y;
  const mpq_class den = cross(ux, uy, vx, vy);
  if (den != 0) {
    const mpq_class s = cross(wx, wy, vx, vy) / den;  // a + s u == c + t v
    const mpq_class t = cross(wx, wy, ux, uy) / den;
    if (s < 0 || s > 1 || t < 0 || t > 1) return {SegmentRelation::Disjoint, {}};
    Point2q p{mpq_class(a.x + s * ux), mpq_class(a.y + s * uy)};
    const bool interior = s > 0 && s < 1 && t > 0 && t < 1;
    return {interior ? SegmentRelation::ProperCrossing : SegmentRelation::Touching, p};
  }
  if (cross(wx, wy, ux, uy) != 0) return {SegmentRelation::Disjoint, {}};  // parallel lines
  // collinear: parameters of c and d along a + s u, overlap with [0, 1]
  const mpq_class uu = dot(ux, uy, ux, uy);
  const mpq_class sc = dot(wx, wy, ux, uy) / uu;
  const mpq_class sd = dot(mpq_class(d.x - a.x), mpq_class(d.y - a.y), ux, uy) / uu;
  const mpq_class lo = std::max(mpq_class(0), std::min(sc, sd)), hi = std::min(mpq_class(1), std::max(sc, sd));
  if (lo > hi) return {SegmentRelation::Disjoint, {}};
  if (lo == hi) return {SegmentRelation::Touching, Point2q{mpq_class(a.x + lo * ux), mpq_class(a.y + lo * uy)}};
  return {SegmentRelation::CollinearOverlap, {}};
}

// classify is invariant under swapping the segments and reversing either one.
void check_all(const Point2q& a, const Point2q& b, const Point2q& c, const Point2q& d) {
  const RefResult r = reference(a, b, c, d);
  const SegmentRelation s = classify(a, b, c, d);
  REQUIRE(s == r.rel);
  REQUIRE(classify(b, a, c, d) == s);
  REQUIRE(classify(a, b, d, c) == s);
  REQUIRE(classify(c, d, a, b) == s);
  REQUIRE(classify(d, c, b, a) == s);
  const auto p = intersection(a, b, c, d);
  REQUIRE(p.has_value() == r.point.has_value());
  if (p) {
    REQUIRE(same(*p, *r.point));
    REQUIRE(on_segment(*p, a, b));
    REQUIRE(on_segment(*p, c, d));
  }
  if (s == SegmentRelation::ProperCrossing) {
    const Point2q q = intersection_point(a, b, c, d);
    REQUIRE(same(q, *r.point));
    REQUIRE(orient2d(a, b, q) == Sign::Zero);
    REQUIRE(orient2d(c, d, q) == Sign::Zero);
    for (const Point2q* e : {&a, &b, &c, &d}) REQUIRE_FALSE(same(q, *e));
  }
}

}  // namespace

TEST_CASE("classify: hand-made cases") {
  // proper crossing of the diagonals of the unit square, at (1/2, 1/2)
  CHECK(classify(P(0, 0), P(1, 1), P(0, 1), P(1, 0)) == SegmentRelation::ProperCrossing);
  const Point2q x = intersection_point(P(0, 0), P(1, 1), P(0, 1), P(1, 0));
  CHECK(x.x == make_rational(1, 2));
  CHECK(x.y == make_rational(1, 2));
  // non-dyadic crossing: (0,0)-(3,1) with (0,1)-(1,0): t solves 3t = 1 - t -> (3/4, 1/4)
  const Point2q y = intersection_point(P(0, 0), P(3, 1), P(0, 1), P(1, 0));
  CHECK(y.x == make_rational(3, 4));
  CHECK(y.y == make_rational(1, 4));
  // endpoint on the other's interior (T)
  CHECK(classify(P(0, 0), P(2, 0), P(1, 0), P(1, 5)) == SegmentRelation::Touching);
  CHECK(classify(P(0, 0), P(2, 0), P(1, -3), P(1, 0)) == SegmentRelation::Touching);
  // shared endpoint
  CHECK(classify(P(0, 0), P(1, 0), P(1, 0), P(2, 3)) == SegmentRelation::Touching);
  CHECK(classify(P(0, 0), P(1, 0), P(0, 0), P(-2, 3)) == SegmentRelation::Touching);
  // almost touching: endpoint just off the segment
  CHECK(classify(P(0, 0), P(2, 0), Pq(1, 1, 1, 1000000), P(1, 5)) == SegmentRelation::Disjoint);
  CHECK(classify(P(0, 0), P(2, 0), Pq(1, 1, -1, 1000000), P(1, 5)) == SegmentRelation::ProperCrossing);
  // collinear overlapping, contained, identical, reversed
  CHECK(classify(P(0, 0), P(2, 2), P(1, 1), P(3, 3)) == SegmentRelation::CollinearOverlap);
  CHECK(classify(P(0, 0), P(3, 3), P(1, 1), P(2, 2)) == SegmentRelation::CollinearOverlap);
  CHECK(classify(P(0, 0), P(3, 3), P(0, 0), P(3, 3)) == SegmentRelation::CollinearOverlap);
  CHECK(classify(P(0, 0), P(3, 3), P(3, 3), P(0, 0)) == SegmentRelation::CollinearOverlap);
  // vertical collinear (lexicographic order falls back to y)
  CHECK(classify(P(5, 0), P(5, 2), P(5, 1), P(5, 7)) == SegmentRelation::CollinearOverlap);
  CHECK(classify(P(5, 0), P(5, 2), P(5, 2), P(5, 7)) == SegmentRelation::Touching);
  CHECK(classify(P(5, 0), P(5, 2), P(5, 3), P(5, 7)) == SegmentRelation::Disjoint);
  // collinear end to end and collinear disjoint
  CHECK(classify(P(0, 0), P(1, 1), P(1, 1), P(2, 2)) == SegmentRelation::Touching);
  CHECK(classify(P(0, 0), P(1, 1), P(2, 2), P(3, 3)) == SegmentRelation::Disjoint);
  // parallel distinct lines
  CHECK(classify(P(0, 0), P(1, 1), P(0, 1), P(1, 2)) == SegmentRelation::Disjoint);
  // lines cross outside both segments
  CHECK(classify(P(0, 0), P(1, 0), P(2, -1), P(2, 1)) == SegmentRelation::Disjoint);
  // degenerate segments
  CHECK(classify(P(1, 1), P(1, 1), P(0, 0), P(2, 2)) == SegmentRelation::Touching);
  CHECK(classify(P(1, 1), P(1, 1), P(0, 0), P(2, 3)) == SegmentRelation::Disjoint);
  CHECK(classify(P(1, 1), P(1, 1), P(1, 1), P(1, 1)) == SegmentRelation::Touching);
  CHECK(classify(P(1, 1), P(1, 1), P(1, 2), P(1, 2)) == SegmentRelation::Disjoint);
  CHECK(classify(P(0, 0), P(2, 2), P(2, 2), P(2, 2)) == SegmentRelation::Touching);
  CHECK(classify(P(0, 0), P(2, 2), P(3, 3), P(3, 3)) == SegmentRelation::Disjoint);
  CHECK(std::string(to_string(SegmentRelation::ProperCrossing)) == "proper_crossing");
}

TEST_CASE("intersection_point rejects parallel lines, intersection of touching cases") {
  CHECK_THROWS_AS(intersection_point(P(0, 0), P(1, 1), P(0, 1), P(1, 2)), Error);
  CHECK_THROWS_AS(intersection_point(P(0, 0), P(1, 1), P(2, 2), P(3, 3)), Error);
  CHECK_THROWS_AS(intersection_point(P(0, 0), P(0, 0), P(2, 2), P(3, 3)), Error);
  try {
    (void)intersection_point(P(0, 0), P(1, 1), P(0, 1), P(1, 2));
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::InvalidArgument);
  }
  // lines that meet outside the segments still have an exact intersection point
  const Point2q q = intersection_point(P(0, 0), P(1, 0), P(2, -1), P(2, 1));
  CHECK(same(q, P(2, 0)));
  auto t = intersection(P(0, 0), P(2, 0), P(1, 0), P(1, 5));
  REQUIRE(t);
  CHECK(same(*t, P(1, 0)));
  t = intersection(P(0, 0), P(1, 1), P(1, 1), P(2, 2));
  REQUIRE(t);
  CHECK(same(*t, P(1, 1)));
  CHECK_FALSE(intersection(P(0, 0), P(2, 2), P(1, 1), P(3, 3)).has_value());
  CHECK_FALSE(intersection(P(0, 0), P(1, 0), P(2, -1), P(2, 1)).has_value());
}

TEST_CASE("on_segment and compare_lex") {
  CHECK(on_segment(P(1, 1), P(0, 0), P(2, 2)));
  CHECK(on_segment(P(0, 0), P(0, 0), P(2, 2)));
  CHECK(on_segment(P(2, 2), P(0, 0), P(2, 2)));
  CHECK_FALSE(on_segment(P(3, 3), P(0, 0), P(2, 2)));
  CHECK_FALSE(on_segment(P(-1, -1), P(0, 0), P(2, 2)));
  CHECK_FALSE(on_segment(P(1, 2), P(0, 0), P(2, 2)));
  CHECK(on_segment(P(0, 0), P(0, 0), P(0, 0)));
  CHECK_FALSE(on_segment(P(0, 1), P(0, 0), P(0, 0)));
  CHECK(compare_lex(P(0, 5), P(1, 0)) == Sign::Negative);
  CHECK(compare_lex(P(1, 5), P(1, 0)) == Sign::Positive);
  CHECK(compare_lex(Pq(1, 2, 1, 3), Pq(2, 4, 2, 6)) == Sign::Zero);
}

TEST_CASE("classify agrees with the linear-algebra reference on every segment pair of a 4x4 grid") {
  // 16 points, 16^4 = 65536 ordered pairs of segments: all degenerate configurations occur
  // (shared endpoints, collinear overlaps, point segments, T-junctions).
  std::vector<Point2q> pts;
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y) pts.push_back(P(x, y));
  int counts[4] = {0, 0, 0, 0};
  for (const auto& a : pts)
    for (const auto& b : pts)
      for (const auto& c : pts)
        for (const auto& d : pts) {
          const SegmentRelation s = classify(a, b, c, d);
          REQUIRE(s == reference(a, b, c, d).rel);
          ++counts[static_cast<int>(s)];
        }
  MESSAGE("grid: disjoint " << counts[0] << ", crossing " << counts[1] << ", touching " << counts[2]
                            << ", overlap " << counts[3]);
  for (int c : counts) CHECK(c > 1000);
}

TEST_CASE("classify, intersection and invariances on random and adversarial rational segments") {
  gmp_randclass g(gmp_randinit_default);
  g.seed(11);
  std::mt19937_64 rng(11);
  auto rq = [&](unsigned long bits) {
    mpz_class n = g.get_z_bits(1 + rng() % bits);
    if (rng() % 2) n = -n;
    mpz_class d = g.get_z_bits(1 + rng() % bits);
    if (d == 0) d = 1;
    return make_rational(n, d);
  };
  auto rp = [&](unsigned long bits) { return Point2q{rq(bits), rq(bits)}; };
  auto lerp = [](const Point2q& a, const Point2q& b, const Rational& t) {
    return Point2q{Rational(a.x + t * (b.x - a.x)), Rational(a.y + t * (b.y - a.y))};
  };
  int counts[4] = {0, 0, 0, 0};
  for (int i = 0; i < 4000; ++i) {
    const Point2q a = rp(80), b = rp(80);
    Point2q c, d;
    switch (i % 5) {
      case 0:  // random
        c = rp(80);
        d = rp(80);
        break;
      case 1:  // c on the interior of ab (T-junction), d random
        c = lerp(a, b, make_rational(1 + rng() % 999, 1000));
        d = rp(80);
        break;
      case 2:  // collinear: both on the line ab, parameters in [-1, 2]
        c = lerp(a, b, make_rational(static_cast<long>(rng() % 31) - 10, 10));
        d = lerp(a, b, make_rational(static_cast<long>(rng() % 31) - 10, 10));
        break;
      case 3:  // crossing through a point of ab, with the far endpoint mirrored
      {
        const Point2q m = lerp(a, b, make_rational(1 + rng() % 99, 100));
        c = rp(80);
        d = lerp(c, m, Rational(2));  // m is the midpoint of cd
        break;
      }
      default:  // shared endpoint
        c = b;
        d = rp(80);
    }
    check_all(a, b, c, d);
    ++counts[static_cast<int>(classify(a, b, c, d))];
  }
  MESSAGE("random: disjoint " << counts[0] << ", crossing " << counts[1] << ", touching " << counts[2]
                              << ", overlap " << counts[3]);
  for (int c : counts) CHECK(c > 100);
}
