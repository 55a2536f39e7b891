// Exact decimal parsing and orient2d for the certifier (GMP only).
#include "certify/exact.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

namespace igm::certify {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// 10^n, cached for small n.
void pow10(mpz_class& out, unsigned long n) {
  static const std::vector<mpz_class> table = [] {
    std::vector<mpz_class> t(64);
    mpz_class p = 1;
    for (auto& e : t) {  // bound: 64 entries
      e = p;
      p *= 10;
    }
    return t;
  }();
  if (n < table.size()) {
    out = table[n];
  } else {
    mpz_ui_pow_ui(out.get_mpz_t(), 10, n);
  }
}

// Digits [first, last) (with possibly a '.' skipped by the caller) into an mpz.
void digits_to_mpz(std::string_view a, std::string_view b, mpz_class& out) {
  std::size_t total = a.size() + b.size();
  if (total <= 19) {
    unsigned long v = 0;
    for (char c : a) v = v * 10 + static_cast<unsigned long>(c - '0');  // bound: <= 19 digits
    for (char c : b) v = v * 10 + static_cast<unsigned long>(c - '0');
    out = v;
    return;
  }
  std::string buf;
  buf.reserve(total);
  buf.append(a);
  buf.append(b);
  mpz_set_str(out.get_mpz_t(), buf.c_str(), 10);
}

}  // namespace

bool parse_exact(std::string_view s, mpq_class& out) {
  const std::size_t n = s.size();
  std::size_t i = 0;
  bool neg = false;
  if (i < n && (s[i] == '+' || s[i] == '-')) {
    neg = s[i] == '-';
    ++i;
  }
  const std::size_t int_begin = i;
  while (i < n && is_digit(s[i])) ++i;  // bound: n
  std::string_view int_digits = s.substr(int_begin, i - int_begin);
  if (i < n && s[i] == '/') {
    if (int_digits.empty()) return false;
    ++i;
    const std::size_t den_begin = i;
    while (i < n && is_digit(s[i])) ++i;  // bound: n
    if (i == den_begin || i != n) return false;
    mpz_class num, den;
    digits_to_mpz(int_digits, {}, num);
    digits_to_mpz(s.substr(den_begin, i - den_begin), {}, den);
    if (den == 0) return false;
    mpz_swap(mpq_numref(out.get_mpq_t()), num.get_mpz_t());
    mpz_swap(mpq_denref(out.get_mpq_t()), den.get_mpz_t());
    out.canonicalize();
    if (neg) out = -out;
    return true;
  }
  std::string_view frac_digits;
  if (i < n && s[i] == '.') {
    ++i;
    const std::size_t fb = i;
    while (i < n && is_digit(s[i])) ++i;  // bound: n
    frac_digits = s.substr(fb, i - fb);
  }
  if (int_digits.empty() && frac_digits.empty()) return false;
  long exponent = 0;
  if (i < n && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    bool eneg = false;
    if (i < n && (s[i] == '+' || s[i] == '-')) {
      eneg = s[i] == '-';
      ++i;
    }
    const std::size_t eb = i;
    while (i < n && is_digit(s[i])) {  // bound: n
      exponent = exponent * 10 + (s[i] - '0');
      if (exponent > kMaxDecimalExponent) return false;
      ++i;
    }
    if (i == eb) return false;
    if (eneg) exponent = -exponent;
  }
  if (i != n) return false;
  // Drop leading zeros of the integer part and trailing zeros of the fraction (value unchanged).
  while (!int_digits.empty() && int_digits.front() == '0') int_digits.remove_prefix(1);
  while (!frac_digits.empty() && frac_digits.back() == '0') frac_digits.remove_suffix(1);
  if (int_digits.empty()) {
    while (!frac_digits.empty() && frac_digits.front() == '0') {  // 0.000ddd: keep scale
      frac_digits.remove_prefix(1);
      --exponent;
    }
  }
  const std::int64_t scale0 = std::int64_t(exponent) - std::int64_t(frac_digits.size());
  if (int_digits.size() + frac_digits.size() <= 18 && scale0 <= 0 && scale0 >= -18) {
    // Fast path: numerator < 10^18 and denominator 10^k <= 10^18 fit in 64 bits; reduce by the
    // integer gcd and store directly (the result is canonical).
    std::uint64_t num = 0, den = 1;
    for (char c : int_digits) num = num * 10 + std::uint64_t(c - '0');   // bound: <= 18 digits
    for (char c : frac_digits) num = num * 10 + std::uint64_t(c - '0');
    for (std::int64_t k = 0; k < -scale0; ++k) den *= 10;                // bound: <= 18
    if (num == 0) {
      out = 0;
      return true;
    }
    const std::uint64_t g = std::gcd(num, den);
    mpz_set_ui(mpq_numref(out.get_mpq_t()), static_cast<unsigned long>(num / g));
    mpz_set_ui(mpq_denref(out.get_mpq_t()), static_cast<unsigned long>(den / g));
    if (neg) mpz_neg(mpq_numref(out.get_mpq_t()), mpq_numref(out.get_mpq_t()));
    return true;
  }
  mpz_class num;
  digits_to_mpz(int_digits, frac_digits, num);
  if (num == 0) {
    out = 0;
    return true;
  }
  const std::int64_t scale = std::int64_t(exponent) - std::int64_t(frac_digits.size());
  mpz_class p;
  if (scale >= 0) {
    pow10(p, static_cast<unsigned long>(scale));
    num *= p;
    p = 1;
  } else {
    pow10(p, static_cast<unsigned long>(-scale));
  }
  if (neg) num = -num;
  mpz_swap(mpq_numref(out.get_mpq_t()), num.get_mpz_t());
  mpz_swap(mpq_denref(out.get_mpq_t()), p.get_mpz_t());
  out.canonicalize();
  return true;
}

