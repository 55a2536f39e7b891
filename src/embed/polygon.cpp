#include "igm/embed/polygon.h"

#include <cmath>
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
    const Integer NN = Integer(N) * N;
    std::vector<Point2q> quarter(g);
    const double pi = std::acos(-1.0);
    for (int k = 0; k < g; ++k) {
      const double theta = pi * k / (2.0 * g);  // in [0, pi/2)
      const long p = std::lround(std::tan(theta / 2.0) * static_cast<double>(N));
      const Integer pp = Integer(p) * p;
      const Integer den = NN + pp;
      quarter[k].x = make_rational(NN - pp, den);
      quarter[k].y = make_rational(Integer(2) * p * N, den);
    }
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

}  // namespace igm
