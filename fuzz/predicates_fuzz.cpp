// libFuzzer target for the exact predicates. The first byte selects how the rest is decoded:
//   0: six raw doubles (8 bytes each, little-endian bit patterns: NaN, Inf, subnormals, anything)
//   1: near-collinear: raw a, b and t, c = a + t (b - a) rounded
//   2: small rationals: 16 (int16 numerator, uint8 denominator) pairs: a, b, c, d
//   3: scaled doubles: (int32 mantissa, int16 binary exponent) pairs: tiny, huge, subnormal
//   4: near-collinear rationals: a, b raw doubles, c = a + t (b - a) exactly with t = int32/uint16,
//      then c.x or c.y moved by +-2^-k (or +-2^-k/3)
//   5: multi-limb dyadics: numerators from 3 optional 64-bit words (zero limbs included) over 2^k;
//      also checks enclose(): lo <= q <= hi exactly
// Checks (abort() on any disagreement): the double filter, when it answers, equals the exact sign;
// orient2d(double) == exact == an mpq reference computed here; the rational filter (when it
// answers), the filtered and the exact rational orient2d agree with it too; antisymmetry and
// cyclic invariance; segment classification is symmetric and a proper crossing point lies on both
// lines. Non-finite doubles must be refused by the filter and throw Error(NonFinite), never crash.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "igm/core/error.h"
#include "igm/exact/intersect.h"
#include "igm/exact/predicates.h"

using namespace igm;

