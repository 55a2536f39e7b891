#include "igm/exact/predicates.h"

#include <cmath>
#include <limits>

#include "igm/core/error.h"

namespace igm {

namespace {

// Shewchuk's ccwerrboundA = (3 + 16 eps) eps with eps = 2^-53 bounds the error of
//   det = (ax-cx)(by-cy) - (ay-cy)(bx-cx)
// evaluated in IEEE double with round-to-nearest relative to detsum = |detleft| + |detright|,
// as long as no operation underflows or overflows. Subtractions never underflow inexactly
// (a subnormal difference is exact); each of the two products and the final subtraction may
// lose at most 2^-1075 absolutely in the subnormal range, so adding 2^-1070 to the bound keeps
// it valid in that range. Overflow yields Inf/NaN in detsum, which the filter refuses.
constexpr double kEps = 0x1p-53;
constexpr double kCcwErrBoundA = (3.0 + 16.0 * kEps) * kEps;
constexpr double kUnderflowSlack = 0x1p-1070;

Sign sign_of(int s) { return s > 0 ? Sign::Positive : (s < 0 ? Sign::Negative : Sign::Zero); }

void require_finite(const Vec2d& p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    throw Error(ErrorKind::NonFinite, "orient2d called with a non-finite coordinate");
}

}  // namespace

std::optional<Sign> orient2d_filter(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  const double detleft = (a.x - c.x) * (b.y - c.y);
  const double detright = (a.y - c.y) * (b.x - c.x);
  const double det = detleft - detright;
  const double detsum = std::fabs(detleft) + std::fabs(detright);
  if (!(detsum <= std::numeric_limits<double>::max())) return std::nullopt;  // Inf or NaN
  const double errbound = kCcwErrBoundA * detsum + kUnderflowSlack;
  if (det > errbound) return Sign::Positive;
  if (-det > errbound) return Sign::Negative;
  return std::nullopt;
}

Sign orient2d_exact(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  require_finite(a);
  require_finite(b);
  require_finite(c);
  const Rational ax(a.x), ay(a.y), bx(b.x), by(b.y), cx(c.x), cy(c.y);  // exact (mpq_set_d)
  const Rational l = (ax - cx) * (by - cy);
  const Rational r = (ay - cy) * (bx - cx);
  return sign_of(cmp(l, r));
}

Sign orient2d(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  if (auto s = orient2d_filter(a, b, c)) return *s;
  return orient2d_exact(a, b, c);
}

Sign orient2d(const Point2q& a, const Point2q& b, const Point2q& c) {
  const Rational l = (a.x - c.x) * (b.y - c.y);
  const Rational r = (a.y - c.y) * (b.x - c.x);
  return sign_of(cmp(l, r));
}

Point2q to_point2q(const Vec2d& p) { return Point2q{to_rational(p.x), to_rational(p.y)}; }

}  // namespace igm
