#include <doctest/doctest.h>

#include <random>

#include "igm/arrange/planar_walk.h"
#include "igm/core/error.h"

using namespace igm;

TEST_CASE("orient2q agrees with the exact orient2d, including collinear, huge and tiny inputs") {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<long> num(-1000000, 1000000), den(1, 1000000);
  std::uniform_int_distribution<int> ex(-1200, 1200);
  auto rnd = [&](bool scaled) {
    Rational q = make_rational(num(rng), den(rng));
    if (scaled) {
      const int e = ex(rng);
      if (e >= 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), e);
      else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), -e);
    }
    return q;
  };
  int zeros = 0;
  for (int k = 0; k < 20000; ++k) {
    const bool scaled = k % 3 == 0;
    Point2q a{rnd(scaled), rnd(scaled)}, b{rnd(scaled), rnd(scaled)}, c{rnd(scaled), rnd(scaled)};
    if (k % 4 == 1) {  // c on the line ab: exactly collinear
      const Rational t = rnd(false);
      c = {Rational(a.x + t * (b.x - a.x)), Rational(a.y + t * (b.y - a.y))};
    }
    if (k % 17 == 0) c = a;
    const Sign e = orient2d(a, b, c);
    zeros += e == Sign::Zero;
    REQUIRE(orient2d(a, b, c) == e);
    REQUIRE(orient2d(b, c, a) == e);
    REQUIRE(orient2d(b, a, c) == -e);
  }
  CHECK(zeros > 4000);
}

TEST_CASE("locate_point finds vertices, edges and faces exactly") {
  PlanarTriangulation m;
  m.positions = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  const PlanarAdjacency adj = PlanarAdjacency::build(4, m.triangles);
  for (int from = 0; from < 4; ++from) {
    auto l = locate_point(m.positions, m.triangles, adj, from, {1, 1});
    CHECK(l.kind == PlanarLocation::Kind::Edge);
    l = locate_point(m.positions, m.triangles, adj, from, {2, 2});
    CHECK(l.kind == PlanarLocation::Kind::Vertex);
    CHECK(m.triangles[l.triangle][l.index] == 2);
    l = locate_point(m.positions, m.triangles, adj, from, {Rational(1, 3), Rational(1, 2)});
    CHECK(l.kind == PlanarLocation::Kind::Face);
    CHECK(l.triangle == 1);
    l = locate_point(m.positions, m.triangles, adj, from, {2, 1});
    CHECK(l.kind == PlanarLocation::Kind::Edge);
    CHECK_THROWS_AS(locate_point(m.positions, m.triangles, adj, from, {3, 1}), Error);
  }
}
