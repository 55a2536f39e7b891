#pragma once
// Synthetic triangulated convex polygons with exact rational coordinates, for the tests and
// benchmarks of arrange/igm/extract: a fan from a centre refined by 1-to-4 midpoint
// subdivision (so template segments run through vertices and along edges), random interior
// face splits, and random exact perturbations of interior vertices (generic crossings).
#include <cstdint>
#include <vector>

#include "igm/arrange/planar_walk.h"

namespace igm {

struct SyntheticDiskOptions {
  int subdivisions = 2;        // 1-to-4 midpoint refinements of the fan (triangles x4 each)
  int insertions = 0;          // random interior points inserted by face splits
  double perturb = 0.0;        // probability that an interior vertex is moved (0..1)
  std::uint64_t seed = 1;      // deterministic
};

/// The polygon `corners` (strictly convex, ccw) fanned from `centre` (strictly inside), then
/// refined as requested. Vertices 0..n-1 are the corners, n is the centre (unless perturbed,
/// it stays at `centre`). Every triangle strictly positive (perturbations are accepted only
/// after an exact check of the moved vertex's triangles). Boundary vertices stay on the
/// polygon's sides. Cost O(n 4^subdivisions + insertions * 1 + perturbed * valence).
/// Throws InvalidArgument on bad options (subdivisions > 12, negative counts).
PlanarTriangulation make_synthetic_disk(const std::vector<Point2q>& corners, const Point2q& centre,
                                        const SyntheticDiskOptions& options);

}  // namespace igm
