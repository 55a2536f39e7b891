#pragma once
// Exact segment-segment relations and intersection points on rational points. Every decision is
// taken by the exact orient2d (filtered) and exact comparisons; points are exact rationals.
#include <optional>

#include "igm/exact/predicates.h"

namespace igm {

/// How two closed segments ab and cd meet, by their intersection set:
///   Disjoint          empty;
///   ProperCrossing    one point, interior to both segments (the segments are not collinear);
///   Touching          one point that is an endpoint of at least one segment (an endpoint on the
///                     other segment's interior, a shared endpoint, collinear segments meeting
///                     end to end, or a degenerate point-segment lying on the other);
///   CollinearOverlap  a segment of positive length (collinear and overlapping).
enum class SegmentRelation { Disjoint, ProperCrossing, Touching, CollinearOverlap };

const char* to_string(SegmentRelation r);

/// Classifies the closed segments ab and cd (degenerate a == b or c == d allowed).
/// Exact: at most four orient2d and a few exact comparisons. Cost O(1) filtered predicates.
SegmentRelation classify(const Point2q& a, const Point2q& b, const Point2q& c, const Point2q& d);

/// True when p lies on the closed segment ab (a == b allowed: then p == a). Exact.
bool on_segment(const Point2q& p, const Point2q& a, const Point2q& b);

/// Lexicographic order (x, then y): Negative if p < q, Zero if p == q. Along a line it orders
/// the points monotonically. Exact.
Sign compare_lex(const Point2q& p, const Point2q& q);

/// Exact intersection point of the supporting lines of ab and cd: a + t (b - a) with
///   t = cross(c - a, d - c) / cross(b - a, d - c).
/// Pre: the lines are not parallel (cross(b - a, d - c) != 0), e.g. classify() returned
/// ProperCrossing; throws igm::Error(InvalidArgument) otherwise. When the segments cross
/// properly, the result lies strictly inside both. Cost: ~20 GMP rational operations; the result
/// has O(bits of the inputs) bits (about 3x the input size for the numerator of t).
Point2q intersection_point(const Point2q& a, const Point2q& b, const Point2q& c, const Point2q& d);

/// The unique common point of the closed segments when their intersection is a single point
/// (ProperCrossing or Touching), nullopt when it is empty or a segment (Disjoint, CollinearOverlap).
std::optional<Point2q> intersection(const Point2q& a, const Point2q& b, const Point2q& c,
                                    const Point2q& d);

}  // namespace igm
