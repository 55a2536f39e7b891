#pragma once
// Deterministic elementary functions: atan2, sin, cos, exp and log computed with +, -, *, / and
// sqrt only (and exact scalings by powers of two).
//
// Why. libm's transcendental functions are not required to be correctly rounded, and x86-64
// glibc picks their kernels at load time by CPU features (FMA, AVX2): the same binary gives
// results that differ in the last bit between machines (measured: the cross field of most shared
// meshes changed with GLIBC_TUNABLES=glibc.cpu.hwcaps=-FMA..., bench/README.md "Field"). Where such
// a value decides output bytes (the cross field decides the field layout), these functions are
// used instead: IEEE-754 double operations in a fixed order (the library is compiled with
// -ffp-contract=off: no fused multiply-add changes a rounding), so the same bits on every
// machine, load and thread count.
//
// How. det_atan2: octant reduction to r = min / max in [0, 1], then
// atan(r) = atan(c) + atan((r - c) / (1 + r c)) with c = k / 8 the nearest eighth (atan(k / 8)
// as a double-double constant) and the Taylor series of atan on |s| <= 1/16 to s^17.
// det_sincos: x = k pi/2 + r with |r| <= pi/4 (Cody and Waite's three-part pi/2, exact products
// for |k| < 2^23), then the Taylor series of sin to r^17 and of cos to r^18. Accuracy (tested
// against libm, tests/core/det_math_test.cpp): within 2 ulp for atan2 anywhere, and for sin / cos
// within 2 ulp plus 2^-53 absolute for |x| <= 2^20 (measured 1.99 and 1.65); beyond that the reduction loses accuracy
// (still deterministic). Cost: a few dozen operations.
namespace igm {

/// atan2(y, x) in [-pi, pi] with std::atan2's conventions for signed zeros and infinities
/// (atan2(+-0, +0) = +-0, atan2(+-0, -0) = +-pi, atan2(+-inf, +-inf) = +-pi/4 or +-3pi/4); NaN if
/// either argument is NaN.
double det_atan2(double y, double x);

struct SinCos {
  double sin = 0, cos = 1;
};

/// sin(x) and cos(x); NaN for a non-finite x. Accuracy above.
SinCos det_sincos(double x);

/// sqrt(x^2 + y^2) without overflow or underflow of the squares (scaled by max(|x|, |y|)):
/// within 2 ulp of std::hypot (whose glibc kernel is CPU-dependent too); +inf if either argument
/// is infinite, else NaN if either is NaN.
double det_hypot(double x, double y);

/// exp(x): x = k ln 2 + r (two-part ln 2), the Taylor series of exp(r) to r^16, times 2^k
/// exactly; +inf above 709.8, 0 below -745.2, NaN for NaN. Within 2 ulp of libm where the result
/// is normal (tests/core/det_math_test.cpp).
double det_exp(double x);

/// log(x): x = m 2^e with m in [sqrt(1/2), sqrt(2)), log m = 2 atanh((m - 1) / (m + 1)) by its
/// series to the 23rd power (fdlibm's arrangement), plus e ln 2 (two-part); -inf at 0, NaN below 0 or for NaN, +inf at
/// +inf. Within 2 ulp of libm (tests/core/det_math_test.cpp).
double det_log(double x);

}  // namespace igm
