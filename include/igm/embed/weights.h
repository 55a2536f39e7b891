#pragma once
// Positive symmetric integer edge weights of a triangulated disk from its 3D geometry, for the
// weighted Tutte maps of embed/tutte.h (the whole disk, and each layout quad's patch).
#include <array>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

enum class WeightKind {
  Uniform,    // every edge 1: Tutte's barycentric map, blind to the geometry
  Cotan,      // cot(alpha) + cot(beta) (the discrete harmonic map, Pinkall & Polthier 1993),
              // clamped into [median / 2^8, median * 2^8] so that it stays positive
  MeanValue,  // Floater's mean value weights (tan(a/2) + tan(b/2)) / |e| from both ends, summed
              // (symmetrized: the system stays symmetric positive definite), clamped alike
};

/// "uniform", "cotan", "mean-value".
const char* to_string(WeightKind kind);

/// One weight per half-edge (3f+i: the edge from corner i to corner i+1 of triangle f), equal on
/// both half-edges of an edge, every weight an integer in [1, 2^16]: the real weights w_e of
/// `kind` are clamped into [m 2^-8, m 2^8] (m: the median of the finite positive w_e; 1 if none),
/// divided by m 2^-8 and rounded. A triangle whose 3D area is zero (coincident or collinear
/// corners, or not finite) contributes nothing; an edge left without a finite positive weight gets
/// the clamp's lower end, never zero or a NaN, so hostile geometry still gives positive weights.
/// Pre: triangles index positions (checked: InvalidArgument). Cost O(F log F).
std::vector<int> edge_weights(const std::vector<Vec3d>& positions, const std::vector<std::array<int, 3>>& triangles,
                              WeightKind kind);

}  // namespace igm
