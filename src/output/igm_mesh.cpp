#include "igm/output/igm_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "../core/parallel.h"
#include "igm/core/error.h"

namespace igm {

namespace {

void put_double(std::ostream& out, double x) {
  char buf[32];
  int n = std::snprintf(buf, sizeof buf, "%.17g", x);
  out.write(buf, n);
}

// The exact decimal expansion of a finite double x = M 2^E (M odd): an integer when E >= 0, else
// M 5^-E / 10^-E, that is -E digits after the point (at most 1074).
std::string exact_decimal(double x) {
  if (x == 0) return "0";
  int e = 0;
  const double m = std::frexp(x, &e);  // x = m 2^e, 0.5 <= |m| < 1
  long long mant = std::llabs(static_cast<long long>(std::ldexp(m, 53)));  // exact: 53 bits
  int exp2 = e - 53;
  while (mant % 2 == 0) mant /= 2, ++exp2;  // at most 52 steps
  Integer digits(static_cast<long>(mant));
  std::string s;
  if (exp2 >= 0) {
    mpz_mul_2exp(digits.get_mpz_t(), digits.get_mpz_t(), static_cast<mp_bitcnt_t>(exp2));
    s = digits.get_str();
  } else {
    const std::size_t frac = static_cast<std::size_t>(-exp2);
    Integer five;
    mpz_ui_pow_ui(five.get_mpz_t(), 5, frac);
    digits *= five;
    s = digits.get_str();
    if (s.size() <= frac) s.insert(0, frac + 1 - s.size(), '0');
    s.insert(s.size() - frac, 1, '.');
  }
  return x < 0 ? "-" + s : s;
}

// A UV coordinate of the doubles file: its exact decimal expansion when it is exactly a double,
// else %.17g of the double nearest to it toward zero.
void put_uv_coordinate(std::ostream& out, const Rational& q) {
  const double d = to_double(q);
  const mpz_srcptr den = q.get_den_mpz_t();
  if (mpz_scan1(den, 0) == mpz_sizeinbase(den, 2) - 1 && std::isfinite(d) && to_rational(d) == q)
    out << exact_decimal(d);
  else
    put_double(out, d);
}

void check_uv_count(const IgmMesh& igm, const std::vector<std::array<Point2q, 3>>& corner_uv) {
  if (corner_uv.size() != igm.triangles.size())
    throw Error(ErrorKind::InvalidArgument, "IGM has " + std::to_string(igm.triangles.size()) + " triangles but " +
                                                std::to_string(corner_uv.size()) + " UV triples");
}

// Writes put(i, stream) for i = 0..n-1 to out, in order. The lines are formatted in parallel
// (core/parallel.h) into strings of kLines items each, kBatch strings at a time, then written in
// order: the same bytes for any thread count, at most kLines * kBatch lines held in memory. Each
// string's stream copies out's format (its locale for integers).
template <class Put>
void put_lines(std::ostream& out, std::int64_t n, const Put& put) {
  constexpr std::int64_t kLines = 2048, kBatch = 64;
  std::vector<std::string> text(kBatch);
  for (std::int64_t b0 = 0; b0 < n; b0 += kLines * kBatch) {
    const std::int64_t chunks = std::min(kBatch, (n - b0 + kLines - 1) / kLines);
    parallel::for_each_index(chunks, 1, [&](std::int64_t c) {
      std::ostringstream s;
      s.copyfmt(out);
      const std::int64_t first = b0 + c * kLines, last = std::min(n, first + kLines);
      for (std::int64_t i = first; i < last; ++i) put(i, s);
      text[static_cast<std::size_t>(c)] = std::move(s).str();
    });
    for (std::int64_t c = 0; c < chunks; ++c) out << text[static_cast<std::size_t>(c)];
  }
}

void put_positions(std::ostream& out, const std::vector<Vec3d>& positions) {
  put_lines(out, static_cast<std::int64_t>(positions.size()), [&](std::int64_t v, std::ostream& o) {
    const Vec3d& p = positions[static_cast<std::size_t>(v)];
    o << "v ";
    put_double(o, p.x);
    o << ' ';
    put_double(o, p.y);
    o << ' ';
    put_double(o, p.z);
    o << '\n';
  });
}

}  // namespace

void write_igm_obj(std::ostream& out, const IgmMesh& igm, bool exact) {
  check_uv_count(igm, igm.corner_uv);
  out << (exact ? "# igm exact IGM: one vt per face corner, exact rationals p/q\n"
                : "# igm IGM: one vt per face corner (exact decimals where exactly doubles, else doubles rounded toward zero)\n");
  put_positions(out, igm.positions);
  put_lines(out, 3 * static_cast<std::int64_t>(igm.corner_uv.size()), [&](std::int64_t c, std::ostream& o) {
    const Point2q& uv = igm.corner_uv[static_cast<std::size_t>(c / 3)][static_cast<std::size_t>(c % 3)];
    o << "vt ";
    if (exact) {
      o << to_string(uv.x) << ' ' << to_string(uv.y);
    } else {
      put_uv_coordinate(o, uv.x);
      o << ' ';
      put_uv_coordinate(o, uv.y);
    }
    o << '\n';
  });
  put_lines(out, static_cast<std::int64_t>(igm.triangles.size()), [&](std::int64_t f, std::ostream& o) {
    o << 'f';
    for (int i = 0; i < 3; ++i)
      o << ' ' << igm.triangles[static_cast<std::size_t>(f)][i] + 1 << '/' << 3 * static_cast<std::size_t>(f) + i + 1;
    o << '\n';
  });
}

certify::IgmInput certify_input(const IgmMesh& igm, const std::vector<std::array<Point2q, 3>>& corner_uv) {
  check_uv_count(igm, corner_uv);
  certify::IgmInput in;
  in.faces = igm.triangles;
  in.num_vertices = static_cast<std::int64_t>(igm.positions.size());
  in.corner_uv.reserve(3 * corner_uv.size());
  for (const auto& tri : corner_uv)
    for (const Point2q& uv : tri) in.corner_uv.push_back({uv.x, uv.y});
  return in;
}

void write_quad_obj(std::ostream& out, const QuadMesh& q) {
  out << "# igm quad mesh\n";
  put_positions(out, q.positions);
  for (const auto& f : q.quads) out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << ' ' << f[3] + 1 << '\n';
}

}  // namespace igm
