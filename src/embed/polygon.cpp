#include "igm/embed/polygon.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "igm/core/error.h"

namespace igm {

namespace {

// Half-plane class of a non-zero direction for exact angular comparison: 0 for angles in
// [0, pi), 1 for [pi, 2 pi).
int half_of(const Rational& dx, const Rational& dy) {
  return (sgn(dy) < 0 || (sgn(dy) == 0 && sgn(dx) < 0)) ? 1 : 0;
}

// Exact "angle(a) < angle(b)" in [0, 2 pi) for non-zero directions.
bool angle_less(const Rational& ax, const Rational& ay, const Rational& bx, const Rational& by) {
  const int ha = half_of(ax, ay), hb = half_of(bx, by);
  if (ha != hb) return ha < hb;
  const Rational cross = ax * by - ay * bx;
  return sgn(cross) > 0;
}

}  // namespace

bool is_strictly_convex_ccw(const std::vector<Point2q>& c) {
  const std::size_t n = c.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (orient2d(c[i], c[(i + 1) % n], c[(i + 2) % n]) != Sign::Positive) return false;
  // All turns are strict left turns, each by an angle in (0, pi): the edge direction then
  // passes angle 0 exactly once per full turn, so counting the wraps gives the winding number.
  std::size_t wraps = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2q& a = c[i];
    const Point2q& b = c[(i + 1) % n];
    const Point2q& d = c[(i + 2) % n];
    const Rational e0x = b.x - a.x, e0y = b.y - a.y, e1x = d.x - b.x, e1y = d.y - b.y;
    if (angle_less(e1x, e1y, e0x, e0y)) ++wraps;
  }
  return wraps == 1;
}

namespace {

// The point of the unit circle whose half-angle tangent is tan(theta / 2) rounded to a multiple of
// 1/N: ((N^2 - p^2), 2 p N) / (N^2 + p^2) with p = round(N tan(theta / 2)), exactly on the circle.
Point2q circle_point(double theta, long N) {
  const long p = std::lround(std::tan(theta / 2.0) * static_cast<double>(N));
  const Integer NN = Integer(N) * N, pp = Integer(p) * p, den = NN + pp;
  return {make_rational(NN - pp, den), make_rational(Integer(2) * p * N, den)};
}

}  // namespace

std::vector<Point2q> canonical_polygon(int genus) {
  if (genus < 1 || genus > 100000)
    throw Error(ErrorKind::InvalidArgument,
                "canonical_polygon: genus must be in 1..100000, got " + std::to_string(genus));
  std::vector<Point2q> corners;
  if (genus == 1) {
    corners = {{Rational(0), Rational(0)}, {Rational(1), Rational(0)}, {Rational(1), Rational(1)},
               {Rational(0), Rational(1)}};
  } else {
    const int g = genus;
    // N: a power of two >= 64 g. tan(theta/2) has derivative >= 1/2, consecutive angles differ
    // by pi/(2g), so consecutive exact tangents differ by >= pi/(4g) > 0.78/g, i.e. by > 50
    // units of 1/N: rounding to multiples of 1/N keeps them strictly increasing.
    long N = 1;
    while (N < 64L * g) N *= 2;
    std::vector<Point2q> quarter(g);
    const double pi = std::acos(-1.0);
    for (int k = 0; k < g; ++k) quarter[k] = circle_point(pi * k / (2.0 * g), N);  // theta in [0, pi/2)
    corners.resize(4 * static_cast<std::size_t>(g));
    for (int k = 0; k < g; ++k) {
      const Point2q& q = quarter[k];
      corners[k] = q;                                   // angle theta_k
      corners[k + g] = Point2q{Rational(-q.y), q.x};    // + 90 degrees, exactly
      corners[k + 2 * g] = Point2q{Rational(-q.x), Rational(-q.y)};
      corners[k + 3 * g] = Point2q{q.y, Rational(-q.x)};
    }
  }
  if (!is_strictly_convex_ccw(corners))
    throw Error(ErrorKind::Internal,
                "canonical_polygon: the polygon for genus " + std::to_string(genus) +
                    " is not strictly convex");
  return corners;
}

