#pragma once
// Union-find (disjoint sets) over 0..n-1, with path halving and union by size (Tarjan 1975).
#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

namespace igm {

class UnionFind {
 public:
  /// n singletons {0}, ..., {n-1}. O(n).
  explicit UnionFind(std::size_t n) : parent_(n), size_(n, 1) { std::iota(parent_.begin(), parent_.end(), 0); }

  /// The representative of x's set. Pre: 0 <= x < n (not checked). Amortized O(alpha(n)); the loop
  /// is bounded by the height of x's tree, O(log n) with union by size.
  int find(int x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  /// Joins the sets of a and b; false if they were one set already. Amortized O(alpha(n)).
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
    return true;
  }

 private:
  std::vector<int> parent_;
  std::vector<int> size_;
};

}  // namespace igm
