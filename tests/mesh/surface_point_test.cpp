// evaluate() of a SurfacePoint: the exact point rounded toward zero, checked against GMP directly.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

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