namespace {

struct Reader {
  const std::uint8_t* p;
  std::size_t n;
  template <class T>
  T get() {  // zero bytes past the end
    T v{};
    unsigned char buf[sizeof(T)] = {};
    const std::size_t k = n < sizeof(T) ? n : sizeof(T);
    std::memcpy(buf, p, k);
    p += k;
    n -= k;
    std::memcpy(&v, buf, sizeof(T));
    return v;
  }
};

void check(bool ok) {
  if (!ok) std::abort();
}

int ref_orient(const Point2q& a, const Point2q& b, const Point2q& c) {
  const mpq_class det = (a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x);
  return sgn(det);
}

void check_rational(const Point2q& a, const Point2q& b, const Point2q& c, int expected) {
  check(static_cast<int>(orient2d(a, b, c)) == expected);
  check(static_cast<int>(orient2d_exact(a, b, c)) == expected);
  if (auto f = orient2d_filter(a, b, c)) check(static_cast<int>(*f) == expected && expected != 0);
  check(orient2d(b, c, a) == static_cast<Sign>(expected));
  check(orient2d(b, a, c) == -static_cast<Sign>(expected));
}

void check_doubles(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  bool finite = true;
  for (const Vec2d* p : {&a, &b, &c}) finite = finite && std::isfinite(p->x) && std::isfinite(p->y);
  if (!finite) {
    check(!orient2d_filter(a, b, c).has_value());
    try {
      (void)orient2d(a, b, c);
      std::abort();  // must throw
    } catch (const Error& e) {
      check(e.kind() == ErrorKind::NonFinite);
    }
    return;
  }
  const Point2q qa = to_point2q(a), qb = to_point2q(b), qc = to_point2q(c);
  const int r = ref_orient(qa, qb, qc);
  const Sign e = orient2d_exact(a, b, c);
  check(static_cast<int>(e) == r);
  if (auto f = orient2d_filter(a, b, c)) check(*f == e && *f != Sign::Zero);
  check(orient2d(a, b, c) == e);
  check(orient2d(b, c, a) == e);
  check(orient2d(c, a, b) == e);
  check(orient2d(b, a, c) == -e);
  check(orient2d(a, c, b) == -e);
  check_rational(qa, qb, qc, r);
}

void check_segments(const Point2q& a, const Point2q& b, const Point2q& c, const Point2q& d) {
  const SegmentRelation s = classify(a, b, c, d);
  check(classify(c, d, a, b) == s);
  check(classify(b, a, d, c) == s);
  const auto p = intersection(a, b, c, d);
  check(p.has_value() == (s == SegmentRelation::ProperCrossing || s == SegmentRelation::Touching));
  if (p) check(on_segment(*p, a, b) && on_segment(*p, c, d));
  if (s == SegmentRelation::ProperCrossing) {
    const Point2q q = intersection_point(a, b, c, d);
    check(orient2d(a, b, q) == Sign::Zero && orient2d(c, d, q) == Sign::Zero);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  Reader in{data + 1, size - 1};
  switch (data[0] % 6) {
    case 0: {
      Vec2d p[3];
      for (auto& q : p) q = {in.get<double>(), in.get<double>()};
      check_doubles(p[0], p[1], p[2]);
      break;
    }
    case 1: {
      const Vec2d a{in.get<double>(), in.get<double>()}, b{in.get<double>(), in.get<double>()};
      const double t = in.get<double>();
      const Vec2d c{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
      check_doubles(a, b, c);
      break;
    }
    case 2: {
      Point2q p[4];
      for (auto& q : p) {
        const auto xn = in.get<std::int16_t>();
        const auto xd = in.get<std::uint8_t>();
        const auto yn = in.get<std::int16_t>();
        const auto yd = in.get<std::uint8_t>();
        q = {make_rational(xn, xd == 0 ? 1 : xd), make_rational(yn, yd == 0 ? 1 : yd)};
      }
      check_rational(p[0], p[1], p[2], ref_orient(p[0], p[1], p[2]));
      check_segments(p[0], p[1], p[2], p[3]);
      break;
    }
    case 4: {
      Point2q p[2];
      for (auto& q : p) {
        const double x = in.get<double>(), y = in.get<double>();
        if (!std::isfinite(x) || !std::isfinite(y)) return 0;
        q = to_point2q({x, y});
      }
      const auto tn = in.get<std::int32_t>();
      const auto td = in.get<std::uint16_t>();
      const Rational t = make_rational(tn, td == 0 ? 1 : td);
      Point2q c{Rational(p[0].x + t * (p[1].x - p[0].x)), Rational(p[0].y + t * (p[1].y - p[0].y))};
      check(ref_orient(p[0], p[1], c) == 0);
      check_rational(p[0], p[1], c, 0);
      const auto k = in.get<std::uint16_t>();
      Rational eps = 1;
      mpq_div_2exp(eps.get_mpq_t(), eps.get_mpq_t(), k % 2200);
      if (k & 0x8000) eps /= 3;
      if (k & 0x4000) eps = -eps;
      if (k & 0x2000)
        c.x += eps;
      else
        c.y += eps;
      check_rational(p[0], p[1], c, ref_orient(p[0], p[1], c));
      break;
    }
    case 5: {
      Point2q p[3];
      for (auto& q : p)
        for (Rational* v : {&q.x, &q.y}) {
          const auto mask = in.get<std::uint8_t>();
          mpz_class n = 0;
          for (int w = 0; w < 3; ++w) {
            const auto word = in.get<std::uint64_t>();
            n <<= 64;
            if (mask & (1 << w)) n += mpz_class(static_cast<unsigned long>(word));
          }
          if (mask & 8) n = -n;
          const auto k = in.get<std::uint8_t>();
          *v = make_rational(n, mpz_class(1) << k);
          if (auto iv = enclose(*v)) {
            check(iv->lo <= iv->hi && to_rational(iv->lo) <= *v && *v <= to_rational(iv->hi));
          }
        }
      check_rational(p[0], p[1], p[2], ref_orient(p[0], p[1], p[2]));
      break;
    }
    default: {
      Vec2d p[3];
      for (auto& q : p) {
        const auto mx = in.get<std::int32_t>();
        const auto ex = in.get<std::int16_t>();
        const auto my = in.get<std::int32_t>();
        const auto ey = in.get<std::int16_t>();
        q = {std::ldexp(static_cast<double>(mx), ex % 1100), std::ldexp(static_cast<double>(my), ey % 1100)};
      }
      check_doubles(p[0], p[1], p[2]);
      // the same values as rationals scaled far beyond double range
      Point2q r[3];
      for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y)) return 0;
        r[i] = to_point2q(p[i]);
        mpq_mul_2exp(r[i].x.get_mpq_t(), r[i].x.get_mpq_t(), 3000);
        mpq_div_2exp(r[i].y.get_mpq_t(), r[i].y.get_mpq_t(), 3000);
      }
      check_rational(r[0], r[1], r[2], ref_orient(r[0], r[1], r[2]));
      break;
    }
  }
  return 0;
}
