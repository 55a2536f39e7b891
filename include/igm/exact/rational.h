#pragma once
// Exact rational numbers on GMP (gmpxx). mpq_class is always kept canonical here: construct
// from integers with make_rational(num, den), which canonicalizes, never mpq_class(num, den)
// alone. Beware `auto x = a + b;` with gmpxx: it binds an expression template; write the type.
#include <gmpxx.h>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace igm {

using Rational = mpq_class;
using Integer = mpz_class;

/// Exact value of a finite double. Throws igm::Error(NonFinite) on NaN or Inf. O(1) limbs.
Rational to_rational(double x);

/// num/den in canonical form. Pre: den != 0 (throws igm::Error(InvalidArgument) otherwise).
Rational make_rational(const Integer& num, const Integer& den);

/// Parses decimal text exactly: [+-]digits[.digits][(e|E)[+-]digits], or [+-]p/q with q > 0.
/// "0.1" is exactly 1/10, never the double nearest to it. Returns nullopt on anything else,
/// including exponents beyond +-max_exponent (a bound on the size of the result).
std::optional<Rational> parse_rational(std::string_view text, long max_exponent = 100000);

/// Nearest-or-adjacent double (truncation toward zero by GMP): for output and initial guesses
/// only, never for decisions.
double to_double(const Rational& q);

/// "p/q", or "p" when the denominator is 1: the exact text form, read back by parse_rational.
std::string to_string(const Rational& q);

/// Bits of numerator plus bits of denominator: the size measure reported by the stages.
std::size_t bit_size(const Rational& q);

}  // namespace igm
