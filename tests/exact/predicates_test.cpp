#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "igm/core/error.h"
#include "igm/exact/predicates.h"
#include "reference.h"

using namespace igm;

namespace {

int as_int(Sign s) { return static_cast<int>(s); }

// The textbook double determinant, no filter.
int naive_sign(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  const double det = (a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}
bool naive_finite(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  return std::isfinite((a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x));
}

int ref(const Vec2d& a, const Vec2d& b, const Vec2d& c) { return igm_ref::orient_d(a.x, a.y, b.x, b.y, c.x, c.y); }
int ref(const Point2q& a, const Point2q& b, const Point2q& c) { return igm_ref::orient(a.x, a.y, b.x, b.y, c.x, c.y); }

struct Counters {
  int total = 0, filter_answered = 0;
};

// Checks every entry point (orient2d, orient2d_exact, orient2d_filter) for one point type
// against the reference, plus the cyclic and antisymmetric invariances; returns the sign.
template <class P>
int check_all(const P& a, const P& b, const P& c, Counters* cnt) {
  const int r = ref(a, b, c);
  REQUIRE(as_int(orient2d(a, b, c)) == r);
  REQUIRE(as_int(orient2d_exact(a, b, c)) == r);
  const auto f = orient2d_filter(a, b, c);
  if (f) {
    REQUIRE(as_int(*f) == r);
    REQUIRE(*f != Sign::Zero);
  }
  REQUIRE(orient2d(b, c, a) == orient2d(a, b, c));
  REQUIRE(orient2d(c, a, b) == orient2d(a, b, c));
  REQUIRE(orient2d(b, a, c) == -orient2d(a, b, c));
  REQUIRE(orient2d(a, c, b) == -orient2d(a, b, c));
  if (cnt) {
    ++cnt->total;
    if (f) ++cnt->filter_answered;
  }
  return r;
}

int check_double(const Vec2d& a, const Vec2d& b, const Vec2d& c, Counters* cnt = nullptr) {
  return check_all(a, b, c, cnt);
}
int check_rational(const Point2q& a, const Point2q& b, const Point2q& c, Counters* cnt = nullptr) {
  return check_all(a, b, c, cnt);
}

double uniform(std::mt19937_64& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

Vec2d rand_pt(std::mt19937_64& rng, double lo = -1, double hi = 1) { return {uniform(rng, lo, hi), uniform(rng, lo, hi)}; }

// A random finite double from random bits (all exponents, subnormals included).
double rand_bits_double(std::mt19937_64& rng) {
  for (;;) {  // bound: expected 1.001 iterations (only exponent 0x7ff is rejected)
    const double x = igm_ref::from_bits(rng());
    if (std::isfinite(x)) return x;
  }
}

mpz_class rand_int(gmp_randclass& g, std::mt19937_64& rng, unsigned long max_bits) {
  const unsigned long bits = 1 + rng() % max_bits;
  mpz_class z = g.get_z_bits(bits);
  if (rng() % 2) z = -z;
  return z;
}
Rational rand_rational(gmp_randclass& g, std::mt19937_64& rng, unsigned long num_bits, unsigned long den_bits) {
  mpz_class n = rand_int(g, rng, num_bits);
  mpz_class d = g.get_z_bits(1 + rng() % den_bits);
  if (d == 0) d = 1;
  return make_rational(n, d);
}
// n / 2^k with |n| < 2^bits, k in [0, bits]: a dyadic number of about `bits` bits.
Rational rand_dyadic(gmp_randclass& g, std::mt19937_64& rng, unsigned long bits) {
  mpz_class n = g.get_z_bits(bits);
  if (rng() % 2) n = -n;
  const unsigned long k = rng() % (bits + 1);
  return make_rational(n, mpz_class(1) << k);
}

Rational scale2(const Rational& q, long k) {
  Rational r = q;
  if (k >= 0)
    mpq_mul_2exp(r.get_mpq_t(), q.get_mpq_t(), static_cast<unsigned long>(k));
  else
    mpq_div_2exp(r.get_mpq_t(), q.get_mpq_t(), static_cast<unsigned long>(-k));
  return r;
}
Point2q scale2(const Point2q& p, long k) { return {scale2(p.x, k), scale2(p.y, k)}; }

}  // namespace

TEST_CASE("double filter: the error-bound inequalities hold in exact arithmetic") {
  // See the proof in src/exact/predicates.cpp: with u = 2^-53, c = (3+16u)u, k = 3u+3u^2+u^3,
  // h = 2^-1075, m = 2^-1070 we need c/(1+u)^3 >= k/(1-u) and (m-h)/(1+u) >= 2(1+u)^2/(1-u) h.
  const mpq_class u(mpz_class(1), mpz_class(1) << 53);
  const mpq_class c = (3 + 16 * u) * u;
  CHECK(to_rational((3.0 + 16.0 * 0x1p-53) * 0x1p-53) == c);  // the constant is exact in double
  const mpq_class k = 3 * u + 3 * u * u + u * u * u;
  CHECK(mpq_class(c / ((1 + u) * (1 + u) * (1 + u))) >= mpq_class(k / (1 - u)));
  const mpq_class h(mpz_class(1), mpz_class(1) << 1075);
  const mpq_class m(mpz_class(1), mpz_class(1) << 1070);
  CHECK(to_rational(0x1p-1070) == m);
  CHECK(mpq_class((m - h) / (1 + u)) >= mpq_class(2 * (1 + u) * (1 + u) / (1 - u) * h));
  // and the bound is not vacuous: c/(1+u)^3 < 3u + 8u^2
  CHECK(mpq_class(c / ((1 + u) * (1 + u) * (1 + u))) < mpq_class(3 * u + 8 * u * u));
}

TEST_CASE("orient2d(double) agrees with GMP on random inputs, the filter answers almost always") {
  std::mt19937_64 rng(1);
  Counters cnt;
  for (int i = 0; i < 20000; ++i) check_double(rand_pt(rng), rand_pt(rng), rand_pt(rng), &cnt);
  CHECK(cnt.filter_answered > 0.999 * cnt.total);
  // random bit patterns: every exponent, overflowing and underflowing products
  Counters wild;
  for (int i = 0; i < 20000; ++i) {
    Vec2d p[3];
    for (auto& q : p) q = {rand_bits_double(rng), rand_bits_double(rng)};
    check_double(p[0], p[1], p[2], &wild);
  }
  MESSAGE("random bit patterns: filter answered " << wild.filter_answered << " of " << wild.total);
}

TEST_CASE("near-collinear doubles: naive determinant often wrong, orient2d never") {
  std::mt19937_64 rng(2);
  int naive_wrong = 0, zero = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Vec2d a = rand_pt(rng), b = rand_pt(rng);
    const double t = uniform(rng, -2, 3);
    const Vec2d c{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};  // on line ab, then rounded
    const int r = check_double(a, b, c);
    if (naive_sign(a, b, c) != r) ++naive_wrong;
    if (r == 0) ++zero;
  }
  MESSAGE("near-collinear: naive wrong on " << naive_wrong << " of " << n << ", exactly collinear " << zero);
  CHECK(naive_wrong > n / 5);

  // The classroom example (Kettner et al. 2008): p on a 2^-53 grid near (0.5, 0.5), line through
  // (12, 12) and (24, 24).
  int classroom_wrong = 0, classroom_total = 0;
  const Vec2d q{12, 12}, r{24, 24};
  for (int i = 0; i < 128; ++i)
    for (int j = 0; j < 128; ++j) {
      const Vec2d p{0.5 + i * 0x1p-53, 0.5 + j * 0x1p-53};
      const int s = check_double(p, q, r);
      if (naive_sign(p, q, r) != s) ++classroom_wrong;
      ++classroom_total;
    }
  MESSAGE("classroom example: naive wrong on " << classroom_wrong << " of " << classroom_total);
  CHECK(classroom_wrong > classroom_total / 10);
}

TEST_CASE("tiny inputs: 1e-300 scale and subnormals") {
  std::mt19937_64 rng(3);
  int naive_wrong = 0;
  const int n = 5000;
  for (int i = 0; i < n; ++i) {
    const double s = 1e-300;
    Vec2d a = rand_pt(rng), b = rand_pt(rng), c = rand_pt(rng);
    for (Vec2d* p : {&a, &b, &c}) p->x *= s, p->y *= s;
    const int r = check_double(a, b, c);
    if (naive_sign(a, b, c) != r) ++naive_wrong;  // products ~1e-600 underflow to 0
  }
  MESSAGE("1e-300 scale: naive wrong on " << naive_wrong << " of " << n);
  CHECK(naive_wrong > n / 2);
  // subnormal coordinates: k * 2^-1074 with |k| < 2^20
  int sub_naive_wrong = 0;
  for (int i = 0; i < n; ++i) {
    Vec2d p[3];
    for (auto& q : p) {
      q.x = std::ldexp(static_cast<double>(static_cast<std::int64_t>(rng() % (1 << 21)) - (1 << 20)), -1074);
      q.y = std::ldexp(static_cast<double>(static_cast<std::int64_t>(rng() % (1 << 21)) - (1 << 20)), -1074);
    }
    const int r = check_double(p[0], p[1], p[2]);
    if (naive_sign(p[0], p[1], p[2]) != r) ++sub_naive_wrong;
  }
  CHECK(sub_naive_wrong > n / 2);
  // near-collinear at the smallest scale: exact zero detected
  const double d = std::numeric_limits<double>::denorm_min();
  CHECK(orient2d(Vec2d{0, 0}, Vec2d{d, d}, Vec2d{2 * d, 2 * d}) == Sign::Zero);
  CHECK(orient2d(Vec2d{0, 0}, Vec2d{d, d}, Vec2d{2 * d, 3 * d}) == Sign::Positive);
  CHECK(orient2d(Vec2d{0, 0}, Vec2d{d, d}, Vec2d{3 * d, 2 * d}) == Sign::Negative);
}

TEST_CASE("huge inputs: 1e300 scale (naive overflows) and DBL_MAX") {
  std::mt19937_64 rng(4);
  int naive_nonfinite = 0;
  const int n = 5000;
  for (int i = 0; i < n; ++i) {
    Vec2d a = rand_pt(rng), b = rand_pt(rng), c = rand_pt(rng);
    for (Vec2d* p : {&a, &b, &c}) p->x *= 1e300, p->y *= 1e300;
    check_double(a, b, c);
    if (!naive_finite(a, b, c)) ++naive_nonfinite;
  }
  MESSAGE("1e300 scale: naive determinant non-finite on " << naive_nonfinite << " of " << n);
  CHECK(naive_nonfinite > n / 2);
  const double M = std::numeric_limits<double>::max();
  check_double({M, M}, {-M, -M}, {0, 0});
  check_double({M, -M}, {-M, M}, {M, M});
  check_double({M, M}, {-M, M}, {M, std::nextafter(M, 0.0)});
  CHECK(orient2d(Vec2d{-M, -M}, Vec2d{M, -M}, Vec2d{0, M}) == Sign::Positive);
  // near-collinear at huge scale
  for (int i = 0; i < 2000; ++i) {
    Vec2d a = rand_pt(rng, -1e300, 1e300), b = rand_pt(rng, -1e300, 1e300);
    const double t = uniform(rng, 0, 1);
    check_double(a, b, {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
  }
}

TEST_CASE("non-finite double inputs give NonFinite, the filter refuses") {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const Vec2d ok{1, 2};
  for (const Vec2d bad : {Vec2d{nan, 0}, Vec2d{0, nan}, Vec2d{inf, 0}, Vec2d{0, -inf}}) {
    CHECK_FALSE(orient2d_filter(bad, ok, Vec2d{3, 5}).has_value());
    CHECK_FALSE(orient2d_filter(ok, Vec2d{3, 5}, bad).has_value());
    for (int pos = 0; pos < 3; ++pos) {
      Vec2d p[3] = {ok, Vec2d{3, 5}, Vec2d{-1, 7}};
      p[pos] = bad;
      try {
        (void)orient2d(p[0], p[1], p[2]);
        FAIL("no exception");
      } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::NonFinite);
      }
      CHECK_THROWS_AS(orient2d_exact(p[0], p[1], p[2]), Error);
      CHECK_THROWS_AS(to_point2q(p[pos]), Error);
    }
  }
}

TEST_CASE("enclose: lo <= q <= hi exactly, relative width below 2^-49, range limits") {
  gmp_randclass g(gmp_randinit_default);
  g.seed(5);
  std::mt19937_64 rng(5);
  auto check_enclosure = [](const Rational& q) {
    const auto iv = enclose(q);
    REQUIRE(iv);
    REQUIRE(iv->lo <= iv->hi);
    REQUIRE(to_rational(iv->lo) <= q);
    REQUIRE(q <= to_rational(iv->hi));
    // relative width below 2^-49
    REQUIRE(Rational(to_rational(iv->hi) - to_rational(iv->lo)) <= Rational(abs(q) / (mpz_class(1) << 49)));
  };
  for (int i = 0; i < 20000; ++i) {
    const Rational q = i % 2 ? rand_rational(g, rng, 400, 400) : rand_dyadic(g, rng, 1 + rng() % 300);
    if (std::abs(static_cast<long>(mpz_sizeinbase(q.get_num_mpz_t(), 2)) -
                 static_cast<long>(mpz_sizeinbase(q.get_den_mpz_t(), 2))) > 990)
      continue;
    check_enclosure(q);
  }
  // exact doubles with power-of-two denominators enclose to a point
  for (int i = 0; i < 5000; ++i) {
    const double x = std::ldexp(uniform(rng, 0.5, 1) * (rng() % 2 ? 1 : -1), static_cast<int>(rng() % 1990) - 995);
    const auto iv = enclose(to_rational(x));
    REQUIRE(iv);
    CHECK(iv->lo == x);
    CHECK(iv->hi == x);
  }
  CHECK(enclose(Rational(0))->lo == 0);
  // range: succeeds for 2^-999 <= |q| <= 2^999, fails for |q| <= 2^-1001 or >= 2^1001
  check_enclosure(scale2(Rational(1), 999));
  check_enclosure(scale2(Rational(-1), -999));
  check_enclosure(scale2(make_rational(-1, 3), 999));
  check_enclosure(scale2(make_rational(5, 3), -999));
  CHECK_FALSE(enclose(scale2(Rational(1), 1001)).has_value());
  CHECK_FALSE(enclose(scale2(Rational(-1), -1001)).has_value());
  CHECK_FALSE(enclose(scale2(make_rational(1, 3), 3000)).has_value());
  CHECK_FALSE(enclose(scale2(make_rational(1, 3), -3000)).has_value());
}

TEST_CASE("rational orient2d agrees with GMP on random rationals with large numerators/denominators") {
  gmp_randclass g(gmp_randinit_default);
  g.seed(6);
  std::mt19937_64 rng(6);
  Counters cnt;
  for (int i = 0; i < 5000; ++i) {
    Point2q p[3];
    for (auto& q : p) q = {rand_rational(g, rng, 300, 300), rand_rational(g, rng, 300, 300)};
    check_rational(p[0], p[1], p[2], &cnt);
  }
  MESSAGE("random rationals: filter answered " << cnt.filter_answered << " of " << cnt.total);
  CHECK(cnt.filter_answered > 0.99 * cnt.total);
}

TEST_CASE("rational orient2d: exactly collinear gives Zero, tiny perturbations give the right sign") {
  gmp_randclass g(gmp_randinit_default);
  g.seed(7);
  std::mt19937_64 rng(7);
  int nonzero = 0;
  for (int i = 0; i < 3000; ++i) {
    const bool dyadic = i % 2;
    auto rnd = [&] { return dyadic ? rand_dyadic(g, rng, 1 + rng() % 200) : rand_rational(g, rng, 120, 120); };
    const Point2q a{rnd(), rnd()}, b{rnd(), rnd()};
    const Rational t = rnd();
    const Point2q c{Rational(a.x + t * (b.x - a.x)), Rational(a.y + t * (b.y - a.y))};
    REQUIRE(orient2d(a, b, c) == Sign::Zero);
    REQUIRE(orient2d_exact(a, b, c) == Sign::Zero);
    REQUIRE_FALSE(orient2d_filter(a, b, c).has_value());
    REQUIRE(check_rational(a, b, c) == 0);
    REQUIRE(check_rational(c, a, b) == 0);
    // perturb c by +-2^-k (times 1/3 for non-dyadic), k up to 400
    Rational eps = scale2(Rational(1), -static_cast<long>(rng() % 400));
    if (!dyadic) eps /= 3;
    if (rng() % 2) eps = -eps;
    const Point2q cx{Rational(c.x + eps), c.y}, cy{c.x, Rational(c.y + eps)};
    if (check_rational(a, b, cx) != 0) ++nonzero;
    check_rational(a, b, cy);
  }
  CHECK(nonzero > 2900);  // nonzero unless a.y == b.y (probability ~0)
}

TEST_CASE("rational orient2d on dyadic coordinates of 60 and 200 bits") {
  gmp_randclass g(gmp_randinit_default);
  g.seed(8);
  std::mt19937_64 rng(8);
  for (unsigned long bits : {60UL, 200UL}) {
    Counters cnt;
    for (int i = 0; i < 5000; ++i) {
      Point2q p[3];
      for (auto& q : p) q = {rand_dyadic(g, rng, bits), rand_dyadic(g, rng, bits)};
      check_rational(p[0], p[1], p[2], &cnt);
    }
    MESSAGE(bits << "-bit dyadic: filter answered " << cnt.filter_answered << " of " << cnt.total);
    CHECK(cnt.filter_answered > 0.99 * cnt.total);
  }
}

TEST_CASE("rational orient2d at extreme scales and mixed scales") {
  gmp_randclass g(gmp_randinit_default);
  g.seed(9);
  std::mt19937_64 rng(9);
  Counters cnt;
  for (long scale : {-5000L, -1100L, -1000L, 0L, 1000L, 1100L, 5000L}) {
    for (int i = 0; i < 500; ++i) {
      Point2q p[3];
      for (auto& q : p) q = {rand_rational(g, rng, 100, 100), rand_rational(g, rng, 100, 100)};
      for (auto& q : p) q = scale2(q, scale);
      check_rational(p[0], p[1], p[2], &cnt);
    }
  }
  CHECK(cnt.filter_answered > 0.99 * cnt.total);  // the common scaling keeps the filter working
  // mixed scales: one coordinate far smaller or larger than the others
  for (int i = 0; i < 3000; ++i) {
    Point2q p[3];
    for (auto& q : p) q = {rand_rational(g, rng, 64, 64), rand_rational(g, rng, 64, 64)};
    const int which = static_cast<int>(rng() % 6);
    Rational& x = which % 2 ? p[which / 2].y : p[which / 2].x;
    x = scale2(x, (rng() % 2 ? 1 : -1) * static_cast<long>(900 + rng() % 4000));
    check_rational(p[0], p[1], p[2]);
  }
  // collinear at mixed scales: (0,0), (2^-3000, 2^-3000), (2^3000, 2^3000)
  const Point2q o{0, 0}, s{scale2(Rational(1), -3000), scale2(Rational(1), -3000)},
      l{scale2(Rational(1), 3000), scale2(Rational(1), 3000)};
  CHECK(orient2d(o, s, l) == Sign::Zero);
  CHECK(orient2d(o, s, Point2q{l.x, Rational(l.y + s.y)}) == Sign::Positive);
  CHECK(orient2d(Point2q{0, 0}, Point2q{0, 0}, Point2q{0, 0}) == Sign::Zero);
}

TEST_CASE("rational orient2d on converted doubles agrees with the double orient2d") {
  std::mt19937_64 rng(10);
  for (int i = 0; i < 10000; ++i) {
    Vec2d p[3];
    for (auto& q : p) q = i % 2 ? Vec2d{rand_bits_double(rng), rand_bits_double(rng)} : rand_pt(rng);
    if (i % 4 == 1) {  // near-collinear
      const double t = uniform(rng, -1, 2);
      p[2] = {p[0].x + t * (p[1].x - p[0].x), p[0].y + t * (p[1].y - p[0].y)};
      if (!std::isfinite(p[2].x) || !std::isfinite(p[2].y)) continue;
    }
    const Sign sd = orient2d(p[0], p[1], p[2]);
    REQUIRE(orient2d(to_point2q(p[0]), to_point2q(p[1]), to_point2q(p[2])) == sd);
    REQUIRE(orient2d_exact(to_point2q(p[0]), to_point2q(p[1]), to_point2q(p[2])) == sd);
  }
}

TEST_CASE("compare and sign on rationals") {
  CHECK(compare(make_rational(1, 3), make_rational(2, 6)) == Sign::Zero);
  CHECK(compare(make_rational(1, 3), make_rational(1, 2)) == Sign::Negative);
  CHECK(compare(make_rational(-1, 3), make_rational(-1, 2)) == Sign::Positive);
  CHECK(sign(make_rational(-1, 3)) == Sign::Negative);
  CHECK(sign(Rational(0)) == Sign::Zero);
}
