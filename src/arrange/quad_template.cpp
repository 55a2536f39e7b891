#include "igm/arrange/quad_template.h"

#include <cmath>
#include <map>
#include <string>

#include "igm/core/error.h"

namespace igm {

namespace {

Point2q affine(const Point2q& a, const Point2q& b, const Point2q& c, const Rational& wa, const Rational& wb,
               const Rational& wc) {
  return {wa * a.x + wb * b.x + wc * c.x, wa * a.y + wb * b.y + wc * c.y};
}

Point2q uv(int x, int y) { return {Rational(x), Rational(y)}; }

// Strictly convex counter-clockwise polygon (every turn strictly left, winding once).
bool strictly_convex_ccw(const std::vector<Point2q>& p) {
  const int n = static_cast<int>(p.size());
  int entries = 0;
  auto upper = [&](int a, int b) {
    const Sign sy = sign(Rational(p[b].y - p[a].y));
    return sy == Sign::Positive || (sy == Sign::Zero && sign(Rational(p[b].x - p[a].x)) == Sign::Positive);
  };
  for (int k = 0; k < n; ++k) {
    const int a = k, b = (k + 1) % n, c = (k + 2) % n;
    if (orient2d(p[a], p[b], p[c]) != Sign::Positive) return false;
    if (!upper(a, b) && upper(b, c)) ++entries;
  }
  return entries == 1;
}

}  // namespace

QuadTemplate make_quad_template(const std::vector<Point2q>& corners, const Point2q& centre) {
  const int n = static_cast<int>(corners.size());
  if (n < 4 || n % 4 != 0)
    throw Error(ErrorKind::InvalidArgument, "quad template: the polygon needs 4g corners (g >= 1), got " + std::to_string(n));
  if (!strictly_convex_ccw(corners))
    throw Error(ErrorKind::InvalidArgument, "quad template: the polygon is not strictly convex and counter-clockwise");
  for (int k = 0; k < n; ++k)
    if (orient2d(corners[k], corners[(k + 1) % n], centre) != Sign::Positive)
      throw Error(ErrorKind::InvalidArgument, "quad template: the centre is not strictly inside the polygon (side " +
                                                  std::to_string(k) + ")",
                  {k});
  QuadTemplate t;
  t.genus = n / 4;
  t.points = corners;
  t.layout_vertex.assign(n, 0);
  if (t.genus == 1) {
    t.quads.push_back({0, 1, 2, 3});
    for (int s = 0; s < 4; ++s) t.side_quad.push_back({0, s});
  } else {
    t.points.push_back(centre);
    t.layout_vertex.push_back(1);
    const int C = n;
    for (int i = 0; i < t.genus; ++i) {
      const Point2q &P1 = corners[4 * i + 1], &P2 = corners[4 * i + 2], &P3 = corners[4 * i + 3];
      const Rational third(1, 3);
      t.points.push_back(affine(P1, P2, centre, third, third, third));                      // A0
      t.points.push_back(affine(P2, centre, centre, Rational(5, 6), Rational(1, 6), Rational(0)));  // A1
      t.points.push_back(affine(P2, P3, centre, third, third, third));                      // A2
      for (int j = 0; j < 3; ++j) t.layout_vertex.push_back(2 + 3 * i + j);
      const int p0 = 4 * i, p1 = p0 + 1, p2 = p0 + 2, p3 = p0 + 3, p4 = (p0 + 4) % n;
      const int a0 = n + 1 + 3 * i, a1 = a0 + 1, a2 = a0 + 2;
      t.quads.push_back({p0, p1, a0, C});
      t.quads.push_back({p1, p2, a1, a0});
      t.quads.push_back({p2, p3, a2, a1});
      t.quads.push_back({p3, p4, C, a2});
      t.quads.push_back({a0, a1, a2, C});
      for (int s = 0; s < 4; ++s) t.side_quad.push_back({5 * i + s, 0});
    }
  }
  for (std::size_t q = 0; q < t.quads.size(); ++q) {
    const auto& Q = t.quads[q];
    for (int i = 0; i < 4; ++i)
      if (orient2d(t.points[Q[i]], t.points[Q[(i + 1) % 4]], t.points[Q[(i + 2) % 4]]) != Sign::Positive)
        throw Error(ErrorKind::Internal, "quad template: quad " + std::to_string(q) + " is not strictly convex for genus " +
                                             std::to_string(t.genus),
                    {static_cast<std::int64_t>(q)});
    const Point2q &a = t.points[Q[0]], &b = t.points[Q[1]], &c = t.points[Q[2]], &d = t.points[Q[3]];
    if (a.x + c.x == b.x + d.x && a.y + c.y == b.y + d.y) {
      t.diagonal.push_back(-1);
    } else {
      t.diagonal.push_back(cmp(dot(a, c, c), dot(b, d, d)) <= 0 ? 0 : 1);
    }
  }
  return t;
}

std::vector<TemplateRegion> template_regions(const QuadTemplate& t) {
  std::vector<TemplateRegion> r;
  for (std::size_t q = 0; q < t.quads.size(); ++q) {
    const auto& Q = t.quads[q];
    const int qi = static_cast<int>(q);
    if (t.diagonal[q] == 0) {
      r.push_back({qi, {Q[0], Q[1], Q[2]}, {uv(0, 0), uv(1, 0), uv(1, 1)}});
      r.push_back({qi, {Q[0], Q[2], Q[3]}, {uv(0, 0), uv(1, 1), uv(0, 1)}});
    } else if (t.diagonal[q] == 1) {
      r.push_back({qi, {Q[0], Q[1], Q[3]}, {uv(0, 0), uv(1, 0), uv(0, 1)}});
      r.push_back({qi, {Q[1], Q[2], Q[3]}, {uv(1, 0), uv(1, 1), uv(0, 1)}});
    } else {
      r.push_back({qi, {Q[0], Q[1], Q[2], Q[3]}, {uv(0, 0), uv(1, 0), uv(1, 1), uv(0, 1)}});
    }
  }
  return r;
}

std::vector<TemplateSegment> template_segments(const QuadTemplate& t) {
  const auto regions = template_regions(t);
  std::vector<TemplateSegment> segs;
  std::map<std::pair<int, int>, int> index;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const auto& c = regions[r].corners;
    const int k = static_cast<int>(c.size());
    for (int i = 0; i < k; ++i) {
      const int a = c[i], b = c[(i + 1) % k];
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = index.find(key);
      if (it == index.end()) {
        index.emplace(key, static_cast<int>(segs.size()));
        TemplateSegment s;
        s.a = a, s.b = b, s.left = static_cast<int>(r);
        // A diagonal joins opposite corners of the region's quad.
        const auto& Q = t.quads[regions[r].quad];
        int ia = 0, ib = 0;
        for (int j = 0; j < 4; ++j) {
          if (Q[j] == a) ia = j;
          if (Q[j] == b) ib = j;
        }
        s.diagonal = (ia - ib + 4) % 4 == 2;
        segs.push_back(s);
      } else {
        TemplateSegment& s = segs[it->second];
        if (s.a != b || s.b != a || s.right >= 0)
          throw Error(ErrorKind::Internal, "quad template: a template edge is not shared by two regions consistently");
        s.right = static_cast<int>(r);
      }
    }
  }
  return segs;
}

std::vector<Segment2> template_geometry(const QuadTemplate& t, const std::vector<TemplateSegment>& segments) {
  std::vector<Segment2> g;
  g.reserve(segments.size());
  for (const auto& s : segments) g.push_back({t.points[s.a], t.points[s.b]});
  return g;
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
  if (!strictly_convex_ccw(p)) throw Error(ErrorKind::Internal, "rational_circle_polygon: rounding broke convexity");
  return p;
}

}  // namespace igm
