#pragma once
// Certified mixed-precision solve of a sparse symmetric positive definite INTEGER system
// A X = B (two rational right-hand sides, one per UV coordinate), the machinery shared by the
// Tutte embedding (tutte.h) and the orbifold Tutte embedding (orbifold_tutte.h):
//   double solve (sparse Cholesky, one factorization) -> while the caller's exact certificate
//   fails: exact residual B - A X on the dyadic iterate, double correction with the same factor,
//   rounding onto a finer common grid 2^-e -> bound on the steps -> exact rational elimination
//   for small systems. Convergence argument: see exact_refinement.cpp.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

/// The matrix A (n x n, symmetric positive definite, integer entries) and the right-hand side.
struct SpdSystem {
  int n = 0;
  std::vector<int> diag;                  // A_ii
  std::vector<int> xadj, adj, val;        // off-diagonal entries, CSR (row i: xadj[i] .. xadj[i+1]-1)
  std::vector<int> rhs_rows;              // rows with a non-zero right-hand side, strictly ascending
  std::vector<Rational> rhs_x, rhs_y;     // their right-hand sides (same order as rhs_rows)
  /// Largest |coordinate| of the fixed data (e.g. boundary positions): the initial grid is chosen
  /// so that max(this, |double solution|) fits in 52 bits.
  double magnitude = 0;
};

struct RefinementOptions {
  /// Bound on the refinement steps after the double solve (each gains ~53 - log2(cond) bits).
  int max_iterations = 40;
  /// Steps run even if the double solution is already certified. Must be <= max_iterations.
  int min_iterations = 0;
  /// When the bound is hit: systems with at most this many unknowns are solved exactly (sparse
  /// rational elimination); larger ones throw igm::Error(Internal) with the statistics.
  int exact_fallback_max_unknowns = 5000;
};

/// The current iterate, as the certificate sees it.
struct RefinementIterate {
  enum class Mode { Double, Grid, Exact };
  Mode mode = Mode::Double;
  const std::vector<double>* xd = nullptr;      // Double: x_i = xd[i], y_i = yd[i]
  const std::vector<double>* yd = nullptr;
  const std::vector<mpz_class>* X = nullptr;    // Grid: x_i = X[i] 2^-e, y_i = Y[i] 2^-e
  const std::vector<mpz_class>* Y = nullptr;
  std::int64_t e = 0;
  const std::vector<Point2q>* exact = nullptr;  // Exact
  /// The exact value of unknown i in any mode. O(1) GMP operations.
  Point2q point(int i) const;
};

struct RefinementStats {
  std::int64_t flips_double = 0;                   // certificate failures at the double solution
  std::vector<std::int64_t> flips_per_iteration;   // one entry per refinement step
  int iterations = 0;
  std::int64_t grid_exponent = 0;                  // 0 if no step ran
  bool exact_fallback = false;
  std::size_t factor_entries = 0;
  double seconds_factorization = 0, seconds_solve = 0, seconds_refinement = 0, seconds_checks = 0,
         seconds_fallback = 0;
};

/// Names for error messages, e.g. {"tutte_embed", "interior vertices", "the exact Tutte solution"}.
struct RefinementNames {
  std::string who, unknowns, solution;
};

/// Number of certificate failures (e.g. non-positive triangles) at an iterate; 0 = certified.
using RefinementCertificate = std::function<std::int64_t(const RefinementIterate&)>;

/// The certified iterate, in the representation it was certified in (no Rational copy is made:
/// read it with iterate().point(i), or the arrays directly).
struct RefinementResult {
  RefinementIterate::Mode mode = RefinementIterate::Mode::Double;
  std::vector<double> xd, yd;
  std::vector<mpz_class> X, Y;
  std::int64_t e = 0;
  std::vector<Point2q> exact;
  RefinementStats stats;
  RefinementIterate iterate() const {
    RefinementIterate it;
    it.mode = mode;
    it.xd = &xd;
    it.yd = &yd;
    it.X = &X;
    it.Y = &Y;
    it.e = e;
    it.exact = &exact;
    return it;
  }
};

/// Solves A X = B until certificate(iterate) == 0 (and at least min_iterations steps ran), as in
/// the header comment. Pre: system.n >= 1, A symmetric positive definite. Post: certificate(x)
/// == 0 was evaluated on the returned iterate. Throws igm::Error(InvalidArgument) for options with
/// max_iterations < 0 or min_iterations > max_iterations, igm::Error(Internal) (message prefixed by
/// names.who) if A is not numerically positive definite, if the exact solution itself fails the
/// certificate, or if the bound is hit on a system too large for the exact fallback.
/// Cost: sparse Cholesky (O(n^1.5) on planar graphs) plus per step O(nnz) big-integer operations
/// and one certificate evaluation; the fallback O(sum of squared row lengths) rational operations.
RefinementResult refine_until_certified(const SpdSystem& system, const RefinementCertificate& certificate,
                                        const RefinementOptions& options, const RefinementNames& names);

/// Scratch integers for grid_orient (no allocation per call).
struct GridScratch {
  mpz_class p, q, r, s, t1, t2;
};

/// Exact orientation of three points given by integer coordinates (a common grid factor does
/// not change the sign): __int128 when they fit, a double filter with a proven bound, else GMP.
Sign grid_orient(const mpz_class& ax, const mpz_class& ay, const mpz_class& bx, const mpz_class& by,
                 const mpz_class& cx, const mpz_class& cy, GridScratch& scratch);

}  // namespace igm
