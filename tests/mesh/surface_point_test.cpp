// evaluate() of a SurfacePoint: the exact point rounded toward zero, checked against GMP directly.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "igm/core/error.h"
#include "igm/mesh/surface_point.h"

using namespace igm;

TEST_CASE("evaluate: each coordinate is the exact convex combination truncated toward zero") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coord(-10, 10);
  std::uniform_int_distribution<long> num(1, 1000);
  std::vector<Vec3d> pos(3);
  int differs_from_naive = 0;
  for (int trial = 0; trial < 2000; ++trial) {  // bound: 2000 random points
    for (Vec3d& p : pos) p = {coord(rng), coord(rng), coord(rng)};
    const long a = num(rng), b = num(rng), c = num(rng);
    const SurfacePoint p = barycentric_point(SurfacePoint::vertex(0), SurfacePoint::vertex(1), SurfacePoint::vertex(2),
                                             {make_rational(a, a + b + c), make_rational(b, a + b + c),
                                              make_rational(c, a + b + c)});
    REQUIRE(p.size() == 3);
    const Vec3d e = evaluate(p, pos);
    const double got[3] = {e.x, e.y, e.z};
    for (int k = 0; k < 3; ++k) {
      const long weight[3] = {a, b, c};
      mpq_class exact = 0;  // independent: GMP's exact conversion of the doubles
      double naive = 0;
      for (int i = 0; i < 3; ++i) {
        const double x = k == 0 ? pos[i].x : (k == 1 ? pos[i].y : pos[i].z);
        mpq_class w(weight[i], a + b + c);
        w.canonicalize();
        exact += mpq_class(x) * w;
        naive += x * (double(weight[i]) / double(a + b + c));
      }
      const double d = got[k];
      const mpq_class lo(d), hi(std::nextafter(d, sgn(exact) >= 0 ? HUGE_VAL : -HUGE_VAL));
      if (sgn(exact) >= 0) CHECK((lo <= exact && exact < hi));
      else CHECK((hi < exact && exact <= lo));
      differs_from_naive += naive != d;
    }
  }
  CHECK(differs_from_naive > 0);  // the naive double sum is not the rounding of the exact point
}

TEST_CASE("evaluate: an input vertex is its input position, combinations drop zero weights") {
  const std::vector<Vec3d> pos = {{-0.0, 1.5, 3}, {2, 2, 2}};
  const Vec3d v = evaluate(SurfacePoint::vertex(0), pos);
  CHECK(std::signbit(v.x));
  CHECK(v.y == 1.5);
  const SurfacePoint end = lerp(SurfacePoint::vertex(0), SurfacePoint::vertex(1), make_rational(1, 1));
  CHECK(end.size() == 1);  // the zero-weight term of vertex 0 is not kept
  CHECK(end.v[0] == 1);
  CHECK(evaluate(end, pos).x == 2);
}

TEST_CASE("combine: the weights of the terms added one by one, ascending ids, zero terms dropped") {
  // Reference: every nonzero term summed per input vertex in a map (ascending ids), independent of
  // the merge that combine() does. Random supports from five ids, so that some pairs span more
  // than three vertices (an Internal error), some share one to three.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> id(0, 4), size(1, 3), num(0, 6), den(1, 8);
  auto random_point = [&] {
    SurfacePoint p;
    std::vector<int> ids;
    const int n = size(rng);
    while (static_cast<int>(ids.size()) < n) {  // <= 5 distinct ids exist, n <= 3
      const int v = id(rng);
      if (std::find(ids.begin(), ids.end(), v) == ids.end()) ids.push_back(v);
    }
    std::sort(ids.begin(), ids.end());
    for (int i = 0; i < n; ++i) p.v[i] = ids[i], p.w[i] = make_rational(1 + num(rng), den(rng));
    if (num(rng) == 0) p.w[n - 1] = 0;  // a zero weight in a used slot is skipped as well
    return p;
  };
  int shared = 0, too_many = 0, halves = 0;
  SurfacePoint reused = SurfacePoint::vertex(4);
  for (int trial = 0; trial < 3000; ++trial) {  // bound: 3000 random pairs
    const SurfacePoint a = random_point(), b = random_point();
    // 1/2 (the midpoint splits' factor, which combine() shifts in) about twice in seven, else
    // num/den from 0 to 6.
    auto factor = [&] { return num(rng) < 2 ? make_rational(1, 2) : make_rational(num(rng), den(rng)); };
    const Rational ta = factor(), tb = factor();
    halves += ta == make_rational(1, 2) && tb == make_rational(1, 2);
    std::map<int, Rational> want;
    for (const auto& [p, t] : {std::pair{&a, &ta}, std::pair{&b, &tb}})
      for (int i = 0; i < 3 && p->v[i] >= 0; ++i)
        if (sgn(*t) != 0 && sgn(p->w[i]) != 0) {
          const Rational term = p->w[i] * *t;
          want[p->v[i]] += term;
        }
    if (want.size() > 3) {
      CHECK_THROWS_AS(combine(a, ta, b, tb), Error);
      ++too_many;
      continue;
    }
    const SurfacePoint r = combine(a, ta, b, tb);
    // combine_into over the previous trial's result (other slots, other weights): the same point.
    combine_into(reused, a, ta, b, tb);
    CHECK(reused.v == r.v);
    for (int i = 0; i < 3; ++i) CHECK(reused.w[i] == r.w[i]);
    REQUIRE(r.size() == static_cast<int>(want.size()));
    int k = 0;
    for (const auto& [v, w] : want) {
      CHECK(r.v[k] == v);
      CHECK(r.w[k] == w);
      CHECK(r.w[k].get_num() == w.get_num());  // canonical: the same numerator and denominator
      CHECK(r.w[k].get_den() == w.get_den());
      ++k;
    }
    for (; k < 3; ++k) {
      CHECK(r.v[k] == -1);
      CHECK(sgn(r.w[k]) == 0);
    }
    shared += a.v[0] == b.v[0];
  }
  CHECK(shared > 100);  // the cases exercised: shared vertices, and supports too large
  CHECK(too_many > 100);
  CHECK(halves > 100);
}
