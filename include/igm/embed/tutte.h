#pragma once
// Exactly certified Tutte embedding of a triangulated disk onto a convex polygon (paper §4.1;
// Tutte 1963, Floater 2003 "One-to-one piecewise linear mappings over triangulations").
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

struct TutteOptions {
  /// Bound on the mixed-precision refinement steps after the double solve. Each step gains
  /// about 53 - log2(cond) bits of accuracy (see tutte.cpp); 40 steps cover > 800 bits on
  /// meshes with condition numbers up to 2^30.
  int max_iterations = 40;
  /// Refinement steps run even if the double solution is already certified (for measurements,
  /// or to move closer to the exact Tutte solution). Must be <= max_iterations.
  int min_iterations = 0;
  /// When the bound is hit: meshes with at most this many interior vertices are solved exactly
  /// (sparse rational elimination); larger ones throw igm::Error(Internal) with the statistics.
  int exact_fallback_max_interior = 5000;
};

struct TutteStats {
  int interior_vertices = 0;
  int boundary_vertices = 0;
  int triangles = 0;
  /// Triangles whose exact orientation is not positive on the plain double solution (interior
  /// coordinates exactly as the doubles computed, boundary exact).
  std::int64_t flips_double = 0;
  /// Non-positive triangles after each refinement step (one entry per step).
  std::vector<std::int64_t> flips_per_iteration;
  int iterations = 0;
  /// Interior coordinates are (integer) * 2^-grid_exponent after refinement (0 if none ran).
  std::int64_t grid_exponent = 0;
  /// max over all output coordinates of igm::bit_size (numerator + denominator bits).
  std::size_t max_bits = 0;
  bool exact_fallback = false;
  double seconds_validate = 0;       // pre-condition checks (half-edges, fans, boundary, sides)
  double seconds_assemble = 0;       // adjacency, degrees, exact right-hand side
  double seconds_factorization = 0;  // nested dissection + multifrontal sparse Cholesky
  std::size_t factor_entries = 0;    // entries of the Cholesky factor's dense blocks
  double seconds_solve = 0;          // double solve of both coordinates
  double seconds_refinement = 0;     // exact residuals, corrections, exact updates
  double seconds_checks = 0;         // orientation checks of all triangles (every round)
  double seconds_fallback = 0;       // exact rational solve, if used
  double seconds_total = 0;
};

struct TutteResult {
  std::vector<Point2q> uv;  // per vertex, exact; boundary vertices at exactly their given position
  TutteStats stats;
};

/// Tutte embedding with uniform weights: every interior vertex at the mean of its neighbours,
/// the boundary fixed. Solved in double (sparse Cholesky, embed/sparse_cholesky.h, one
/// factorization for both coordinates and all corrections), then refined with exact residuals
/// and double corrections into dyadic coordinates until the EXACT orientation of every triangle
/// is positive (certified with exact predicates before returning); exact rational fallback for
/// small meshes if the iteration bound is hit.
///
/// Input: vertices 0 .. num_vertices-1 (all used), `triangles` consistently oriented
/// (counter-clockwise in the intended embedding), `boundary` the boundary cycle in
/// counter-clockwise order (the order of the boundary half-edges), `boundary_uv[i]` the fixed
/// position of boundary[i]: consecutive positions form a convex polygon traversed once
/// counter-clockwise whose corners turn strictly and whose other vertices lie strictly inside
/// a side, in order.
/// Pre-conditions, checked (igm::Error(InvalidArgument) naming the element): indices in range,
/// no repeated vertex in a triangle, every vertex used, edge-manifold and consistently oriented,
/// one fan per vertex, connected, Euler characteristic 1, exactly one boundary loop equal to
/// `boundary` in this orientation, the boundary polygon as above, no interior edge joining two
/// boundary vertices on one polygon side, no triangle with three vertices on one side.
/// Post: every triangle has exact orientation > 0 (the map is one-to-one, Floater 2003).
/// Cost: O(F log valence) checks, sparse Cholesky of the interior Laplacian (O(n^1.5) on planar
/// meshes), then per refinement step O(F) big-integer operations on numbers of
/// ~grid_exponent bits. Measured (bench/embed_bench.cpp): 100k faces ~0.2-0.4 s CPU, 1M faces a
/// few seconds CPU. Throws igm::Error(Internal) if refinement and fallback fail.
TutteResult tutte_embed(int num_vertices, const std::vector<std::array<int, 3>>& triangles,
                        const std::vector<int>& boundary, const std::vector<Point2q>& boundary_uv,
                        const TutteOptions& options = {});

/// The same with positive integer weights: every interior vertex at the weighted mean of its
/// neighbours. `halfedge_weights` has one entry per half-edge, 3f+i for the edge from corner i to
/// corner i+1 of triangle f; the two half-edges of an interior edge carry the same weight (the
/// system stays symmetric positive definite; boundary half-edges are not used), every weight is
/// >= 1 and each vertex's sum fits an int. Empty: uniform weights. Weights from the 3D geometry:
/// embed/weights.h. Tutte's theorem holds for any positive weights (Floater 2003), so the
/// post-condition is the same. Errors as above, plus InvalidArgument naming the edge for a
/// missing, non-positive or asymmetric weight or a vertex whose weights overflow.
TutteResult tutte_embed(int num_vertices, const std::vector<std::array<int, 3>>& triangles,
                        const std::vector<int>& boundary, const std::vector<Point2q>& boundary_uv,
                        const std::vector<int>& halfedge_weights, const TutteOptions& options = {});

}  // namespace igm
