#include "igm/exact/predicates.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "igm/core/error.h"

// The error bounds below assume every + - * is rounded once to nearest-even (no FMA contraction,
// no extended precision). GCC in ISO mode and the project's -ffp-contract=off guarantee it; the
// pragma additionally pins it for clang.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

namespace igm {

namespace {

// ---------------------------------------------------------------------------------------------
// Double filter: proof of the bound.
//
// Notation: u = 2^-53 (unit roundoff), h = 2^-1075 (half the smallest subnormal). For one IEEE
// double operation with round-to-nearest and a finite result fl(x) of the exact value x:
//   (R1) add/sub:  |fl(x) - x| <= u |fl(x)|          (a subnormal sum/difference is exact)
//   (R2) mul:      |fl(x) - x| <= u |fl(x)| + h      (h covers a result in the subnormal range)
//   (R3) rounding is monotone and odd, so fl(x) >= x / (1 + u) - h for x >= 0 (h only for mul).
// Exact quantities: p = ax-cx, q = by-cy, r = ay-cy, s = bx-cx, L = pq, R = rs, D = L - R.
// Computed: p^ q^ r^ s^, L^ = fl(p^ q^), R^ = fl(r^ s^), D^ = fl(L^ - R^), S^ = fl(|L^| + |R^|).
// By (R1) p = p^(1+t1), q = q^(1+t2) with |ti| <= u, so |p^q^ - pq| <= (2u + u^2)|p^q^|, and by
// (R2) |p^q^| <= (1+u)|L^| + h. Hence
//   |L^ - L| <= u|L^| + h + (2u+u^2)((1+u)|L^| + h) = k|L^| + (1+u)^2 h,  k = 3u + 3u^2 + u^3,
// the same for R. With (R1) on the last subtraction, |D^ - (L^ - R^)| <= u|D^|, so
//   |D^ - D| <= k (|L^| + |R^|) + 2(1+u)^2 h + u|D^|.
// The sign of D^ is certainly the sign of D when |D^ - D| < |D^|, which holds when
//   |D^| > k/(1-u) * (|L^|+|R^|) + 2(1+u)^2/(1-u) * h.                                  (*)
// The code computes E = fl(fl(c * S^) + m) with c = (3 + 16u)u (exact in double) and m = 2^-1070.
// By (R3): S^ >= (|L^|+|R^|)/(1+u), fl(c S^) >= c S^/(1+u) - h, and E >= (fl(c S^) + m)/(1+u), so
//   E >= c/(1+u)^3 * (|L^|+|R^|) + (m - h)/(1+u).
// Then |D^| > E implies (*) because c/(1+u)^3 >= k/(1-u) (3u + 7u^2 - O(u^3) >= 3u + 6u^2 + O(u^3))
// and (m - h)/(1+u) = 31h/(1+u) >= 2(1+u)^2/(1-u) h. Both inequalities are checked with exact
// rational arithmetic in tests/exact/predicates_test.cpp. Overflow: if any intermediate overflows
// then L^ or R^ is infinite or NaN, so S^ is Inf/NaN and the filter refuses; if S^ is finite then
// |L^ - R^| <= |L^|+|R^| gives |D^| <= S^ finite, and fl(c S^) + m cannot overflow. A difference that
// rounds to DBL_MAX still satisfies (R1). Comparisons are exact.
// ---------------------------------------------------------------------------------------------
constexpr double kEps = 0x1p-53;
constexpr double kCcwErrBoundA = (3.0 + 16.0 * kEps) * kEps;
constexpr double kUnderflowSlack = 0x1p-1070;

Sign sign_of(int s) { return s > 0 ? Sign::Positive : (s < 0 ? Sign::Negative : Sign::Zero); }

void require_finite(const Vec2d& p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    throw Error(ErrorKind::NonFinite, "orient2d called with a non-finite coordinate");
}

// ---------------------------------------------------------------------------------------------
// Rational filter: outward-rounded interval arithmetic without changing the rounding mode.
//
// (N1) For a finite double x and the exact value y of one + - * / on doubles with fl(y) = x
//      finite: next_down(x) <= y <= next_up(x). Round-to-nearest moves y by at most half the gap
//      to the neighbour of x on y's side (at a binade boundary, the smaller gap), in every range
//      including subnormals; next_down/next_up step exactly one gap.
// (N2) Hence [next_down(fl(a.lo - b.hi)), next_up(fl(a.hi - b.lo))] contains a - b for all
//      a in A, b in B; for products the extremes over a box are at its corners, so
//      [next_down(min fl(corner)), next_up(max fl(corner))] contains every product.
// (N3) Rounding is monotone with fl(0) = 0, so fl(y) > 0 implies y > 0 and fl(y) < 0 implies y < 0:
//      the last subtraction needs no widening.
// No overflow can occur: coordinates are scaled by a common power of two into [-4, 4]
// (scaling by 2^k is exact, and the sign of the determinant, homogeneous of degree 2, is unchanged).
// ---------------------------------------------------------------------------------------------

// The next double above x, for finite x, branch-free (operand signs are unpredictable here).
// x + 0.0 maps -0 to +0 and leaves every other value unchanged; then the bit pattern of a positive
// double (or +0) steps up by one, that of a negative double steps down by one (toward -0).
// Pre: x finite (callers never pass Inf/NaN: every value in the filter is below 2^8).
inline double next_up(double x) {
  const auto b = std::bit_cast<std::uint64_t>(x + 0.0);
  const std::uint64_t neg = b >> 63;
  return std::bit_cast<double>(b + 1 - 2 * neg);
}
inline double next_down(double x) { return -next_up(-x); }

// 2^k as a double, for -1022 <= k <= 1023 (a normal number: exact scaling).
inline double pow2(long k) { return std::bit_cast<double>(static_cast<std::uint64_t>(k + 1023) << 52); }

// The leading bits of a nonzero integer z, read from its limbs (GMP's documented mpz_size and
// mpz_limbs_read; 64-bit limbs without nails): |z| has bit length e, and with m the integer formed
// by its top 53 bits (truncation toward zero), lo = m 2^-53 in [0.5, 1) and
//   lo * 2^e <= |z| < (lo + 2^-53) 2^e = next_up(lo) 2^e        (the gap in [0.5, 1) is 2^-53),
// with equality on the left (exact) iff every bit below the top 53 is zero. m < 2^53 converts to
// double exactly and the scaling by 2^-53 is exact. Cost: O(1), plus a scan of the lower limbs
// for exactness that stops at the first nonzero limb (bound: the limb count).
static_assert(GMP_LIMB_BITS == 64 && GMP_NAIL_BITS == 0, "64-bit limbs without nails expected");
struct Lead {
  double lo, hi;
  long e;
};
[[gnu::always_inline]] inline Lead lead(mpz_srcptr z) {
  const auto n = static_cast<std::ptrdiff_t>(mpz_size(z));  // >= 1: z != 0
  const mp_limb_t* d = mpz_limbs_read(z);
  const std::uint64_t top = d[n - 1];
  const int clz = __builtin_clzll(top);
  std::uint64_t w = top << clz;  // the top 64 bits of |z|, bit 63 set
  std::uint64_t rest = 0;        // nonzero iff some bit below the window is set
  if (n >= 2) {
    if (clz) w |= d[n - 2] >> (64 - clz);
    rest = d[n - 2] & (~std::uint64_t(0) >> clz);
    for (std::ptrdiff_t i = n - 3; i >= 0 && rest == 0; --i) rest = d[i];
  }
  rest |= w & 0x7ff;  // the 11 window bits below the top 53
  Lead r;
  r.lo = static_cast<double>(w >> 11) * 0x1p-53;
  r.hi = rest == 0 ? r.lo : next_up(r.lo);
  r.e = 64 * static_cast<long>(n) - clz;
  return r;
}

// log2 of a power-of-two positive integer d, or -1 when d is not a power of two. O(1) for a
// single limb; otherwise scans the lower limbs (bound: the limb count, stops at a nonzero limb).
inline long pow2_exponent(mpz_srcptr d) {
  const auto n = static_cast<std::ptrdiff_t>(mpz_size(d));
  const mp_limb_t* l = mpz_limbs_read(d);
  const std::uint64_t top = l[n - 1];
  if ((top & (top - 1)) != 0) return -1;
  for (std::ptrdiff_t i = n - 2; i >= 0; --i)
    if (l[i] != 0) return -1;
  return 64 * static_cast<long>(n - 1) + __builtin_ctzll(top);
}

// |q| = mag * 2^e with mag in [lo, hi] subset of [0.25, 4); sign separately. zero when q == 0.
struct Mag {
  double lo = 0, hi = 0;
  long e = 0;
  int sgn = 0;
};
[[gnu::always_inline]] inline Mag magnitude(const Rational& q) {
  Mag m;
  m.sgn = mpq_sgn(q.get_mpq_t());
  if (m.sgn == 0) return m;
  const Lead n = lead(q.get_num_mpz_t());
  if (const long k = pow2_exponent(q.get_den_mpz_t()); k >= 0) {
    // den = 2^k = 0.5 * 2^(k+1): |q| = (2 n.lo .. 2 n.hi) 2^(ne - k - 1), exact doubling.
    m.e = n.e - k - 1;
    m.lo = 2 * n.lo;
    m.hi = 2 * n.hi;
    return m;
  }
  const Lead d = lead(q.get_den_mpz_t());
  m.e = n.e - d.e;
  // |q| / 2^e = (|num| / 2^ne) / (den / 2^de) in [n.lo / d.hi, n.hi / d.lo] subset of [0.5, 2];
  // (N1): the quotients are normal, widening gives [0.25, 4).
  m.lo = next_down(n.lo / d.hi);
  m.hi = next_up(n.hi / d.lo);
  return m;
}

// [lo, hi] containing sgn * mag * 2^(e - shift), for e - shift <= 1000. When the scaled exponent is
// below -1000, the value is below 4 * 2^-1001 < 2^-998 in magnitude: enclose by [0, 2^-998].
inline IntervalD scaled(const Mag& m, long shift) {
  if (m.sgn == 0) return {0, 0};
  const long k = m.e - shift;
  double lo, hi;
  if (k >= -1000) {
    const double f = pow2(k);  // lo * f >= 0.25 * 2^-1000 is normal: both products exact
    lo = m.lo * f;
    hi = m.hi * f;
  } else {
    lo = 0;
    hi = 0x1p-998;
  }
  return m.sgn > 0 ? IntervalD{lo, hi} : IntervalD{-hi, -lo};
}

inline IntervalD isub(const IntervalD& a, const IntervalD& b) {
  return {next_down(a.lo - b.hi), next_up(a.hi - b.lo)};
}
inline IntervalD imul(const IntervalD& a, const IntervalD& b) {
  const double p1 = a.lo * b.lo, p2 = a.lo * b.hi, p3 = a.hi * b.lo, p4 = a.hi * b.hi;
  return {next_down(std::min(std::min(p1, p2), std::min(p3, p4))),
          next_up(std::max(std::max(p1, p2), std::max(p3, p4)))};
}

// Per-thread scratch integers for the exact rational path (no allocation after warm-up).
struct Scratch {
  mpz_t t[8];
  Scratch() {
    for (auto& z : t) mpz_init(z);
  }
  ~Scratch() {
    for (auto& z : t) mpz_clear(z);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
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

namespace {

// x = m 2^e exactly with m an integer, |m| < 2^53: frexp gives f in [0.5, 1) with x = f 2^ex (also
// for subnormals), and f 2^53 is an integer in [2^52, 2^53), computed exactly by ldexp.
struct Split {
  long long m;
  int e;
};
inline Split split(double x) {
  if (x == 0) return {0, std::numeric_limits<int>::max()};  // never the minimum exponent
  int ex;
  const double f = std::frexp(x, &ex);
  return {static_cast<long long>(std::ldexp(f, 53)), ex - 53};
}
inline void set_scaled(mpz_ptr t, const Split& s, int emin) {
  mpz_set_si(t, static_cast<long>(s.m));
  if (s.m != 0) mpz_mul_2exp(t, t, static_cast<unsigned long>(s.e - emin));  // < 2100 bits shift
}

}  // namespace

Sign orient2d_exact(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  require_finite(a);
  require_finite(b);
  require_finite(c);
  // Every double is an integer times 2^e: with Ex (Ey) the least exponent among the nonzero x (y)
  // coordinates, x = X 2^Ex with X integer, and det = det(X, Y) 2^(Ex+Ey): same sign.
  const Split sax = split(a.x), sbx = split(b.x), scx = split(c.x);
  const Split say = split(a.y), sby = split(b.y), scy = split(c.y);
  const int ex = std::min({sax.e, sbx.e, scx.e}), ey = std::min({say.e, sby.e, scy.e});
  Scratch& S = scratch();
  mpz_ptr t0 = S.t[0], t1 = S.t[1], t2 = S.t[2], t3 = S.t[3], t4 = S.t[4], t5 = S.t[5];
  set_scaled(t0, sax, ex);
  set_scaled(t1, sbx, ex);
  set_scaled(t2, scx, ex);
  mpz_sub(t0, t0, t2);  // p = ax - cx
  mpz_sub(t1, t1, t2);  // s = bx - cx
  set_scaled(t2, sby, ey);
  set_scaled(t3, say, ey);
  set_scaled(t4, scy, ey);
  mpz_sub(t2, t2, t4);  // q = by - cy
  mpz_sub(t3, t3, t4);  // r = ay - cy
  mpz_mul(t4, t0, t2);
  mpz_mul(t5, t3, t1);
  return sign_of(mpz_cmp(t4, t5));
}

Sign orient2d(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  if (auto s = orient2d_filter(a, b, c)) return *s;
  return orient2d_exact(a, b, c);
}

std::optional<IntervalD> enclose(const Rational& q) {
  const Mag m = magnitude(q);
  if (m.sgn == 0) return IntervalD{0, 0};
  if (m.e < -1000 || m.e > 1000) return std::nullopt;
  return scaled(m, 0);  // k = m.e >= -1000: the exact branch, within [2^-1002, 2^1002)
}

std::optional<Sign> orient2d_filter(const Point2q& a, const Point2q& b, const Point2q& c) {
  const Mag m[6] = {magnitude(a.x), magnitude(a.y), magnitude(b.x),
                    magnitude(b.y), magnitude(c.x), magnitude(c.y)};
  // Common scale: the largest exponent among the nonzero coordinates, so that every scaled
  // magnitude is below 4 (mag < 4 and e - shift <= 0).
  long shift = std::numeric_limits<long>::min();
  for (const Mag& x : m)
    if (x.sgn != 0) shift = std::max(shift, x.e);
  if (shift == std::numeric_limits<long>::min()) return std::nullopt;  // all zero: collinear
  // Pivot: the determinant is invariant under cyclic rotation of (a, b, c). Subtracting the point
  // of largest magnitude would cancel its product term cx*cy (present in both L and R) only in
  // exact arithmetic, leaving interval widths of its size: subtract the smallest point instead.
  auto point_exp = [&](int i) {
    const long ex = m[2 * i].sgn ? m[2 * i].e : std::numeric_limits<long>::min();
    const long ey = m[2 * i + 1].sgn ? m[2 * i + 1].e : std::numeric_limits<long>::min();
    return std::max(ex, ey);
  };
  const long e0 = point_exp(0), e1 = point_exp(1), e2 = point_exp(2);
  const int pivot = (e0 <= e1 && e0 <= e2) ? 0 : (e1 <= e2 ? 1 : 2);
  const int ia = (pivot + 1) % 3, ib = (pivot + 2) % 3, ic = pivot;  // (a,b,c) rotated, same sign
  const IntervalD ax = scaled(m[2 * ia], shift), ay = scaled(m[2 * ia + 1], shift),
                  bx = scaled(m[2 * ib], shift), by = scaled(m[2 * ib + 1], shift),
                  cx = scaled(m[2 * ic], shift), cy = scaled(m[2 * ic + 1], shift);
  // |values| < 4: differences < 8, products < 64(1+2^-50), no overflow anywhere.
  const IntervalD l = imul(isub(ax, cx), isub(by, cy));
  const IntervalD r = imul(isub(ay, cy), isub(bx, cx));
  if (l.lo - r.hi > 0) return Sign::Positive;  // (N3)
  if (l.hi - r.lo < 0) return Sign::Negative;
  return std::nullopt;
}

Sign orient2d_exact(const Point2q& a, const Point2q& b, const Point2q& c) {
  Scratch& S = scratch();
  mpz_ptr t0 = S.t[0], t1 = S.t[1], t2 = S.t[2], t3 = S.t[3], t4 = S.t[4], t5 = S.t[5];
  const mpz_srcptr axn = a.x.get_num_mpz_t(), axd = a.x.get_den_mpz_t();
  const mpz_srcptr ayn = a.y.get_num_mpz_t(), ayd = a.y.get_den_mpz_t();
  const mpz_srcptr bxn = b.x.get_num_mpz_t(), bxd = b.x.get_den_mpz_t();
  const mpz_srcptr byn = b.y.get_num_mpz_t(), byd = b.y.get_den_mpz_t();
  const mpz_srcptr cxn = c.x.get_num_mpz_t(), cxd = c.x.get_den_mpz_t();
  const mpz_srcptr cyn = c.y.get_num_mpz_t(), cyd = c.y.get_den_mpz_t();
  const long kax = pow2_exponent(axd), kay = pow2_exponent(ayd), kbx = pow2_exponent(bxd),
             kby = pow2_exponent(byd), kcx = pow2_exponent(cxd), kcy = pow2_exponent(cyd);
  if (kax >= 0 && kay >= 0 && kbx >= 0 && kby >= 0 && kcx >= 0 && kcy >= 0) {
    // Dyadic: x = X / 2^Kx for all three x-coordinates with X integer, y likewise; the
    // determinant is the integer determinant divided by 2^(Kx+Ky) > 0.
    const long kx = std::max({kax, kbx, kcx}), ky = std::max({kay, kby, kcy});
    mpz_mul_2exp(t0, axn, kx - kax);
    mpz_mul_2exp(t1, bxn, kx - kbx);
    mpz_mul_2exp(t2, cxn, kx - kcx);
    mpz_sub(t0, t0, t2);  // p = ax - cx
    mpz_sub(t1, t1, t2);  // s = bx - cx
    mpz_mul_2exp(t2, byn, ky - kby);
    mpz_mul_2exp(t3, ayn, ky - kay);
    mpz_mul_2exp(t4, cyn, ky - kcy);
    mpz_sub(t2, t2, t4);  // q = by - cy
    mpz_sub(t3, t3, t4);  // r = ay - cy
    mpz_mul(t4, t0, t2);  // L = p q
    mpz_mul(t5, t3, t1);  // R = r s
    return sign_of(mpz_cmp(t4, t5));
  }
  // General: with P1 = axn cxd - cxn axd (ax - cx = P1/(axd cxd)), P2 = byn cyd - cyn byd,
  // P3 = ayn cyd - cyn ayd, P4 = bxn cxd - cxn bxd and all denominators > 0,
  //   det * axd ayd bxd byd cxd cyd = P1 P2 ayd bxd - P3 P4 axd byd.
  mpz_ptr t6 = S.t[6], t7 = S.t[7];
  mpz_mul(t0, axn, cxd);
  mpz_mul(t6, cxn, axd);
  mpz_sub(t0, t0, t6);  // P1
  mpz_mul(t1, byn, cyd);
  mpz_mul(t6, cyn, byd);
  mpz_sub(t1, t1, t6);  // P2
  mpz_mul(t2, ayn, cyd);
  mpz_mul(t6, cyn, ayd);
  mpz_sub(t2, t2, t6);  // P3
  mpz_mul(t3, bxn, cxd);
  mpz_mul(t6, cxn, bxd);
  mpz_sub(t3, t3, t6);  // P4
  mpz_mul(t4, t0, t1);
  mpz_mul(t6, ayd, bxd);
  mpz_mul(t4, t4, t6);  // P1 P2 ayd bxd
  mpz_mul(t5, t2, t3);
  mpz_mul(t7, axd, byd);
  mpz_mul(t5, t5, t7);  // P3 P4 axd byd
  return sign_of(mpz_cmp(t4, t5));
}

Sign orient2d(const Point2q& a, const Point2q& b, const Point2q& c) {
  if (auto s = orient2d_filter(a, b, c)) return *s;
  return orient2d_exact(a, b, c);
}

Point2q to_point2q(const Vec2d& p) { return Point2q{to_rational(p.x), to_rational(p.y)}; }

}  // namespace igm
