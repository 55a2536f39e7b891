#pragma once
// Sparse Cholesky factorization A = L L^T of a symmetric positive definite matrix in double:
// nested-dissection ordering (BFS level-set separators) and a multifrontal factorization with
// dense frontal matrices (Eigen dense kernels). Used by the Tutte embedding for the double solve
// and for every correction of the exact refinement; on planar meshes the work is O(n^1.5) and
// the factor O(n log n) entries. Only approximate solutions come out of here: nothing decides
// anything geometric from them.
#include <Eigen/Dense>
#include <cstddef>
#include <vector>

namespace igm {

class SparseCholesky {
 public:
  /// Factorizes the n x n matrix with diagonal `diag` and off-diagonal entries in CSR form:
  /// row i has entries val[k] in columns adj[k], k in xadj[i] .. xadj[i+1]-1. Pre: symmetric
  /// (entry (i,j) present iff (j,i) is, equal values), no diagonal entries in adj. Throws
  /// igm::Error(InvalidArgument) on malformed input, igm::Error(Internal) if a pivot is not
  /// positive (the matrix is not numerically positive definite).
  void factorize(const std::vector<int>& xadj, const std::vector<int>& adj,
                 const std::vector<double>& val, const std::vector<double>& diag);

  /// Solves A X = B in place for the n x k matrix B (several right-hand sides share the factor).
  /// Cost O(k * factor_entries()).
  void solve(Eigen::MatrixXd& b) const;

  int size() const { return n_; }
  /// Stored entries of the dense blocks of L (a measure of fill).
  std::size_t factor_entries() const { return entries_; }
  /// Largest frontal matrix dimension (the top separator plus its border).
  int max_front() const { return max_front_; }

 private:
  struct Node {
    int s0 = 0, s1 = 0;        // positions of its pivots (its separator) in elimination order
    std::vector<int> border;   // positions > s1-1 coupled to the separator (sorted)
    Eigen::MatrixXd L;         // (k + border) x k: [L11; L21]
  };
  int n_ = 0;
  std::vector<int> order_;     // order_[p] = original index eliminated at position p
  std::vector<Node> nodes_;    // in elimination (post-)order
  std::size_t entries_ = 0;
  int max_front_ = 0;
};

}  // namespace igm
