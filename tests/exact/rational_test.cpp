#include <doctest/doctest.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/exact/rational.h"
#include "reference.h"

using namespace igm;

namespace {

Rational exact_from_bits(double x) { return igm_ref::exact_from_bits(x); }

bool canonical(const Rational& q) {
  Integer g;
  mpz_gcd(g.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
  return q.get_den() > 0 && g == 1;
}

Integer pow10(unsigned long k) {
  Integer r = 1;
  for (unsigned long i = 0; i < k; ++i) r *= 10;  // bound: k iterations (k small in tests)
  return r;
}

using igm_ref::from_bits;

}  // namespace

TEST_CASE("to_rational is exact on special doubles") {
  CHECK(to_rational(0.0) == 0);
  CHECK(to_rational(-0.0) == 0);
  CHECK(sgn(to_rational(-0.0)) == 0);
  CHECK(to_rational(1.0) == 1);
  CHECK(to_rational(-2.5) == make_rational(-5, 2));
  CHECK(to_rational(0.1) == make_rational(Integer("3602879701896397"), Integer(1) << 55));
  CHECK(to_rational(0.1) != make_rational(1, 10));
  const double tiny = std::numeric_limits<double>::denorm_min();
  CHECK(to_rational(tiny) == make_rational(1, Integer(1) << 1074));
  CHECK(to_rational(-tiny) == make_rational(-1, Integer(1) << 1074));
  const double minnorm = std::numeric_limits<double>::min();
  CHECK(to_rational(minnorm) == make_rational(1, Integer(1) << 1022));
  const double big = std::numeric_limits<double>::max();
  CHECK(to_rational(big) == Rational((Integer(1) << 1024) - (Integer(1) << 971)));
  CHECK(to_rational(-big) == -to_rational(big));
  // the largest subnormal
  CHECK(to_rational(from_bits(0x000fffffffffffffULL)) ==
        make_rational((Integer(1) << 52) - 1, Integer(1) << 1074));
}

TEST_CASE("to_rational agrees with the bit-field value and round-trips") {
  std::mt19937_64 rng(12345);
  int checked = 0, subnormal = 0;
  for (int i = 0; i < 20000; ++i) {
    std::uint64_t b = rng();
    if (i % 4 == 0) b &= 0x800fffffffffffffULL;  // a quarter subnormal (or zero)
    const double x = from_bits(b);
    if (!std::isfinite(x)) continue;
    const Rational q = to_rational(x);
    REQUIRE(q == exact_from_bits(x));
    CHECK(canonical(q));
    CHECK(to_double(q) == x);  // an exact double converts back to itself
    const auto back = parse_rational(to_string(q));
    REQUIRE(back);
    CHECK(*back == q);
    ++checked;
    if (x != 0 && std::fabs(x) < std::numeric_limits<double>::min()) ++subnormal;
  }
  CHECK(checked > 19000);
  CHECK(subnormal > 4000);
}

TEST_CASE("to_rational rejects NaN and infinities with NonFinite") {
  for (double x : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::signaling_NaN(),
                   std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                   from_bits(0xfff8000000000001ULL)}) {
    try {
      (void)to_rational(x);
      FAIL("no exception for a non-finite double");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::NonFinite);
    }
  }
}

TEST_CASE("make_rational canonicalizes and rejects a zero denominator") {
  CHECK(canonical(make_rational(6, -4)));
  CHECK(make_rational(6, -4) == make_rational(-3, 2));
  CHECK(make_rational(6, -4).get_num() == -3);
  CHECK(make_rational(0, -7).get_den() == 1);
  CHECK_THROWS_AS(make_rational(1, 0), Error);
}

