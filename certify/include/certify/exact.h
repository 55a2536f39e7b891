#pragma once
// The certifier's own exact arithmetic: decimal/rational text -> mpq_class without any double,
// and a plain orient2d (double filter with a proven error bound, exact GMP fallback).
#include <string>
#include <string_view>

#include <gmpxx.h>

namespace igm::certify {

/// Largest |exponent| accepted in decimal text ("1e-5000" is rejected): keeps every parsed
/// number's size proportional to the text, not to a declared exponent.
inline constexpr long kMaxDecimalExponent = 4000;

/// Parses exactly: [+-]digits[.digits][(e|E)[+-]digits] (at least one mantissa digit; ".5" and
/// "5." accepted) or [+-]digits/digits (denominator > 0). No inf/nan/hex. Returns false on any
/// other text or an exponent beyond kMaxDecimalExponent. out is canonical on success.
bool parse_exact(std::string_view text, mpq_class& out);

/// A UV point with its exact value and a double approximation for the filter.
struct ExactPoint {
  mpq_class x, y;
  double ax = 0, ay = 0;   // mpq_get_d (truncated) approximations
  bool filterable = false; // both approximations are 0 exactly-for-0 or in [2^-400, 2^400]
};

/// Fills ax, ay, filterable from x, y.
void prepare(ExactPoint& p);

/// Sign of det[b-a, c-a]: +1 counter-clockwise, -1 clockwise, 0 collinear. Exact.
/// Filter: with M = max |approx coordinate|, the computed determinant differs from the exact one
/// by at most 64 u M^2 (1+O(u)), u = 2^-53 (derivation in certify/README.md); we use 2^-46 M^2.
int orient2d(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c);
/// Exact path only (for tests).
int orient2d_exact(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c);
/// The exact determinant value (for witnesses).
mpq_class orient2d_value(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c);

/// "p/q" or "p" (canonical).
std::string to_string(const mpq_class& q);

}  // namespace igm::certify
