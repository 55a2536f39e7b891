#include "igm/exact/rational.h"

#include <cmath>
#include <limits>

#include "igm/core/error.h"

namespace igm {

Rational to_rational(double x) {
  if (!std::isfinite(x)) throw Error(ErrorKind::NonFinite, "cannot convert a non-finite double to a rational");
  Rational q;
  mpq_set_d(q.get_mpq_t(), x);  // exact for every finite double
  return q;
}

Rational make_rational(const Integer& num, const Integer& den) {
  if (den == 0) throw Error(ErrorKind::InvalidArgument, "rational with zero denominator");
  Rational q(num, den);
  q.canonicalize();
  return q;
}

namespace {

// ASCII decimal digit only (std::isdigit is locale-dependent in principle).
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Hard cap on max_exponent: keeps every exponent computation below in range of long
// (|e10| <= 2 * kMaxExponentCap) and 10^|e10| below ~2^(6.7e8) bits.
constexpr long kMaxExponentCap = 100000000;

// Parses [+-]digits into z; returns false if no digit.
bool parse_integer(std::string_view s, Integer& z) {
  std::size_t i = 0;
  bool neg = false;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) neg = s[i++] == '-';
  if (i == s.size()) return false;
  for (std::size_t j = i; j < s.size(); ++j)
    if (!is_digit(s[j])) return false;
  std::string digits(s.substr(i));
  if (z.set_str(digits, 10) != 0) return false;
  if (neg) z = -z;
  return true;
}

}  // namespace

std::optional<Rational> parse_rational(std::string_view text, long max_exponent) {
  if (text.empty()) return std::nullopt;
  if (max_exponent < 0) max_exponent = 0;
  if (max_exponent > kMaxExponentCap) max_exponent = kMaxExponentCap;
  if (auto slash = text.find('/'); slash != std::string_view::npos) {
    Integer p, q;
    std::string_view den = text.substr(slash + 1);
    if (!den.empty() && (den[0] == '+' || den[0] == '-')) return std::nullopt;
    if (!parse_integer(text.substr(0, slash), p) || !parse_integer(den, q) || q == 0) return std::nullopt;
    return make_rational(p, q);
  }
  std::size_t i = 0;
  bool neg = false;
  if (text[i] == '+' || text[i] == '-') neg = text[i++] == '-';
  std::string digits;
  long frac_digits = 0;
  bool any_digit = false, seen_point = false;
  for (; i < text.size(); ++i) {
    char c = text[i];
    if (is_digit(c)) {
      digits.push_back(c);
      any_digit = true;
      if (seen_point) ++frac_digits;
    } else if (c == '.' && !seen_point) {
      seen_point = true;
    } else {
      break;
    }
  }
  if (!any_digit) return std::nullopt;
  long exponent = 0;
  if (i < text.size()) {
    if (text[i] != 'e' && text[i] != 'E') return std::nullopt;
    std::string_view e = text.substr(i + 1);
    std::size_t k = 0;
    bool eneg = false;
    if (k < e.size() && (e[k] == '+' || e[k] == '-')) eneg = e[k++] == '-';
    if (k == e.size()) return std::nullopt;
    // Bound: one step per character of the exponent; exponent <= max_exponent <= 1e8 before each
    // step, so exponent * 10 + 9 never overflows a long.
    for (; k < e.size(); ++k) {
      if (!is_digit(e[k])) return std::nullopt;
      exponent = exponent * 10 + (e[k] - '0');
      if (exponent > max_exponent) return std::nullopt;
    }
    if (eneg) exponent = -exponent;
  }
  if (static_cast<long>(digits.size()) > max_exponent) return std::nullopt;
  Integer mant;
  if (mant.set_str(digits, 10) != 0) return std::nullopt;
  long e10 = exponent - frac_digits;
  Integer scale;
  mpz_ui_pow_ui(scale.get_mpz_t(), 10, static_cast<unsigned long>(e10 < 0 ? -e10 : e10));
  Rational q = e10 >= 0 ? Rational(Integer(mant * scale)) : make_rational(mant, scale);
  if (neg) q = -q;
  return q;
}

double to_double(const Rational& q) {
  // mpq_get_d truncates toward zero, subnormals included; beyond the double range it returns
  // +-Inf (GMP documents overflow as system dependent), which truncation maps to +-DBL_MAX.
  const double d = q.get_d();
  if (std::isinf(d)) return std::copysign(std::numeric_limits<double>::max(), d);
  return d;
}

double approximate(const Rational& q) {
  const mpz_srcptr den = q.get_den_mpz_t();
  const std::size_t k = mpz_sizeinbase(den, 2) - 1;
  if (mpz_scan1(den, 0) != k) return to_double(q);  // not a power of two
  // q = m 2^e / 2^k with m in [0.5, 1) truncated (relative error < 2^-52); ldexp rounds once more
  // only in the subnormal range.
  long e = 0;
  const double m = mpz_get_d_2exp(&e, q.get_num_mpz_t());
  const long ex = e - static_cast<long>(k);
  if (ex > 1100) return std::copysign(std::numeric_limits<double>::max(), m);
  if (ex < -1100) return 0.0 * m;
  const double d = std::ldexp(m, static_cast<int>(ex));
  if (std::isinf(d)) return std::copysign(std::numeric_limits<double>::max(), m);
  return d;
}

std::string to_string(const Rational& q) {
  if (q.get_den() == 1) return q.get_num().get_str();
  return q.get_num().get_str() + "/" + q.get_den().get_str();
}

std::size_t bit_size(const Rational& q) {
  return mpz_sizeinbase(q.get_num_mpz_t(), 2) + mpz_sizeinbase(q.get_den_mpz_t(), 2);
}

}  // namespace igm