TEST_CASE("parse_rational accepts the documented forms with exact values") {
  struct Case {
    const char* text;
    Rational expected;
  };
  const std::vector<Case> cases = {
      {"0", make_rational(0, 1)},
      {"-0", make_rational(0, 1)},
      {"+0.000", make_rational(0, 1)},
      {"1e-3", make_rational(1, 1000)},
      {".5", make_rational(1, 2)},
      {"-.5", make_rational(-1, 2)},
      {"5.", make_rational(5, 1)},
      {"+1.25E+2", make_rational(125, 1)},
      {"1.25e2", make_rational(125, 1)},
      {"0.1", make_rational(1, 10)},
      {"-12.5e-1", make_rational(-5, 4)},
      {"1/3", make_rational(1, 3)},
      {"-2/4", make_rational(-1, 2)},
      {"+6/3", make_rational(2, 1)},
      {"0/5", make_rational(0, 1)},
      {"-0/5", make_rational(0, 1)},
      {"007", make_rational(7, 1)},
      {"1e0", make_rational(1, 1)},
      {"1e-0", make_rational(1, 1)},
      {"2E+000003", make_rational(2000, 1)},
      {"123456789012345678901234567890", Rational(Integer("123456789012345678901234567890"))},
      {"3.14159265358979323846264338327950288", make_rational(Integer("314159265358979323846264338327950288"),
                                                             Integer("100000000000000000000000000000000000"))},
  };
  for (const auto& c : cases) {
    CAPTURE(c.text);
    const auto q = parse_rational(c.text);
    REQUIRE(q);
    CHECK(*q == c.expected);
    CHECK(canonical(*q));
  }
  // canonical form in detail
  const auto q = parse_rational("-2/4");
  REQUIRE(q);
  CHECK(q->get_num() == -1);
  CHECK(q->get_den() == 2);
  CHECK(to_string(*q) == "-1/2");
  CHECK(to_string(*parse_rational("-0")) == "0");
  CHECK(to_string(*parse_rational("1.50")) == "3/2");
}

TEST_CASE("parse_rational rejects malformed text") {
  for (const char* t : {"", "e5", "1e", "1e+", "1e-", "--1", "+-1", "-+1", "nan", "NaN", "inf", "-inf",
                        "Infinity", "0x10", "0X1p3", " 1", "1 ", " ", "\t1", "1\n", "1 /2", "1/ 2", "1/0",
                        "1/-2", "1/+2", "-1/-2", "1/", "/2", "/", ".", "-.", "+", "-", "1.2.3", "1..2",
                        "1e1.5", "1e1e1", "1/2/3", "1.5/2", "1/2.5", "1/2e3", "e", "E", ".e1", "1,5",
                        "١", "1_000", "0b1", "1f", "1d", "++1"}) {
    CAPTURE(t);
    CHECK_FALSE(parse_rational(t).has_value());
  }
  // embedded NUL is not whitespace-trimmed either
  CHECK_FALSE(parse_rational(std::string_view("1\0", 2)).has_value());
}

TEST_CASE("parse_rational matches integer arithmetic on random decimal text") {
  std::mt19937_64 rng(777);
  for (int i = 0; i < 3000; ++i) {
    const int int_digits = static_cast<int>(rng() % 12);
    const int frac_digits = static_cast<int>(rng() % 12);
    if (int_digits + frac_digits == 0) continue;
    std::string digits;
    for (int k = 0; k < int_digits + frac_digits; ++k) digits.push_back(static_cast<char>('0' + rng() % 10));
    const bool neg = rng() % 2;
    const bool has_exp = rng() % 2;
    const long exponent = has_exp ? static_cast<long>(rng() % 61) - 30 : 0;
    std::string text = neg ? "-" : (rng() % 3 == 0 ? "+" : "");
    text += digits.substr(0, int_digits);
    if (frac_digits > 0 || rng() % 2) text += ".";
    text += digits.substr(int_digits);
    if (has_exp) {
      text.push_back(rng() % 2 ? 'e' : 'E');
      text.append(std::to_string(exponent));
    }
    // expected: digits * 10^(exponent - frac_digits), by integer arithmetic
    const Integer mant(digits, 10);
    const long e10 = exponent - frac_digits;
    Rational expected = e10 >= 0 ? Rational(Integer(mant * pow10(static_cast<unsigned long>(e10))))
                                 : make_rational(mant, pow10(static_cast<unsigned long>(-e10)));
    if (neg) expected = -expected;
    CAPTURE(text);
    const auto q = parse_rational(text);
    REQUIRE(q);
    CHECK(*q == expected);
    CHECK(canonical(*q));
  }
}

TEST_CASE("parse_rational p/q matches make_rational on random integers") {
  std::mt19937_64 rng(99);
  for (int i = 0; i < 2000; ++i) {
    const long p = static_cast<long>(rng() % 2000001) - 1000000;
    const long q = static_cast<long>(rng() % 1000000) + 1;
    const std::string text = std::to_string(p) + "/" + std::to_string(q);
    const auto r = parse_rational(text);
    REQUIRE(r);
    CHECK(*r == make_rational(p, q));
    CHECK(canonical(*r));
    // r * q == p exactly
    CHECK(Rational(*r * q) == p);
  }
}

