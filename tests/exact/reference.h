#pragma once
// Reference implementations for the exact tests, written independently of src/exact:
// the exact value of a double from its bit fields, and orient2d as a plain GMP mpq determinant.
#include <gmpxx.h>

#include <cstdint>
#include <cstring>

namespace igm_ref {

// (-1)^s * m * 2^(e - 1075) from the bit fields, integer arithmetic only. Pre: x finite.
inline mpq_class exact_from_bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, 8);
  const bool neg = b >> 63;
  const int e = static_cast<int>((b >> 52) & 0x7ff);
  std::uint64_t m = b & ((std::uint64_t(1) << 52) - 1);
  int ex = 1 - 1075;
  if (e != 0) {
    m |= std::uint64_t(1) << 52;
    ex = e - 1075;
  }
  mpz_class num;
  mpz_import(num.get_mpz_t(), 1, 1, sizeof(m), 0, 0, &m);
  mpz_class den = 1;
  if (ex >= 0)
    num <<= ex;
  else
    den <<= -ex;
  if (neg) num = -num;
  mpq_class q(num, den);
  q.canonicalize();
  return q;
}

// Sign (-1, 0, 1) of (ax-cx)(by-cy) - (ay-cy)(bx-cx) in mpq.
inline int orient(const mpq_class& ax, const mpq_class& ay, const mpq_class& bx, const mpq_class& by,
                  const mpq_class& cx, const mpq_class& cy) {
  mpq_class det = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx);
  return sgn(det);
}

inline int orient_d(double ax, double ay, double bx, double by, double cx, double cy) {
  return orient(exact_from_bits(ax), exact_from_bits(ay), exact_from_bits(bx), exact_from_bits(by),
                exact_from_bits(cx), exact_from_bits(cy));
}

inline double from_bits(std::uint64_t b) {
  double x;
  std::memcpy(&x, &b, 8);
  return x;
}

}  // namespace igm_ref
