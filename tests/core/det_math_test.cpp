#include "igm/core/det_math.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>

using igm::det_atan2;
using igm::det_sincos;

namespace {

// Distance in units in the last place between a double and a long double reference (x86-64:
// 64-bit significand, libm's long double functions accurate to far below a double ulp).
double ulps(double got, long double want) {
  const double w = static_cast<double>(want);
  const double ulp = std::nextafter(std::fabs(w), INFINITY) - std::fabs(w);
  return static_cast<double>(std::fabs(static_cast<long double>(got) - want) / ulp);
}

}  // namespace

TEST_CASE("det_atan2 is within 2 ulp of atan2 in every octant, for tiny and huge arguments") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> e(-40, 40);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double y = std::ldexp(u(rng), e(rng)), x = std::ldexp(u(rng), e(rng));
    const double err = ulps(det_atan2(y, x), atan2l(static_cast<long double>(y), static_cast<long double>(x)));
    worst = std::max(worst, err);
  }
  // Near the eighths' boundaries and the octants' diagonals.
  for (int k = 0; k <= 16; ++k)
    for (double d : {-1e-12, -1e-16, 0.0, 1e-16, 1e-12}) {
      const double r = k / 16.0 + d;
      for (const auto& [y, x] : {std::pair{r, 1.0}, std::pair{1.0, r}, std::pair{-r, -1.0}, std::pair{1.0, -r}})
        worst = std::max(worst, ulps(det_atan2(y, x), atan2l(static_cast<long double>(y), static_cast<long double>(x))));
    }
  MESSAGE("det_atan2: largest error " << worst << " ulp");
  CHECK(worst <= 2.0);
}

TEST_CASE("det_atan2 follows atan2's conventions for zeros, axes, infinities and NaN") {
  const double inf = INFINITY, pi = std::numbers::pi;
  CHECK(det_atan2(0.0, 0.0) == 0.0);
  CHECK(!std::signbit(det_atan2(0.0, 0.0)));
  CHECK(std::signbit(det_atan2(-0.0, 0.0)));
  CHECK(det_atan2(0.0, -0.0) == pi);
  CHECK(det_atan2(-0.0, -0.0) == -pi);
  CHECK(det_atan2(0.0, -1.0) == pi);
  CHECK(det_atan2(-0.0, -1.0) == -pi);
  CHECK(det_atan2(1.0, 0.0) == pi / 2);
  CHECK(det_atan2(-1.0, 0.0) == -pi / 2);
  CHECK(det_atan2(1.0, 1.0) == pi / 4);
  CHECK(det_atan2(1.0, inf) == 0.0);
  CHECK(det_atan2(inf, 1.0) == pi / 2);
  CHECK(det_atan2(inf, inf) == pi / 4);
  CHECK(det_atan2(-inf, -inf) == std::atan2(-inf, -inf));
  CHECK(std::isnan(det_atan2(NAN, 1.0)));
  CHECK(std::isnan(det_atan2(1.0, NAN)));
  // Odd in y, and the range (-pi, pi] except for the signed zeros.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int i = 0; i < 1000; ++i) {
    const double y = u(rng), x = u(rng);
    CHECK(det_atan2(-y, x) == -det_atan2(y, x));
    CHECK(std::fabs(det_atan2(y, x)) <= pi);
  }
}

TEST_CASE("det_sincos is within 2 ulp (plus 2^-53 absolute) of sin and cos up to 2^20, exact at 0") {
  std::mt19937_64 rng(11);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = std::ldexp(std::uniform_real_distribution<double>(-1, 1)(rng), static_cast<int>(rng() % 21));
    const igm::SinCos sc = det_sincos(x);
    const long double s = sinl(static_cast<long double>(x)), c = cosl(static_cast<long double>(x));
    for (const auto& [got, want] : {std::pair{sc.sin, s}, std::pair{sc.cos, c}}) {
      const double abs_err = static_cast<double>(std::fabs(static_cast<long double>(got) - want));
      const double err = std::min(ulps(got, want), abs_err / std::ldexp(1.0, -53));
      worst = std::max(worst, err);
    }
  }
  // Multiples of pi/4 and pi/2 (the reduction's boundaries and its hardest points).
  for (int k = -64; k <= 64; ++k) {
    const double x = k * (std::numbers::pi / 4);
    const igm::SinCos sc = det_sincos(x);
    worst = std::max(worst, std::min(ulps(sc.sin, sinl(static_cast<long double>(x))),
                                     static_cast<double>(std::fabs(sc.sin - sinl(static_cast<long double>(x)))) / 0x1p-53));
    worst = std::max(worst, std::min(ulps(sc.cos, cosl(static_cast<long double>(x))),
                                     static_cast<double>(std::fabs(sc.cos - cosl(static_cast<long double>(x)))) / 0x1p-53));
  }
  MESSAGE("det_sincos: largest error " << worst);
  CHECK(worst <= 2.0);
  CHECK(det_sincos(0.0).sin == 0.0);
  CHECK(det_sincos(0.0).cos == 1.0);
  CHECK(std::isnan(det_sincos(INFINITY).sin));
  CHECK(std::isnan(det_sincos(NAN).cos));
}