std::vector<Point2q> schema_polygon(int n) {
  if (n < 3 || n > 400000)
    throw Error(ErrorKind::InvalidArgument, "schema_polygon: a polygon needs 3 to 400000 corners, got " + std::to_string(n));
  if (n % 4 == 0) return canonical_polygon(n / 4);
  if (n % 2 == 0) {
    // Half the corners at angles in (-pi/2, pi/2), the others their negations (a half turn,
    // exactly). As in canonical_polygon: tan(theta/2) has derivative >= 1/2 there and consecutive
    // angles differ by 2 pi / n, so consecutive exact tangents differ by >= pi / n > 50 units of
    // 1/N (N a power of two >= 16 n): rounding keeps them strictly increasing, and the bit sizes
    // stay those of canonical_polygon (small denominators N^2 + p^2), not those of a full circle.
    long N = 1;
    while (N < 16L * n) N *= 2;
    const int h = n / 2;
    const double pi = std::acos(-1.0);
    std::vector<Point2q> corners(static_cast<std::size_t>(n));
    for (int k = 0; k < h; ++k) {
      corners[k] = circle_point(-pi / 2 + pi * (k + 0.5) / h, N);  // theta in (-pi/2, pi/2)
      corners[k + h] = {Rational(-corners[k].x), Rational(-corners[k].y)};
    }
    if (!is_strictly_convex_ccw(corners))
      throw Error(ErrorKind::Internal, "schema_polygon: the " + std::to_string(n) + "-gon is not strictly convex");
    return corners;
  }
  // Odd n: rational points of the unit circle; 2 bits per doubling of n past 64 keep them apart.
  int bits = 24;
  for (int m = 64; m < n && bits < 60; m *= 2) bits += 2;
  return rational_circle_polygon(n, bits);
}

Point2q polygon_centre(const std::vector<Point2q>& corners) {
  if (corners.empty()) throw Error(ErrorKind::InvalidArgument, "polygon_centre: no corners");
  Rational sx = 0, sy = 0;
  for (const Point2q& p : corners) {
    sx += p.x;
    sy += p.y;
  }
  const Rational n(static_cast<long>(corners.size()));
  return Point2q{Rational(sx / n), Rational(sy / n)};
}

std::vector<Point2q> place_boundary(const std::vector<Point2q>& corners,
                                   const std::vector<int>& side_edge_counts) {
  const std::size_t n = corners.size();
  if (n < 3)
    throw Error(ErrorKind::InvalidArgument, "place_boundary: a polygon needs at least 3 corners");
  if (side_edge_counts.size() != n)
    throw Error(ErrorKind::InvalidArgument,
                "place_boundary: " + std::to_string(side_edge_counts.size()) +
                    " side edge counts for " + std::to_string(n) + " sides");
  std::size_t total = 0;
  for (std::size_t s = 0; s < n; ++s) {
    if (side_edge_counts[s] < 1)
      throw Error(ErrorKind::InvalidArgument,
                  "place_boundary: side " + std::to_string(s) + " has " +
                      std::to_string(side_edge_counts[s]) + " edges (needs >= 1)",
                  {static_cast<std::int64_t>(s)});
    total += static_cast<std::size_t>(side_edge_counts[s]);
  }
  std::vector<Point2q> out;
  out.reserve(total);
  for (std::size_t s = 0; s < n; ++s) {
    const Point2q& a = corners[s];
    const Point2q& b = corners[(s + 1) % n];
    const Rational dx = b.x - a.x, dy = b.y - a.y;
    const int ns = side_edge_counts[s];
    out.push_back(a);
    for (int i = 1; i < ns; ++i) {
      const Rational lambda = make_rational(Integer(i), Integer(ns));
      out.push_back(Point2q{Rational(a.x + lambda * dx), Rational(a.y + lambda * dy)});
    }
  }
  return out;
}

