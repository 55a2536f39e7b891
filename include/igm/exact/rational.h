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

/// Parses decimal text exactly, the whole string:
///   [+-] (digits [. [digits]] | . digits) [(e|E) [+-] digits]      e.g. "1e-3", ".5", "5.", "+1.25E+2"
///   [+-] digits / digits   (denominator unsigned and nonzero)         e.g. "1/3", "-2/4" -> -1/2
/// "0.1" is exactly 1/10, never the double nearest to it; the result is canonical. Returns
/// nullopt on anything else (empty, whitespace anywhere, "e5", "1e", "--1", "nan", "inf", "0x10",
/// "1/0", "1/-2"), and when |exponent| > max_exponent or the mantissa has more than max_exponent
/// digits: a bound on the size of the result (about 3.33 * 2 * max_exponent bits). max_exponent is
/// clamped to [0, 1e8]. Cost: O(n^2) at worst in the length n of the text (GMP conversion).
std::optional<Rational> parse_rational(std::string_view text, long max_exponent = 100000);

/// The double nearest to q toward zero (truncation: |to_double(q)| <= |q| < the next double away
/// from zero), over the whole range: +-DBL_MAX beyond it, 0 (with q's sign lost) below the
/// smallest subnormal 2^-1074. Never Inf or NaN. For output and initial guesses only, never for decisions.
double to_double(const Rational& q);

/// A double within relative error 2^-51 of q (plus 2^-1074 absolute; +-DBL_MAX beyond the range;
/// not necessarily the truncation). Fast for power-of-two denominators (no division), which the
/// refined embeddings produce. For candidate filters with a stated margin and for pictures only.
double approximate(const Rational& q);

/// "p/q", or "p" when the denominator is 1: the exact text form, read back by parse_rational.
std::string to_string(const Rational& q);

/// Bits of numerator plus bits of denominator: the size measure reported by the stages.
std::size_t bit_size(const Rational& q);

}  // namespace igm
