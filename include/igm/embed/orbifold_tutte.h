#pragma once
// Orbifold Tutte embedding of a sphere cut along a path through four cones onto the (2,2,2,2)
// "pillowcase" orbifold (Aigerman & Lipman, "Orbifold Tutte Embeddings", SIGGRAPH Asia 2015;
// paper §5), certified exactly.
//
// The disk of topology/sphere_cut.h is mapped with its cone copies fixed at
//   A = (1,0), B1 = (2,0), C1 = (2,1), D = (1,1), C2 = (0,1), B2 = (0,0)
// (the fundamental domain is a deformed [0,2] x [0,1], area 2). The two copies of a path vertex
// are related by x -> s x + t (s = +-1 for both coordinates, t integer):
//   leg A-B: p2 = (2,0) - p1 (rotation by pi about A)   leg B-C: p2 = p1 - (2,0)
//   leg C-D: p2 = (2,2) - p1 (rotation by pi about D)
// Unknowns: one point per non-cone surface vertex (copy 1 for path vertices); copy 2 is s x + t
// of it, exact by construction. Energy: sum over surface edges of |X_a - X_b|^2 in one disk copy
// of the edge (uniform weights), minimized where every vertex is the mean of its neighbours in
// its own chart. Its matrix is integer, symmetric, positive definite (cones fixed), the same for
// both coordinates; solved and refined by embed/exact_refinement.h until the exact orientation
// of every disk triangle is positive. Aigerman & Lipman prove the exact minimizer is a bijection
// onto the orbifold for positive weights, so the refinement terminates.
#include <array>
#include <vector>

#include "igm/embed/exact_refinement.h"
#include "igm/topology/sphere_cut.h"

namespace igm {

/// x -> s x + (tx, ty).
struct PillowcaseMap {
  int s = 1, tx = 0, ty = 0;
};

/// The transition from copy 1 to copy 2 of a vertex inside leg 0 (A-B), 1 (B-C) or 2 (C-D).
PillowcaseMap pillowcase_transition(int leg);

/// The fixed position of boundary corner i (0..5: A, B1, C1, D, C2, B2).
std::array<int, 2> pillowcase_corner(int i);

struct OrbifoldTutteStats {
  int free_vertices = 0;     // unknowns (non-cone surface vertices)
  int triangles = 0;
  RefinementStats refinement;
  std::size_t max_bits = 0;  // max bit_size of a UV coordinate
  double seconds_assemble = 0, seconds_total = 0;
};

struct OrbifoldTutteResult {
  std::vector<Point2q> uv;  // per disk vertex of the cut, exact
  OrbifoldTutteStats stats;
};

/// The certified embedding of cut.disk_triangles (see above). Post: every disk triangle has exact
/// orientation > 0; the cone copies are at their corners; copy 2 of every path vertex is exactly
/// the leg's transition of copy 1. Throws igm::Error(Internal) if the refinement and its exact
/// fallback fail, igm::Error(InvalidArgument) on a malformed cut (a cone not a path vertex, two
/// adjacent cones). Cost: sparse Cholesky of the free-vertex Laplacian plus the refinement steps.
OrbifoldTutteResult orbifold_tutte_embed(const SphereCut& cut, const RefinementOptions& options = {});

/// The same with positive symmetric integer weights on the surface's edges (one per half-edge of
/// cut.surface.mesh, equal on an edge's two halves, >= 1; embed/weights.h): every free vertex at the
/// weighted mean of its neighbours' lifts. The system stays symmetric positive definite; Aigerman &
/// Lipman's bijectivity argument holds for positive symmetric weights. Empty: uniform weights.
/// Throws igm::Error(InvalidArgument) naming the edge for a missing, non-positive or asymmetric weight.
OrbifoldTutteResult orbifold_tutte_embed(const SphereCut& cut, const std::vector<int>& halfedge_weights,
                                         const RefinementOptions& options);

}  // namespace igm