std::vector<Point2q> place_boundary_at(const std::vector<Point2q>& corners,
                                       const std::vector<std::vector<Rational>>& side_params) {
  const std::size_t n = corners.size();
  if (n < 3) throw Error(ErrorKind::InvalidArgument, "place_boundary_at: a polygon needs at least 3 corners");
  if (side_params.size() != n)
    throw Error(ErrorKind::InvalidArgument, "place_boundary_at: " + std::to_string(side_params.size()) +
                                                " parameter lists for " + std::to_string(n) + " sides");
  std::vector<Point2q> out;
  for (std::size_t s = 0; s < n; ++s) {
    const auto& t = side_params[s];
    const auto side = static_cast<std::int64_t>(s);
    if (t.empty() || sgn(t[0]) != 0)
      throw Error(ErrorKind::InvalidArgument, "place_boundary_at: the parameters of side " + std::to_string(s) +
                                                  " do not start at 0",
                  {side});
    for (std::size_t i = 1; i < t.size(); ++i)
      if (t[i] <= t[i - 1] || t[i] >= 1)
        throw Error(ErrorKind::InvalidArgument, "place_boundary_at: the parameters of side " + std::to_string(s) +
                                                    " do not increase strictly below 1",
                    {side});
    const Point2q& a = corners[s];
    const Point2q& b = corners[(s + 1) % n];
    const Rational dx = b.x - a.x, dy = b.y - a.y;
    out.push_back(a);
    for (std::size_t i = 1; i < t.size(); ++i) out.push_back(Point2q{Rational(a.x + t[i] * dx), Rational(a.y + t[i] * dy)});
  }
  return out;
}

std::vector<Rational> arc_length_parameters(const std::vector<double>& lengths, int bits) {
  const std::size_t n = lengths.size();
  if (n < 1) throw Error(ErrorKind::InvalidArgument, "arc_length_parameters: a chain needs at least one edge");
  if (bits < 1 || bits > 52)
    throw Error(ErrorKind::InvalidArgument, "arc_length_parameters: bits must be in 1..52, got " + std::to_string(bits));
  const std::int64_t one = std::int64_t(1) << bits;
  if (static_cast<std::uint64_t>(n) > static_cast<std::uint64_t>(one))
    throw Error(ErrorKind::InvalidArgument, "arc_length_parameters: " + std::to_string(n) +
                                                " edges need more than " + std::to_string(bits) + " bits");
  double total = 0;
  bool usable = true;
  for (double l : lengths) {
    if (!std::isfinite(l) || l < 0) usable = false;
    total += l;
  }
  if (!std::isfinite(total) || total <= 0) usable = false;
  std::vector<std::int64_t> k(n + 1);
  double run = 0;
  for (std::size_t i = 0; i <= n; ++i) {
    const double frac = usable ? run / total : static_cast<double>(i) / static_cast<double>(n);
    k[i] = std::llround(std::ldexp(std::min(1.0, std::max(0.0, frac)), bits));
    if (i < n && usable) run += lengths[i];
  }
  k[0] = 0;
  k[n] = one;
  // Distinct and increasing: up from the start, then down from the end (both bounded by n steps).
  for (std::size_t i = 1; i < n; ++i) k[i] = std::max(k[i], k[i - 1] + 1);
  for (std::size_t i = n - 1; i >= 1; --i) {
    k[i] = std::min(k[i], k[i + 1] - 1);
    if (i == 1) break;
  }
  Integer den;
  mpz_ui_pow_ui(den.get_mpz_t(), 2, static_cast<unsigned long>(bits));
  std::vector<Rational> t(n + 1);
  for (std::size_t i = 0; i <= n; ++i) t[i] = make_rational(Integer(static_cast<long>(k[i])), den);
  return t;
}

std::vector<Point2q> rational_circle_polygon(int n, int bits) {
  if (n < 3 || bits < 1 || bits > 60) throw Error(ErrorKind::InvalidArgument, "rational_circle_polygon: bad arguments");
  std::vector<Point2q> p;
  p.reserve(n);
  const double pi = std::acos(-1.0);
  Integer den;
  mpz_ui_pow_ui(den.get_mpz_t(), 2, static_cast<unsigned long>(bits));
  for (int k = 0; k < n; ++k) {
    const double theta = 2 * pi * (k + 0.5) / n;
    const double s = std::tan(theta / 2);  // an initial guess only; the point is exact below
    const Rational sq = make_rational(Integer(static_cast<long>(std::llround(std::ldexp(s, bits)))), den);
    const Rational s2 = sq * sq;
    p.push_back({Rational((1 - s2) / (1 + s2)), Rational(2 * sq / (1 + s2))});
  }
  if (!is_strictly_convex_ccw(p)) throw Error(ErrorKind::Internal, "rational_circle_polygon: rounding broke convexity");
  return p;
}

}  // namespace igm
