#include "igm/core/det_math.h"

#include <cmath>
#include <limits>

namespace igm {

namespace {

// atan(k / 8) = kAtanHi[k] + kAtanLo[k], k = 0..8 (double-double, from 300-bit arithmetic).
constexpr double kAtanHi[9] = {0.0,
                               0x1.fd5ba9aac2f6ep-4,
                               0x1.f5b75f92c80ddp-3,
                               0x1.6f61941e4def1p-2,
                               0x1.dac670561bb4fp-2,
                               0x1.1e00babdefeb4p-1,
                               0x1.4978fa3269ee1p-1,
                               0x1.700a7c5784634p-1,
                               0x1.921fb54442d18p-1};
constexpr double kAtanLo[9] = {0.0,
                               -0x1.cd37686760c17p-59,
                               0x1.8ab6e3cf7afbdp-57,
                               -0x1.c63aae6f6e918p-56,
                               0x1.a2b7f222f65e2p-56,
                               -0x1.928df287a668fp-58,
                               0x1.2419a87f2a458p-56,
                               -0x1.8c34d25aadef6p-56,
                               0x1.1a62633145c07p-55};
constexpr double kPiHi = 0x1.921fb54442d18p+1, kPiLo = 0x1.1a62633145c07p-53;
constexpr double kHalfPiHi = 0x1.921fb54442d18p+0, kHalfPiLo = 0x1.1a62633145c07p-54;
// pi/2 = kP1 + kP2 + kP3 (kP1, kP2 with 30 significant bits: k * kP1 and k * kP2 exact for |k| < 2^23).
constexpr double kP1 = 0x1.921fb548p+0, kP2 = -0x1.de973dc8p-31, kP3 = -0x1.9d9cceba3f91fp-62;
constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
// Taylor coefficients, each the double nearest to: (-1)^i / (2i + 1) (atan), (-1)^i / (2i + 1)!
// (sin), (-1)^i / (2i)! (cos).
constexpr double kAtanC[9] = {0x1.0000000000000p+0,  -0x1.5555555555555p-2, 0x1.999999999999ap-3,
                              -0x1.2492492492492p-3, 0x1.c71c71c71c71cp-4,  -0x1.745d1745d1746p-4,
                              0x1.3b13b13b13b14p-4,  -0x1.1111111111111p-4, 0x1.e1e1e1e1e1e1ep-5};
constexpr double kSinC[9] = {0x1.0000000000000p+0,  -0x1.5555555555555p-3, 0x1.1111111111111p-7,
                             -0x1.a01a01a01a01ap-13, 0x1.71de3a556c734p-19, -0x1.ae64567f544e4p-26,
                             0x1.6124613a86d09p-33,  -0x1.ae7f3e733b81fp-41, 0x1.952c77030ad4ap-49};
constexpr double kCosC[10] = {0x1.0000000000000p+0,  -0x1.0000000000000p-1, 0x1.5555555555555p-5,
                              -0x1.6c16c16c16c17p-10, 0x1.a01a01a01a01ap-16, -0x1.27e4fb7789f5cp-22,
                              0x1.1eed8eff8d898p-29,  -0x1.93974a8c07c9dp-37, 0x1.ae7f3e733b81fp-45,
                              -0x1.6827863b97d97p-53};

// atan(r) for r in [0, 1].
double atan_unit(double r) {
  const int k = static_cast<int>(r * 8 + 0.5);  // 0..8
  const double c = k * 0.125;
  const double s = (r - c) / (1 + r * c);  // |s| <= 1/16
  const double s2 = s * s;
  // s - s^3/3 + s^5/5 - ... + s^17/17, Horner in s^2.
  double p = 0;
  for (int i = 8; i >= 0; --i) p = kAtanC[i] + s2 * p;
  return kAtanHi[k] + (kAtanLo[k] + s * p);
}

}  // namespace

double det_atan2(double y, double x) {
  if (std::isnan(x) || std::isnan(y)) return x + y;
  const double ax = std::fabs(x), ay = std::fabs(y);
  const bool steep = ay > ax;
  const double mx = steep ? ay : ax, mn = steep ? ax : ay;
  double a;  // the angle of (ax, ay) in [0, pi/2]
  if (mx == 0) {
    a = 0;
  } else if (std::isinf(mn)) {
    a = kAtanHi[8];  // both infinite: pi/4
  } else {
    const double t = atan_unit(mn / mx);
    a = steep ? (kHalfPiHi - t) + kHalfPiLo : t;
  }
  if (std::signbit(x)) a = (kPiHi - a) + kPiLo;
  return std::signbit(y) ? -a : a;
}

SinCos det_sincos(double x) {
  if (!std::isfinite(x)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan};
  }
  if (x == 0) return {x, 1.0};  // sin(-0) = -0 (the reduction below would give +0)
  const double kd = std::nearbyint(x * kTwoOverPi);  // round to nearest (the default mode)
  const double r = ((x - kd * kP1) - kd * kP2) - kd * kP3;  // |r| <= pi/4 (a hair more)
  const double r2 = r * r;
  // sin r = r (1 - r^2/3! + ... + r^16/17!), cos r = 1 - r^2/2! + ... + r^18/18!: Horner in r^2.
  double ps = 0, pc = 0;
  for (int i = 8; i >= 0; --i) ps = kSinC[i] + r2 * ps;
  for (int i = 9; i >= 0; --i) pc = kCosC[i] + r2 * pc;
  const double s = r * ps, c = pc;
  // The quadrant k mod 4 (kd is an integer-valued double; fmod is exact).
  const int q = static_cast<int>(std::fmod(kd, 4.0) + 4) % 4;
  switch (q) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

double det_hypot(double x, double y) {
  const double ax = std::fabs(x), ay = std::fabs(y);
  if (std::isinf(ax) || std::isinf(ay)) return std::numeric_limits<double>::infinity();
  if (std::isnan(ax) || std::isnan(ay)) return x + y;
  const double m = std::fmax(ax, ay), n = std::fmin(ax, ay);
  if (m == 0) return 0.0;
  const double r = n / m;  // in [0, 1]: 1 + r^2 neither overflows nor loses m's scale
  return m * std::sqrt(1 + r * r);
}

namespace {

// ln 2 = kLn2Hi + kLn2Lo (fdlibm's split: kLn2Hi has 21 trailing zero bits, so k * kLn2Hi is exact
// for |k| < 2^21).
constexpr double kLn2Hi = 0x1.62e42fee00000p-1, kLn2Lo = 0x1.a39ef35793c76p-33;
// Each the double nearest to 1 / i! (exp) and to 1 / (2i + 1) (atanh).
constexpr double kExpC[17] = {0x1.0000000000000p+0,  0x1.0000000000000p+0,  0x1.0000000000000p-1,
                              0x1.5555555555555p-3,  0x1.5555555555555p-5,  0x1.1111111111111p-7,
                              0x1.6c16c16c16c17p-10, 0x1.a01a01a01a01ap-13, 0x1.a01a01a01a01ap-16,
                              0x1.71de3a556c734p-19, 0x1.27e4fb7789f5cp-22, 0x1.ae64567f544e4p-26,
                              0x1.1eed8eff8d898p-29, 0x1.6124613a86d09p-33, 0x1.93974a8c07c9dp-37,
                              0x1.ae7f3e733b81fp-41, 0x1.ae7f3e733b81fp-45};
constexpr double kAtanhC[12] = {0x1.0000000000000p+0, 0x1.5555555555555p-2, 0x1.999999999999ap-3,
                                0x1.2492492492492p-3, 0x1.c71c71c71c71cp-4, 0x1.745d1745d1746p-4,
                                0x1.3b13b13b13b14p-4, 0x1.1111111111111p-4, 0x1.e1e1e1e1e1e1ep-5,
                                0x1.af286bca1af28p-5, 0x1.8618618618618p-5, 0x1.642c8590b2164p-5};

}  // namespace

double det_exp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.8) return std::numeric_limits<double>::infinity();
  if (x < -745.2) return 0.0;
  const double k = std::nearbyint(x / (kLn2Hi + kLn2Lo));  // |k| <= 1076
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;           // |r| <= ln 2 / 2 (a little more)
  double p = 0;
  for (int i = 16; i >= 0; --i) p = kExpC[i] + r * p;  // sum r^i / i!, i <= 16
  // 2^k p in two exact scalings (p in [0.7, 1.5]: one ldexp could overflow or lose bits early).
  const int ki = static_cast<int>(k);
  return std::ldexp(std::ldexp(p, ki / 2), ki - ki / 2);
}

double det_log(double x) {
  if (std::isnan(x) || x < 0) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0) return -std::numeric_limits<double>::infinity();
  if (std::isinf(x)) return x;
  int e = 0;
  double m = std::frexp(x, &e);  // x = m 2^e, m in [1/2, 1): exact
  if (m < 0x1.6a09e667f3bcdp-1) {  // below sqrt(1/2): m in [sqrt(1/2), sqrt(2))
    m *= 2;
    --e;
  }
  // log m = log(1 + f) = 2 atanh(s) = 2 s + s R, s = f / (2 + f), |s| <= 0.1716, R = 2 sum_i
  // s^2i / (2i + 1) (i = 1..11), written as f - (f^2/2 - s (f^2/2 + R)) with f = m - 1 exact
  // (fdlibm's form: the rounding errors stay in the small correction).
  const double f = m - 1, s = f / (2 + f), z = s * s, hfsq = 0.5 * f * f;
  double q = 0;
  for (int i = 11; i >= 1; --i) q = kAtanhC[i] + z * q;
  const double R = 2 * z * q;
  return e * kLn2Hi - ((hfsq - (s * (hfsq + R) + e * kLn2Lo)) - f);
}

}  // namespace igm
