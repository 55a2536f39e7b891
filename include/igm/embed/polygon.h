#pragma once
// The canonical polygonal schema as a convex polygon with exact rational corners (paper §3, §4.1,
// §5 "Genus 1"), and the placement of the cut disk's boundary vertices on its sides.
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

/// The convex 4g-gon onto which the disk cut along 2g loops is embedded. Corners are rational,
/// counter-clockwise, corner 0 first; side s runs from corner s to corner s+1 (mod 4g).
///  - genus 1: exactly the unit square (0,0), (1,0), (1,1), (0,1): the torus map is then an IGM.
///  - genus g >= 2: rational points ((1-t^2)/(1+t^2), 2t/(1+t^2)) of the unit circle close to a
///    regular 4g-gon, corner 0 = (1,0). The double tan(theta/2) only chooses the rational t (a
///    multiple of 1/N, N a power of two >= 64 g); corner k+g is corner k rotated by exactly 90
///    degrees, so the corners are symmetric and their mean is exactly the origin.
/// Post: strictly convex, checked exactly with orient2d (throws igm::Error(Internal) otherwise).
/// Throws igm::Error(InvalidArgument) for genus < 1 or genus > 100000. Cost O(g) GMP operations;
/// corner bit sizes grow like 4 log2(64 g).
std::vector<Point2q> canonical_polygon(int genus);

/// The convex polygon of a disk with n >= 3 sides: the unit square for n = 4, canonical_polygon(n / 4)
/// for other multiples of 4; for other even n the same construction by half turns (corners on the
/// unit circle from tangents rounded to multiples of 1/N, N a power of two >= 16 n; corner k + n/2
/// is minus corner k, so the mean is exactly the origin; bit sizes as canonical_polygon's); odd n:
/// rational_circle_polygon(n) (near-regular, corners on the unit circle). Strictly convex and
/// counter-clockwise. Throws igm::Error(InvalidArgument) for n < 3 or n > 400000. Cost O(n).
std::vector<Point2q> schema_polygon(int n);

/// The exact centroid (mean) of the corners: a strictly interior point of a strictly convex
/// polygon. (1/2, 1/2) for the unit square, exactly (0, 0) for canonical_polygon(g >= 2).
/// Throws igm::Error(InvalidArgument) if corners is empty.
Point2q polygon_centre(const std::vector<Point2q>& corners);

/// True iff the closed polygon corners[0], corners[1], ... is strictly convex and
/// counter-clockwise: every consecutive triple turns strictly left and the boundary winds
/// exactly once around its interior. Exact (orient2d on rationals). Needs >= 3 corners.
bool is_strictly_convex_ccw(const std::vector<Point2q>& corners);

/// Boundary vertex positions on the polygon: side s (corner s -> corner s+1) receives
/// side_edge_counts[s] = n_s mesh edges, its vertices at the exact parameters i / n_s,
/// i = 0 .. n_s - 1 (the corner itself at i = 0). Returns sum(n_s) points along the boundary
/// cycle, counter-clockwise, starting at corner 0.
/// Seamlessness: in the word a b a^-1 b^-1 side s+2 is traversed backwards, so the vertex at
/// parameter i/n of side s and the one at (n-i)/n of side s+2 (equal counts n) are the two copies
/// of one loop vertex, at the same parameter measured from the corresponding root copies
/// (corner s, resp. corner s+3). Throws igm::Error(InvalidArgument) if the sizes differ, there are
/// fewer than 3 corners or some n_s < 1. Cost O(sum n_s) rational operations.
std::vector<Point2q> place_boundary(const std::vector<Point2q>& corners,
                                   const std::vector<int>& side_edge_counts);

/// Boundary positions at given parameters: side s receives its vertices at
/// corners[s] + t (corners[s+1] - corners[s]) for t in side_params[s], which must start with 0 and
/// increase strictly below 1 (the side's last vertex is the next side's corner). Paired sides get
/// seamless copies when the parameters of one are 1 - t of the other's, reversed. Returns the
/// points along the boundary cycle from corner 0. Throws igm::Error(InvalidArgument) naming the
/// side for parameters that do not start at 0, do not increase strictly or reach 1. Cost O(total).
std::vector<Point2q> place_boundary_at(const std::vector<Point2q>& corners,
                                       const std::vector<std::vector<Rational>>& side_params);

/// Parameters 0 = t_0 < t_1 < ... < t_n = 1 of the vertices of a chain of n >= 1 edges with the
/// given (3D) lengths: t_i is the arc length fraction up to vertex i, rounded to the nearest
/// multiple of 2^-bits (bits in 1..52), then moved up (from t_1 on) or down (back from t_(n-1)) by
/// the least multiples that keep consecutive parameters apart, so that zero-length edges still get
/// distinct parameters. Lengths that are negative, not finite, or sum to zero: uniform i/n.
/// Throws igm::Error(InvalidArgument) if n < 1, bits is out of range or n > 2^bits. Deterministic.
/// Cost O(n).
std::vector<Rational> arc_length_parameters(const std::vector<double>& lengths, int bits = 32);

/// Test and benchmark helper: n corners on the unit circle, exactly rational
/// ((1-s^2)/(1+s^2), 2s/(1+s^2)) with s a dyadic approximation (`bits` fractional bits) of
/// tan(theta_k/2), theta_k = 2 pi (k + 1/2) / n; counter-clockwise, strictly convex (checked).
std::vector<Point2q> rational_circle_polygon(int n, int bits = 24);

}  // namespace igm
