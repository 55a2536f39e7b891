#pragma once
// Robust geometric predicates. Every geometric decision in igm goes through these:
//   if (orient2d(a, b, c) == Sign::Positive) ...
// The double version is a floating-point filter with a proven error bound (Shewchuk 1997,
// "Adaptive precision floating-point arithmetic and fast robust geometric predicates", the
// ccwerrboundA bound, extended with an absolute term for underflow) and an exact GMP fallback.
// Requires -ffp-contract=off (set for the whole project): an FMA would void the bound.
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

/// Orientation of (a, b, c): Positive if counter-clockwise, Negative if clockwise, Zero if
/// collinear; exact for every finite input. Cost O(1); the exact path runs only when the
/// filter cannot decide. Pre: finite coordinates (throws igm::Error(NonFinite) otherwise).
Sign orient2d(const Vec2d& a, const Vec2d& b, const Vec2d& c);

/// The filter alone: the exact sign when the error bound proves it, nullopt otherwise (also on
/// overflow and non-finite input). For tests and the filter-vs-exact fuzzer.
std::optional<Sign> orient2d_filter(const Vec2d& a, const Vec2d& b, const Vec2d& c);

/// The exact path alone (GMP), for tests. Pre: finite coordinates.
Sign orient2d_exact(const Vec2d& a, const Vec2d& b, const Vec2d& c);

/// Exact orientation of rational points. Cost: a few GMP multiplications.
Sign orient2d(const Point2q& a, const Point2q& b, const Point2q& c);

/// Exact double -> rational point conversion (throws NonFinite).
Point2q to_point2q(const Vec2d& p);

}  // namespace igm