TEST_CASE("det_sincos at special points: signed zero, pi, pi/2, the reduction's sign") {
  const double pi = std::numbers::pi;
  CHECK(std::signbit(det_sincos(-0.0).sin));
  CHECK(det_sincos(-0.0).cos == 1.0);
  // sin(pi_double) = pi - pi_double to far below an ulp: 0x1.1a62633145c07p-53 correctly rounded.
  CHECK(det_sincos(pi).sin == 0x1.1a62633145c07p-53);
  CHECK(det_sincos(-pi).sin == -0x1.1a62633145c07p-53);
  CHECK(det_sincos(pi).cos == -1.0);
  CHECK(det_sincos(pi / 2).sin == 1.0);
  CHECK(det_sincos(pi / 2).cos == 0x1.1a62633145c07p-54);
  CHECK(det_sincos(0x1p-30).sin == 0x1p-30);  // sin x = x for |x| < 2^-26 (correctly rounded)
  CHECK(det_sincos(0x1p-30).cos == 1.0);
  // sin^2 + cos^2 = 1 within a few ulp, and sin(-x) = -sin(x), cos(-x) = cos(x) exactly.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-100, 100);
  for (int i = 0; i < 1000; ++i) {
    const double x = u(rng);
    const igm::SinCos a = det_sincos(x), b = det_sincos(-x);
    CHECK(b.sin == -a.sin);
    CHECK(b.cos == a.cos);
    CHECK(std::fabs(a.sin * a.sin + a.cos * a.cos - 1) <= 0x1p-50);
  }
}

TEST_CASE("det_hypot is within 2 ulp of hypot, without overflow or underflow") {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> e(-1070, 1020);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = std::ldexp(u(rng), e(rng)), y = i % 2 ? std::ldexp(u(rng), e(rng)) : x * u(rng);
    worst = std::max(worst, ulps(igm::det_hypot(x, y), hypotl(static_cast<long double>(x), static_cast<long double>(y))));
  }
  MESSAGE("det_hypot: largest error " << worst << " ulp");
  CHECK(worst <= 2.0);
  CHECK(igm::det_hypot(3.0, 4.0) == 5.0);
  CHECK(igm::det_hypot(-0.0, 0.0) == 0.0);
  CHECK(igm::det_hypot(0x1p1000, 0x1p1000) == 0x1.6a09e667f3bcdp+1000);  // sqrt(2) 2^1000, no overflow
  CHECK(igm::det_hypot(0x1p-1070, 0.0) == 0x1p-1070);                    // subnormal, no underflow
  CHECK(igm::det_hypot(-7.0, 0.0) == 7.0);
  CHECK(igm::det_hypot(INFINITY, NAN) == INFINITY);
  CHECK(std::isnan(igm::det_hypot(NAN, 1.0)));
}

TEST_CASE("det_exp and det_log are within 2 ulp of expl and logl, with libm's special values") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(-700, 700), um(0.5, 1);
  std::uniform_int_distribution<int> e(-1000, 1000);
  double worst_exp = 0, worst_log = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = i % 2 == 0 ? ux(rng) : ux(rng) * 1e-3;  // and near 0, where r is small
    worst_exp = std::max(worst_exp, ulps(igm::det_exp(x), expl(static_cast<long double>(x))));
    const double y = i % 2 == 0 ? std::ldexp(um(rng), e(rng)) : 1 + ux(rng) * 1e-6;  // and near 1
    worst_log = std::max(worst_log, ulps(igm::det_log(y), logl(static_cast<long double>(y))));
  }
  MESSAGE("det_exp: largest error " << worst_exp << " ulp; det_log: " << worst_log << " ulp");
  CHECK(worst_exp <= 2.0);
  CHECK(worst_log <= 2.0);
  CHECK(igm::det_exp(0) == 1);
  CHECK(igm::det_log(1) == 0);
  CHECK(igm::det_exp(1000) == INFINITY);
  CHECK(igm::det_exp(-1000) == 0);
  CHECK(std::isnan(igm::det_exp(NAN)));
  CHECK(igm::det_log(0) == -INFINITY);
  CHECK(igm::det_log(INFINITY) == INFINITY);
  CHECK(std::isnan(igm::det_log(-1)));
  CHECK(std::isnan(igm::det_log(NAN)));
}
