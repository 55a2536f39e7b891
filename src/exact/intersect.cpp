#include "igm/exact/intersect.h"

#include "igm/core/error.h"

namespace igm {

namespace {

bool same(const Point2q& p, const Point2q& q) { return p.x == q.x && p.y == q.y; }

const Point2q& lex_min(const Point2q& p, const Point2q& q) { return compare_lex(p, q) == Sign::Positive ? q : p; }
const Point2q& lex_max(const Point2q& p, const Point2q& q) { return compare_lex(p, q) == Sign::Positive ? p : q; }

// Collinear case (all four points on one line, a != b, c != d): the intersection of the two
// lexicographic ranges [lo, hi]; returns compare_lex(lo, hi).
Sign collinear_overlap(const Point2q& a, const Point2q& b, const Point2q& c, const Point2q& d) {
  const Point2q& s1 = lex_min(a, b);
  const Point2q& e1 = lex_max(a, b);
  const Point2q& s2 = lex_min(c, d);
  const Point2q& e2 = lex_max(c, d);
  const Point2q& lo = lex_max(s1, s2);
  const Point2q& hi = lex_min(e1, e2);
  return compare_lex(lo, hi);
}

}  // namespace

const char* to_string(SegmentRelation r) {
  switch (r) {
    case SegmentRelation::Disjoint: return "disjoint";
    case SegmentRelation::ProperCrossing: return "proper_crossing";
    case SegmentRelation::Touching: return "touching";
    case SegmentRelation::CollinearOverlap: return "collinear_overlap";
  }
  return "unknown";
}

Sign compare_lex(const Point2q& p, const Point2q& q) {
  const Sign sx = compare(p.x, q.x);
  return sx != Sign::Zero ? sx : compare(p.y, q.y);
}

bool on_segment(const Point2q& p, const Point2q& a, const Point2q& b) {
  if (orient2d(a, b, p) != Sign::Zero) return false;
  // p on the line ab (or a == b): inside iff between a and b lexicographically.
  return compare_lex(lex_min(a, b), p) != Sign::Positive && compare_lex(p, lex_max(a, b)) != Sign::Positive;
}

SegmentRelation classify(const Point2q& a, const Point2q& b, const Point2q& c, const Point2q& d) {
  const bool ab_point = same(a, b), cd_point = same(c, d);
  if (ab_point || cd_point) {
    if (ab_point && cd_point) return same(a, c) ? SegmentRelation::Touching : SegmentRelation::Disjoint;
    if (ab_point) return on_segment(a, c, d) ? SegmentRelation::Touching : SegmentRelation::Disjoint;
    return on_segment(c, a, b) ? SegmentRelation::Touching : SegmentRelation::Disjoint;
  }
  const Sign o1 = orient2d(a, b, c), o2 = orient2d(a, b, d);
  if (o1 == Sign::Zero && o2 == Sign::Zero) {  // c, d on the line ab: all four collinear
    const Sign s = collinear_overlap(a, b, c, d);
    return s == Sign::Negative ? SegmentRelation::CollinearOverlap
                               : (s == Sign::Zero ? SegmentRelation::Touching : SegmentRelation::Disjoint);
  }
  if (o1 == o2) return SegmentRelation::Disjoint;  // c, d strictly on the same side of line ab
  const Sign o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (o3 == o4) return SegmentRelation::Disjoint;  // not both zero: lines ab and cd differ
  // Now c, d are not strictly on one side of line ab, nor a, b of line cd, and the lines are
  // distinct: the segments meet in the single point where the lines meet.
  if (o1 != Sign::Zero && o2 != Sign::Zero && o3 != Sign::Zero && o4 != Sign::Zero)
    return SegmentRelation::ProperCrossing;
  return SegmentRelation::Touching;
}

Point2q intersection_point(const Point2q& a, const Point2q& b, const Point2q& c, const Point2q& d) {
  const Rational ux = b.x - a.x, uy = b.y - a.y;  // b - a
  const Rational vx = d.x - c.x, vy = d.y - c.y;  // d - c
  const Rational den = ux * vy - uy * vx;
  if (sgn(den) == 0)
    throw Error(ErrorKind::InvalidArgument, "intersection_point: the supporting lines are parallel");
  const Rational wx = c.x - a.x, wy = c.y - a.y;  // c - a
  const Rational t = (wx * vy - wy * vx) / den;
  return Point2q{Rational(a.x + t * ux), Rational(a.y + t * uy)};
}

std::optional<Point2q> intersection(const Point2q& a, const Point2q& b, const Point2q& c, const Point2q& d) {
  switch (classify(a, b, c, d)) {
    case SegmentRelation::Disjoint:
    case SegmentRelation::CollinearOverlap:
      return std::nullopt;
    case SegmentRelation::ProperCrossing:
      return intersection_point(a, b, c, d);
    case SegmentRelation::Touching:
      break;
  }
  // Touching: the common point is an endpoint. Degenerate segments first.
  if (same(a, b)) return a;
  if (same(c, d)) return c;
  for (const Point2q* p : {&c, &d})
    if (on_segment(*p, a, b)) return *p;
  for (const Point2q* p : {&a, &b})
    if (on_segment(*p, c, d)) return *p;
  throw Error(ErrorKind::Internal, "intersection: touching segments without a common endpoint");
}

}  // namespace igm
