// The certifier's own exact decimal parser and orient2d (filter + exact).
#include <doctest/doctest.h>

#include <random>
#include <string>

#include "certify/exact.h"

using namespace igm::certify;

namespace {
mpq_class q(const char* s) {
  mpq_class r(s);
  r.canonicalize();
  return r;
}
ExactPoint pt(const mpq_class& x, const mpq_class& y) {
  ExactPoint p;
  p.x = x;
  p.y = y;
  prepare(p);
  return p;
}
}  // namespace

TEST_CASE("parse_exact: decimals and rationals, exactly") {
  struct Case {
    const char* text;
    const char* value;
  } cases[] = {{"3.75040769577", "375040769577/100000000000"},
               {"-5.51591682434", "-275795841217/50000000000"},
               {"0.1", "1/10"},
               {"-0", "0"},
               {"+7/14", "1/2"},
               {"-3/9", "-1/3"},
               {".5", "1/2"},
               {"5.", "5"},
               {"1e3", "1000"},
               {"1E+2", "100"},
               {"-2.5e-3", "-1/400"},
               {"0.000125", "1/8000"},
               {"00012.500", "25/2"},
               {"123456789012345678901234567890", "123456789012345678901234567890"},
               {"0.30000000000000000000000000001", "30000000000000000000000000001/100000000000000000000000000000"},
               {"4.4e-16", "11/25000000000000000"},
               {"1e-4000", nullptr}};
  for (const auto& c : cases) {
    CAPTURE(c.text);
    mpq_class v;
    REQUIRE(parse_exact(c.text, v));
    if (c.value) {
      CHECK(v == q(c.value));
    } else {
      CHECK(v > 0);
      CHECK(mpz_sizeinbase(v.get_den_mpz_t(), 10) == 4001);
    }
  }
  // 0.1 is not the double 0.1
  mpq_class tenth;
  REQUIRE(parse_exact("0.1", tenth));
  CHECK(tenth != mpq_class(0.1));
}

TEST_CASE("parse_exact: rejects everything else") {
  for (const char* bad : {"", "-", "+", ".", "e5", "1e", "1e+", "nan", "NaN", "inf", "-inf", "1/0", "0x10", "1e4001",
                          "1e99999999999999999999", "1.2.3", "1/-2", "-1/+2", " 1", "1 ", "1,5", "1/2/3", "1/2e3",
                          "--1", "1d3", "/2", "2/", "1e5.5"}) {
    CAPTURE(bad);
    mpq_class v;
    CHECK_FALSE(parse_exact(bad, v));
  }
}

TEST_CASE("orient2d: exact on decimals that doubles get wrong") {
  mpq_class a, b, c;
  REQUIRE(parse_exact("0.1", a));
  REQUIRE(parse_exact("0.2", b));
  REQUIRE(parse_exact("0.3", c));
  CHECK(orient2d(pt(a, a), pt(b, b), pt(c, c)) == 0);
  // nudge by 10^-30: far below double resolution at 0.3
  mpq_class eps;
  REQUIRE(parse_exact("1e-30", eps));
  CHECK(orient2d(pt(a, a), pt(b, b), pt(c, c + eps)) == 1);
  CHECK(orient2d(pt(a, a), pt(b, b), pt(c, c - eps)) == -1);
  CHECK(orient2d(pt(0, 0), pt(1, 0), pt(0, 1)) == 1);
  CHECK(orient2d(pt(0, 0), pt(0, 1), pt(1, 0)) == -1);
  CHECK(orient2d(pt(0, 0), pt(0, 0), pt(0, 0)) == 0);
  // huge and tiny magnitudes bypass the filter
  mpq_class big, tiny;
  REQUIRE(parse_exact("1e500", big));
  REQUIRE(parse_exact("1e-500", tiny));
  CHECK_FALSE(pt(big, 0).filterable);
  CHECK_FALSE(pt(tiny, 0).filterable);
  CHECK(orient2d(pt(0, 0), pt(big, 0), pt(big, tiny)) == 1);
  CHECK(orient2d(pt(0, 0), pt(tiny, 0), pt(tiny, -tiny)) == -1);
}

TEST_CASE("orient2d: filter agrees with the exact predicate on near-degenerate decimals") {
  std::mt19937_64 rng(12345);
  std::uniform_int_distribution<long> coord(-2000000000L, 2000000000L);
  std::uniform_int_distribution<int> small(-3, 3);
  int decided_by_filter_disagree = 0, zero = 0;
  for (int it = 0; it < 20000; ++it) {
    // points on a line p + t d, with tiny perturbations at the 1e-17 scale of the decimals
    const mpq_class px(mpz_class(coord(rng)), mpz_class(1000000000)), py(mpz_class(coord(rng)), mpz_class(1000000000));
    const mpq_class dx(mpz_class(coord(rng)), mpz_class(1000000000)), dy(mpz_class(coord(rng)), mpz_class(1000000000));
    const mpq_class s(small(rng), 1), t(small(rng) + 5, 1);
    const mpq_class e1(small(rng), mpz_class("100000000000000000")), e2(small(rng), mpz_class("100000000000000000"));
    const ExactPoint a = pt(px, py), b = pt(px + s * dx + e1, py + s * dy), c = pt(px + t * dx, py + t * dy + e2);
    const int f = orient2d(a, b, c), e = orient2d_exact(a, b, c);
    if (f != e) ++decided_by_filter_disagree;
    if (e == 0) ++zero;
  }
  CHECK(decided_by_filter_disagree == 0);
  CHECK(zero > 100);  // the generator does produce exactly collinear cases
}
