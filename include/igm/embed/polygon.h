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

}  // namespace igm