void prepare(ExactPoint& p) {
  p.ax = mpq_get_d(p.x.get_mpq_t());
  p.ay = mpq_get_d(p.y.get_mpq_t());
  auto ok = [](double v, int s) {
    if (s == 0) return v == 0.0;
    double m = std::fabs(v);
    return m >= 0x1p-400 && m <= 0x1p400;
  };
  p.filterable = ok(p.ax, sgn(p.x)) && ok(p.ay, sgn(p.y));
}

mpq_class orient2d_value(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c) {
  mpq_class r = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return r;
}

int orient2d_exact(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c) {
  thread_local mpq_class t1, t2, t3, t4;
  mpq_sub(t1.get_mpq_t(), b.x.get_mpq_t(), a.x.get_mpq_t());
  mpq_sub(t2.get_mpq_t(), c.y.get_mpq_t(), a.y.get_mpq_t());
  mpq_mul(t1.get_mpq_t(), t1.get_mpq_t(), t2.get_mpq_t());
  mpq_sub(t3.get_mpq_t(), b.y.get_mpq_t(), a.y.get_mpq_t());
  mpq_sub(t4.get_mpq_t(), c.x.get_mpq_t(), a.x.get_mpq_t());
  mpq_mul(t3.get_mpq_t(), t3.get_mpq_t(), t4.get_mpq_t());
  return mpq_cmp(t1.get_mpq_t(), t3.get_mpq_t()) > 0 ? 1 : (mpq_equal(t1.get_mpq_t(), t3.get_mpq_t()) ? 0 : -1);
}

int orient2d(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c) {
  if (a.filterable && b.filterable && c.filterable) {
    const double m = std::max({std::fabs(a.ax), std::fabs(a.ay), std::fabs(b.ax), std::fabs(b.ay),
                               std::fabs(c.ax), std::fabs(c.ay)});
    if (m == 0.0) return 0;  // filterable zeros are exact zeros: three equal points
    const double det = (b.ax - a.ax) * (c.ay - a.ay) - (b.ay - a.ay) * (c.ax - a.ax);
    const double bound = m * m * 0x1p-46;  // >= 128 u M^2 > proven 64 u M^2 (1+O(u))
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  return orient2d_exact(a, b, c);
}

std::string to_string(const mpq_class& q) { return q.get_str(); }

}  // namespace igm::certify