TEST_CASE("parse_rational exponent bound") {
  CHECK(parse_rational("1e100000").has_value());
  CHECK_FALSE(parse_rational("1e100001").has_value());
  CHECK(parse_rational("1e-100000").has_value());
  CHECK_FALSE(parse_rational("1e-100001").has_value());
  CHECK(*parse_rational("3e5", 5) == 300000);
  CHECK_FALSE(parse_rational("3e6", 5).has_value());
  CHECK_FALSE(parse_rational("1.234567", 5).has_value());  // mantissa digits also bounded
  CHECK_FALSE(parse_rational("1e99999999999999999999999999999").has_value());
  // Regression: with max_exponent near LONG_MAX the exponent accumulator used to overflow (UB)
  // and accept absurd exponents; max_exponent is now clamped to 1e8.
  CHECK_FALSE(parse_rational("1e9223372036854775807", LONG_MAX).has_value());
  CHECK_FALSE(parse_rational("1e92233720368547758070", LONG_MAX).has_value());
  CHECK_FALSE(parse_rational("1e100000001", LONG_MAX).has_value());
  CHECK(*parse_rational("1e-1", LONG_MAX) == make_rational(1, 10));
  // negative bound behaves as 0: only exponent 0 and single-digit-free mantissas... i.e. nothing
  // with digits beyond the bound
  CHECK_FALSE(parse_rational("1", -5).has_value());
  // size of an accepted result is bounded: 10^-100000 has ~332k bits
  const auto big = parse_rational("1e-100000");
  REQUIRE(big);
  CHECK(bit_size(*big) < 340000);
}

TEST_CASE("to_string and bit_size") {
  CHECK(to_string(make_rational(-7, 3)) == "-7/3");
  CHECK(to_string(make_rational(8, 4)) == "2");
  CHECK(bit_size(make_rational(3, 4)) == 2 + 3);
  CHECK(bit_size(make_rational(0, 1)) == 1 + 1);
  CHECK(bit_size(to_rational(std::numeric_limits<double>::denorm_min())) == 1 + 1075);
}

TEST_CASE("to_double truncates toward zero over the whole range, never Inf") {
  gmp_randclass g(gmp_randinit_default);
  g.seed(21);
  std::mt19937_64 rng(21);
  const double M = std::numeric_limits<double>::max();
  const Rational Mq = to_rational(M);
  int beyond = 0, subnormal = 0, zero = 0;
  for (int i = 0; i < 20000; ++i) {
    Integer n = g.get_z_bits(1 + rng() % 200), d = g.get_z_bits(1 + rng() % 200);
    if (d == 0) d = 1;
    if (n == 0) n = 1;
    Rational q = make_rational(n, d);
    const long shift = static_cast<long>(rng() % 2400) - 1200;  // 2^-1400 .. 2^1400
    if (shift >= 0)
      mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<unsigned long>(shift));
    else
      mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<unsigned long>(-shift));
    const bool neg = rng() % 2;
    if (neg) q = -q;
    const double x = to_double(q);
    REQUIRE(std::isfinite(x));
    const Rational aq = abs(q);
    const double ax = std::fabs(x);
    CAPTURE(to_string(q));
    REQUIRE(to_rational(ax) <= aq);  // toward zero
    if (ax == M) {
      if (aq > Mq) ++beyond;
    } else {
      REQUIRE(aq < to_rational(std::nextafter(ax, INFINITY)));  // the largest such double
    }
    if (x != 0) REQUIRE((x < 0) == neg);
    if (x == 0) ++zero;
    if (x != 0 && ax < std::numeric_limits<double>::min()) ++subnormal;
  }
  CHECK(beyond > 1000);
  CHECK(subnormal > 50);
  CHECK(zero > 1000);
  // Regression: values beyond the double range used to come back as +-Inf from mpq_get_d.
  Rational huge = 1;
  mpq_mul_2exp(huge.get_mpq_t(), huge.get_mpq_t(), 2000);
  CHECK(to_double(huge) == M);
  CHECK(to_double(-huge) == -M);
  CHECK(to_double(Rational(Mq + 1)) == M);
}
