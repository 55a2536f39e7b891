#pragma once
// Sparse Cholesky factorization A = L L^T of a symmetric positive definite matrix in double, for
// the Tutte embeddings (their double solve and every exact-refinement correction) and the Newton
// systems of smoothing. Only approximate solutions come out of here: nothing decides anything
// geometric from them; but every bit of them is reproducible (below), because the smoothing's
// trajectory and the refinement's dyadic iterates depend on every one.
//
// SuiteSparse's CHOLMOD does the analysis: a fill-reducing order (METIS nested dissection, or AMD
// for small systems; computed on the graph of groups when the unknowns come in groups, e.g. the
// two coordinates of a vertex), the elimination tree and, where CHOLMOD's rule (flops / nnz(L) >=
// 40) calls for it, the supernodes with their row structure. Small systems are then factorized by
// CHOLMOD's simplicial LDL^T (no BLAS). Supernodal ones are factorized here, multifrontally over
// CHOLMOD's supernodes, with Eigen's dense kernels on blocks of at most kDenseBlock columns,
// independent subtrees and the column blocks of large fronts in parallel (oneTBB, in the caller's
// task arena: igm/core/threads.h). Not by CHOLMOD's own supernodal factorization: that calls the
// machine's BLAS (OpenBLAS, MKL: kernels dispatched by CPU and split by thread count, so the
// rounding changes from machine to machine), and with Debian's reference BLAS it was 4x slower
// (bench/README.md, "Sparse Cholesky").
//
// Reproducibility: every floating-point operation is fixed by the matrix, its pattern and the
// compiled code, not by the thread count, the scheduling or the machine: each front sums its
// children in a fixed order; parallel work only splits into independent blocks of fixed size;
// every Eigen product has an inner dimension of at most kDenseBlock, below the smallest k-blocking
// Eigen derives from any L1 cache size (>= 200 for L1 >= 16 KB), so its run-time cache query does
// not change a sum's order either.
#include <Eigen/Dense>
#include <cstddef>
#include <memory>
#include <vector>

namespace igm {

struct SparseCholeskyStats {
  int n = 0;
  bool supernodal = false;     // this file's multifrontal factorization, else CHOLMOD's simplicial
  bool metis = false;          // METIS ordering, else AMD
  std::size_t factor_entries = 0;  // stored entries of L (supernodal: with its dense blocks)
  double flops = 0;            // of one numeric factorization (CHOLMOD's count)
  int supernodes = 0;
  int max_front = 0;           // largest frontal matrix dimension (supernodal)
  double seconds_analyze = 0;  // ordering and symbolic analysis
  double seconds_factorize = 0;  // the last numeric factorization
};

class SparseCholesky {
 public:
  /// Dense blocks: the widest panel any dense product works on (see above).
  static constexpr int kDenseBlock = 128;
  /// The fill-reducing order: METIS (nested dissection: the least fill on surfaces, but the dearer
  /// analysis) or AMD (minimum degree: a cheap analysis, more fill); Automatic: METIS from
  /// kMetisMinUnknowns unknowns on. Measured in bench/README.md ("Sparse Cholesky"): systems
  /// factorized once (the Tutte maps) are fastest with AMD, the Newton systems that smoothing
  /// factorizes at every iteration with METIS once they are large.
  /// LevelSets: nested dissection by BFS level sets (the project's own, O(n log n)): on a disk's
  /// Laplacian (the Tutte maps) as little fill as METIS for a fraction of its time; on surfaces with
  /// handles its level sets wrap around them (bad fronts). Ignores groups.
  enum class Ordering { Automatic, Metis, Amd, LevelSets };
  static constexpr int kMetisMinUnknowns = 20000;

  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  /// Analysis of the n x n pattern: off-diagonal entries in CSR form (row i has columns
  /// adj[xadj[i] .. xadj[i+1]-1]), symmetric (j in row i iff i in row j), no diagonal entries (the
  /// diagonal is always present). `group` (empty, or one id >= 0 per unknown, the ids 0..G-1 all
  /// used): unknowns of one group are ordered together, the order computed on the graph of groups.
  /// Throws igm::Error(InvalidArgument) on malformed input. Cost: the ordering (METIS about
  /// O(n log n)) and the symbolic factorization, O(nnz(L)).
  void analyze(const std::vector<int>& xadj, const std::vector<int>& adj, const std::vector<int>& group = {},
               Ordering ordering = Ordering::Automatic);

  /// Numeric factorization of the analyzed pattern with off-diagonal values `val` (aligned with
  /// adj, symmetric) and diagonal `diag`. False if the matrix is not numerically positive definite
  /// (then solve() must not be called). Pre: analyze() ran. Cost: flops() operations.
  bool factorize_numeric(const std::vector<double>& val, const std::vector<double>& diag);

  /// analyze() then factorize_numeric(); throws igm::Error(InvalidArgument) on malformed input,
  /// igm::Error(Internal) if the matrix is not numerically positive definite.
  void factorize(const std::vector<int>& xadj, const std::vector<int>& adj, const std::vector<double>& val,
                 const std::vector<double>& diag, Ordering ordering = Ordering::Automatic);

  /// Solves A X = B in place for the n x k matrix B (several right-hand sides share the factor).
  /// Pre: a successful factorization. Cost O(k * factor_entries()).
  void solve(Eigen::MatrixXd& b) const;

  /// Frees the numeric factor of a supernodal factorization (most of its memory), keeping the
  /// analysis: factorize_numeric() is needed again before solve(). No effect on a simplicial one.
  void release_numeric();

  int size() const { return stats_.n; }
  std::size_t factor_entries() const { return stats_.factor_entries; }
  int max_front() const { return stats_.max_front; }
  const SparseCholeskyStats& stats() const { return stats_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  SparseCholeskyStats stats_;
};

}  // namespace igm
