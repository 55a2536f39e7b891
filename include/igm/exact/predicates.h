#pragma once
// Robust geometric predicates. Every geometric decision in igm goes through these:
//   if (orient2d(a, b, c) == Sign::Positive) ...
// The double version is a floating-point filter with a proven error bound (Shewchuk 1997,
// "Adaptive precision floating-point arithmetic and fast robust geometric predicates", the
// ccwerrboundA bound, re-derived in predicates.cpp with an absolute term for underflow) and an
// exact GMP fallback. The rational version encloses every coordinate in a double interval,
// evaluates the determinant in interval arithmetic (outward rounded with nextafter, no change of
// rounding mode) and falls back to exact integer arithmetic when the sign is not certain.
// Requires -ffp-contract=off (set for the whole project): an FMA would void the bounds.
#include <optional>

#include "igm/exact/rational.h"

namespace igm {

enum class Sign : int { Negative = -1, Zero = 0, Positive = 1 };

inline Sign operator-(Sign s) { return static_cast<Sign>(-static_cast<int>(s)); }

struct Vec2d {
  double x = 0, y = 0;
};
struct Vec3d {
  double x = 0, y = 0, z = 0;
};
struct Point2q {
  Rational x, y;
};

/// Sign of an exact rational.
inline Sign sign(const Rational& q) { return static_cast<Sign>(sgn(q)); }

/// Exact comparison: Negative if a < b, Zero if a == b, Positive if a > b.
inline Sign compare(const Rational& a, const Rational& b) {
  const int c = cmp(a, b);
  return c < 0 ? Sign::Negative : (c > 0 ? Sign::Positive : Sign::Zero);
}

/// Orientation of (a, b, c): Positive if counter-clockwise, Negative if clockwise, Zero if
/// collinear; exact for every finite input. Cost O(1); the exact path runs only when the
/// filter cannot decide. Pre: finite coordinates (throws igm::Error(NonFinite) otherwise).
Sign orient2d(const Vec2d& a, const Vec2d& b, const Vec2d& c);

/// The filter alone: the exact sign when the error bound proves it, nullopt otherwise (also on
/// overflow and non-finite input). Never answers Zero. For tests and the filter-vs-exact fuzzer.
std::optional<Sign> orient2d_filter(const Vec2d& a, const Vec2d& b, const Vec2d& c);

/// The exact path alone, for tests: each double is m 2^e (|m| < 2^53), the determinant is taken on
/// GMP integers after shifting to common exponents. Pre: finite coordinates (throws NonFinite).
Sign orient2d_exact(const Vec2d& a, const Vec2d& b, const Vec2d& c);

/// Exact orientation of rational points (same convention as above). Filtered: every coordinate is
/// enclosed in a double interval (enclose(), after a common power-of-two scaling, so any magnitude
/// works), the determinant is evaluated in outward-rounded interval arithmetic (about 30 double
/// operations after reading the leading bits of the 12 integers); exact integer arithmetic (no gcd;
/// shifts only for dyadic coordinates) when the interval contains 0: always for exactly collinear
/// points. Thread-safe (per-thread scratch integers). Proof in src/exact/predicates.cpp.
/// Measured (callgrind, instructions per call, random triples): 60-bit dyadic 933 (orient2d_exact
/// alone 1239, plain mpq determinant 10011); 200-bit dyadic 1084 (1779, 17940); general 60-bit
/// rationals 1264 (1976, 24737). Collinear triples pay the filter plus the exact path.
Sign orient2d(const Point2q& a, const Point2q& b, const Point2q& c);

/// The rational filter alone: the exact sign when the interval evaluation proves it, nullopt
/// otherwise. Never answers Zero.
std::optional<Sign> orient2d_filter(const Point2q& a, const Point2q& b, const Point2q& c);

/// The exact rational path alone: sign of the determinant by integer arithmetic on numerators
/// and denominators (shifts only when every denominator is a power of two). For tests, benches.
Sign orient2d_exact(const Point2q& a, const Point2q& b, const Point2q& c);

/// A closed double interval [lo, hi].
struct IntervalD {
  double lo = 0, hi = 0;
};

/// A double interval containing q: lo <= q <= hi exactly, hi - lo <= 2^-49 |q| (hi == lo when q is
/// a double with a power-of-two denominator). Succeeds for q == 0 and 2^-999 <= |q| <= 2^999; nullopt
/// for |q| <= 2^-1001 or |q| >= 2^1001 (between: either). Cost: reads the top limbs, <= 2 divisions.
std::optional<IntervalD> enclose(const Rational& q);

/// Exact double -> rational point conversion (throws NonFinite).
Point2q to_point2q(const Vec2d& p);

}  // namespace igm
