#pragma once
// Internal to the field stage (cross_field.cpp, cone_pairs.cpp): the connection Laplacian and
// its factorization. Not installed, not part of the API.
#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>

#include <chrono>
#include <complex>
#include <vector>

#include "igm/embed/sparse_cholesky.h"
#include "igm/field/cross_field.h"

namespace igm::field_internal {

using Complex = std::complex<double>;
using SpMat = Eigen::SparseMatrix<Complex>;
using Vec = Eigen::VectorXcd;
using Clock = std::chrono::steady_clock;

inline double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// The smoothness energy on the dual graph (Knoeppel et al. 2013, face-based):
/// E(u) = sum over interior edges of w_e |u_g - exp(4 i rho_h) u_f|^2 (h the edge's half-edge
/// in f, g = face(twin h)), w_e = |e| / d_e, |e| and d_e (the distance between the two faces'
/// centroids) each at least 1e-3 mean edge lengths, so that every interior edge couples its
/// faces (w_e > 0: the dual graph of a connected surface stays connected where edges have length
/// 0), and the mass M = diag(face area, at least 1e-6 of the mean face area). Measured: cone
/// counts do not depend on the weights (|e| / d_e, 1, or |e|^2 / (A_f + A_g) give the same
/// counts within 10 %, docs/field.md).
struct System {
  SpMat A;                      // F x F, Hermitian, both triangles stored
  std::vector<double> mass;     // per face
  std::vector<double> weight;   // per half-edge: w_e (0 on a boundary half-edge)
  double mean_edge = 0;         // mean edge length (every edge once)
  double total_area = 0;
};

System build_system(const TriMesh& mesh, const std::vector<Vec3d>& positions, const FaceFrames& frames);

/// Mean edge length, every edge (interior or boundary) once.
double mean_edge_length(const TriMesh& mesh, const std::vector<Vec3d>& positions);

/// Sparse LDL^T factorization of a symmetric / Hermitian positive definite matrix (the lower
/// triangle is read) by CHOLMOD in its simplicial mode: no BLAS call, so the same bits on any
/// machine, BLAS library and thread count (the supernodal mode's depend on the BLAS). Ordering:
/// AMD, and METIS nested dissection above kMetisAbove unknowns (fewer flops on large surfaces;
/// METIS seeds its own generator: deterministic), AMD again if METIS is unavailable. CHOLMOD
/// prints nothing (print level 0).
constexpr int kMetisAbove = 200000;

template <class Scalar>
class Factor {
 public:
  using Matrix = Eigen::SparseMatrix<Scalar>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  Factor() {
    chol_.setMode(Eigen::CholmodLDLt);
    chol_.cholmod().print = 0;
  }
  /// Factorizes m; adds the wall time to `seconds`. Throws igm::Error(Internal) if the matrix
  /// is not numerically positive definite.
  void compute(const Matrix& m, double& seconds) {
    const auto t0 = Clock::now();
    bool ok = false;
    if (m.rows() > kMetisAbove) {
      chol_.cholmod().nmethods = 1;
      chol_.cholmod().method[0].ordering = CHOLMOD_METIS;
      chol_.compute(m);
      ok = chol_.info() == Eigen::Success;
    }
    if (!ok) {
      chol_.cholmod().nmethods = 1;
      chol_.cholmod().method[0].ordering = CHOLMOD_AMD;
      chol_.compute(m);
      ok = chol_.info() == Eigen::Success;
    }
    seconds += since(t0);
    if (!ok) fail();
  }
  Vector solve(const Vector& b) const { return chol_.solve(b); }

 private:
  [[noreturn]] static void fail();
  Eigen::CholmodDecomposition<Matrix, Eigen::Lower> chol_;
};

/// Every matrix the field stage factorizes gets kRegularization times its diagonal added to its
/// diagonal. A's rows are weakly diagonally dominant (A_ff = sum of w_e = sum of |A_fg| over all
/// neighbours), so the sum is strictly dominant row by row: its LDL^T pivots are at least that
/// excess (a Schur complement of a diagonally dominant matrix stays dominant, growth <= 2),
/// about 10^4 times the elimination's rounding even for a 1M-face mesh, so CHOLMOD never meets a
/// non-positive pivot, whatever the geometry (zero-length edges, zero-area faces, weights
/// 10^6 apart). Solutions move by about 1e-9 relative.
inline constexpr double kRegularization = 1e-9;

/// The diagonal entry every factorized form of the system gives face f: A_ff (real, `a_ff`)
/// times 1 + kRegularization plus shift * M_ff; the face's mass where that is not positive (a
/// face with no interior edge). restricted() and LargeFactor share it.
inline double regularized_diagonal(const System& sys, int f, double a_ff, double shift) {
  const double d = a_ff * (1 + kRegularization) + shift * sys.mass[f];
  return d > 0 ? d : sys.mass[f];
}

/// The submatrix of sys.A on `free_faces` (slot: face -> its row, or -1) plus shift * M plus
/// kRegularization * diag(A) (a row whose diagonal would be 0, a face with no interior edge: its
/// mass instead).
SpMat restricted(const System& sys, const std::vector<int>& free_faces, const std::vector<int>& slot, double shift);

/// The field's system above CrossFieldOptions::real_form_above faces: the real symmetric form [[Re, -Im], [Im, Re]] of
/// restricted(sys, free faces, shift) written on every face (2F unknowns, the two parts of a face
/// ordered together; a face that is not free is decoupled: identity row and column), factorized
/// by embed/sparse_cholesky.h (METIS ordering, supernodal on Eigen's dense kernels: the same bits
/// for any thread count). Its analysis depends only on the pattern of sys.A, i.e. on the mesh, so
/// it is kept between factorizations (CrossFieldCache: the pipeline's rounds change the
/// constraints and the shift, not the mesh) and done again only when the pattern differs. The
/// results do not depend on whether the analysis was kept. Measured against CHOLMOD's simplicial
/// complex factorization in bench/README.md ("Issue 44, stop 55").
class LargeFactor {
 public:
  /// slot: face -> its free index, or -1 (not free). Adds the wall time to `seconds`. Throws
  /// igm::Error(Internal) if the matrix is not numerically positive definite.
  void factorize(const System& sys, const std::vector<int>& slot, double shift, double& seconds);
  /// x over every face for b over every face (a face that is not free: x = b).
  Vec solve(const Vec& b) const;
  /// Frees the numeric factor, keeping the analysis.
  void release() { chol_.release_numeric(); }
  int analyses() const { return analyses_; }

 private:
  std::vector<int> xadj_, adj_, group_;
  SparseCholesky chol_;
  bool analyzed_ = false;
  int analyses_ = 0;
};

/// The cone cleanup of CrossFieldOptions (remove_close_pairs, split_valence2, split_valence6;
/// cone_pairs.cpp). `fixed` marks the boundary-constrained faces. Updates theta, periods,
/// valences, cones, close_pairs and the cleanup stats.
void clean_cones(const TriMesh& mesh, const std::vector<Vec3d>& positions, const System& sys,
                 const std::vector<char>& fixed, const CrossFieldOptions& options, CrossField& field);

}  // namespace igm::field_internal
