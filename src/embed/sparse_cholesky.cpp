#include "igm/embed/sparse_cholesky.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <string>

#include "igm/core/error.h"

namespace igm {

namespace {

// Largest dense frontal matrix accepted (32768^2 doubles = 8 GiB would be the next step); planar
// meshes of 10^7 vertices have fronts of a few thousand.
constexpr int kMaxFront = 20000;

struct NdNode {
  int s0, s1, parent;
};

// Nested-dissection elimination order by BFS level-set separators: BFS from a pseudo-peripheral
// vertex (the last vertex of a first BFS); among the levels preceded by 30% .. 70% of the
// vertices the smallest becomes the separator, eliminated after both sides, which are ordered
// the same way (explicit task stack). Disconnected parts are split into components; parts of
// <= kLeaf vertices are leaves in BFS order. Every task either emits its vertices (leaf),
// emits a non-empty separator and two strictly smaller parts, or splits into two non-empty
// components: at most 2n tasks, each O(size) work; O(n log n) for balanced splits.
// Output: order[p] = vertex at position p; nodes with separator positions [s0, s1) and parent.
void nested_dissection(const std::vector<int>& xadj, const std::vector<int>& adj, std::vector<int>& order,
                       std::vector<NdNode>& nodes) {
  constexpr int kLeaf = 32;
  const int n = static_cast<int>(xadj.size()) - 1;
  order.assign(n, -1);
  nodes.clear();
  std::vector<int> work(n), owner(n, -1), level(n, -1), queue, level_count;
  std::iota(work.begin(), work.end(), 0);
  struct Task {
    int begin, end, out, parent;  // vertices work[begin, end) take positions out .. out+size-1
  };
  std::vector<Task> tasks{{0, n, 0, -1}};
  int stamp = 0;
  queue.reserve(n);
  auto bfs = [&](int s, int tag) {  // BFS restricted to the task's vertices (owner == tag)
    queue.clear();
    queue.push_back(s);
    level[s] = 0;
    owner[s] = tag + 1;
    for (std::size_t h = 0; h < queue.size(); ++h) {
      const int v = queue[h];
      for (int k = xadj[v]; k < xadj[v + 1]; ++k) {
        const int w = adj[k];
        if (owner[w] == tag) {
          owner[w] = tag + 1;
          level[w] = level[v] + 1;
          queue.push_back(w);
        }
      }
    }
    for (int v : queue) owner[v] = tag;
  };
  auto leaf = [&](const Task& t) {
    for (int k = 0; k < static_cast<int>(queue.size()); ++k) order[t.out + k] = queue[k];
    nodes.push_back({t.out, t.out + static_cast<int>(queue.size()), t.parent});
  };
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    const int size = t.end - t.begin;
    if (size <= 0) continue;
    const int tag = 2 * (++stamp);
    for (int k = t.begin; k < t.end; ++k) owner[work[k]] = tag;
    bfs(work[t.begin], tag);
    const int reached = static_cast<int>(queue.size());
    if (reached < size) {  // several components: split this one off
      for (int v : queue) owner[v] = tag + 1;
      std::vector<int> rest;
      rest.reserve(size - reached);
      for (int k = t.begin; k < t.end; ++k)
        if (owner[work[k]] == tag) rest.push_back(work[k]);
      std::copy(queue.begin(), queue.end(), work.begin() + t.begin);
      std::copy(rest.begin(), rest.end(), work.begin() + t.begin + reached);
      tasks.push_back({t.begin, t.begin + reached, t.out, t.parent});
      tasks.push_back({t.begin + reached, t.end, t.out + reached, t.parent});
      continue;
    }
    if (size <= kLeaf) {
      leaf(t);
      continue;
    }
    bfs(queue.back(), tag);  // from a far vertex
    const int L = level[queue.back()];
    if (L < 2) {
      leaf(t);
      continue;
    }
    level_count.assign(L + 1, 0);
    for (int v : queue) ++level_count[level[v]];
    int mid = -1;
    {
      long before = 0, best = -1, best_dist = 0;
      for (int l = 0; l <= L; ++l) {
        if (l >= 1 && l <= L - 1 && 10 * before >= 3L * size && 10 * before <= 7L * size) {
          const long dist = std::labs(2 * before + level_count[l] - size);
          if (best < 0 || level_count[l] < best || (level_count[l] == best && dist < best_dist)) {
            best = level_count[l];
            best_dist = dist;
            mid = l;
          }
        }
        before += level_count[l];
      }
      if (mid < 0) mid = std::clamp(level[queue[size / 2]], 1, L - 1);
    }
    int na = 0, nsep = 0;
    for (int v : queue) {
      if (level[v] < mid)
        ++na;
      else if (level[v] == mid)
        ++nsep;
    }
    const int nb = size - na - nsep;
    // queue is sorted by level: [A | S | B].
    std::copy(queue.begin(), queue.begin() + na, work.begin() + t.begin);
    std::copy(queue.begin() + na + nsep, queue.end(), work.begin() + t.begin + na);
    const int s0 = t.out + na + nb;
    for (int k = 0; k < nsep; ++k) order[s0 + k] = queue[na + k];
    const int id = static_cast<int>(nodes.size());
    nodes.push_back({s0, t.out + size, t.parent});
    tasks.push_back({t.begin, t.begin + na, t.out, id});
    tasks.push_back({t.begin + na, t.begin + na + nb, t.out + na, id});
  }
}

}  // namespace

void SparseCholesky::factorize(const std::vector<int>& xadj, const std::vector<int>& adj,
                               const std::vector<double>& val, const std::vector<double>& diag) {
  const int n = static_cast<int>(diag.size());
  if (xadj.size() != diag.size() + 1 || adj.size() != val.size() || xadj.back() != static_cast<int>(adj.size()))
    throw Error(ErrorKind::InvalidArgument, "SparseCholesky: inconsistent CSR sizes");
  for (int a : adj)
    if (a < 0 || a >= n) throw Error(ErrorKind::InvalidArgument, "SparseCholesky: column out of range");
  n_ = n;
  entries_ = 0;
  max_front_ = 0;
  std::vector<NdNode> nd;
  nested_dissection(xadj, adj, order_, nd);
  std::vector<int> pos(n);
  for (int p = 0; p < n; ++p) pos[order_[p]] = p;

  // Post-order: by separator start (a subtree's positions all precede its separator).
  std::vector<int> perm(nd.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::sort(perm.begin(), perm.end(), [&](int a, int b) { return nd[a].s0 < nd[b].s0; });
  std::vector<int> rank(nd.size());
  for (std::size_t i = 0; i < perm.size(); ++i) rank[perm[i]] = static_cast<int>(i);
  const int nn = static_cast<int>(nd.size());
  std::vector<int> parent(nn);
  std::vector<std::vector<int>> children(nn);
  nodes_.assign(nn, Node{});
  for (int i = 0; i < nn; ++i) {
    const NdNode& x = nd[perm[i]];
    nodes_[i].s0 = x.s0;
    nodes_[i].s1 = x.s1;
    parent[i] = x.parent < 0 ? -1 : rank[x.parent];
    if (parent[i] >= 0) children[parent[i]].push_back(i);
  }

  std::vector<Eigen::MatrixXd> update(nn);  // Schur complement on each node's border
  std::vector<int> loc(n, -1), mark(n, -1);
  for (int i = 0; i < nn; ++i) {  // children (smaller ranks) are done before their parent
    Node& node = nodes_[i];
    const int k = node.s1 - node.s0;
    // Border: positions after the separator coupled to it directly or through a child.
    std::vector<int>& border = node.border;
    for (int p = node.s0; p < node.s1; ++p) {
      const int v = order_[p];
      for (int e = xadj[v]; e < xadj[v + 1]; ++e) {
        const int q = pos[adj[e]];
        if (q >= node.s1 && mark[q] != i) {
          mark[q] = i;
          border.push_back(q);
        }
      }
    }
    for (int c : children[i])
      for (int q : nodes_[c].border)
        if (q >= node.s1 && mark[q] != i) {
          mark[q] = i;
          border.push_back(q);
        }
    std::sort(border.begin(), border.end());
    const int u = static_cast<int>(border.size());
    for (int p = node.s0; p < node.s1; ++p) loc[p] = p - node.s0;
    for (int j = 0; j < u; ++j) loc[border[j]] = k + j;
    max_front_ = std::max(max_front_, k + u);
    if (k + u > kMaxFront)
      throw Error(ErrorKind::Internal, "SparseCholesky: frontal matrix of dimension " + std::to_string(k + u) +
                                           " exceeds the limit " + std::to_string(kMaxFront) +
                                           " (graph without small separators)");

    Eigen::MatrixXd F = Eigen::MatrixXd::Zero(k + u, k + u);  // lower triangle used
    for (int p = node.s0; p < node.s1; ++p) {
      const int v = order_[p];
      const int lp = p - node.s0;
      F(lp, lp) = diag[v];
      for (int e = xadj[v]; e < xadj[v + 1]; ++e) {
        const int q = pos[adj[e]];
        if (q < node.s0) continue;  // eliminated earlier: arrives through a child's update
        const int lq = loc[q];
        if (lq > lp) F(lq, lp) = val[e];
      }
    }
    for (int c : children[i]) {  // extend-add
      const std::vector<int>& cb = nodes_[c].border;
      const Eigen::MatrixXd& U = update[c];
      for (int b = 0; b < static_cast<int>(cb.size()); ++b) {
        const int lb = loc[cb[b]];
        for (int a = b; a < static_cast<int>(cb.size()); ++a) F(loc[cb[a]], lb) += U(a, b);
      }
      update[c] = Eigen::MatrixXd();
    }
    {
      Eigen::Ref<Eigen::MatrixXd> F11 = F.topLeftCorner(k, k);
      Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> llt(F11);  // in place
      if (llt.info() != Eigen::Success)
        throw Error(ErrorKind::Internal, "SparseCholesky: matrix not positive definite (pivot at position " +
                                             std::to_string(node.s0) + ")");
    }
    if (u > 0) {
      auto F21 = F.bottomLeftCorner(u, k);
      F.topLeftCorner(k, k).triangularView<Eigen::Lower>().transpose().solveInPlace<Eigen::OnTheRight>(F21);
      F.bottomRightCorner(u, u).selfadjointView<Eigen::Lower>().rankUpdate(F21, -1.0);
      update[i] = F.bottomRightCorner(u, u);
    }
    node.L = F.leftCols(k);
    entries_ += static_cast<std::size_t>(k) * (k + 1) / 2 + static_cast<std::size_t>(u) * k;
  }
}

void SparseCholesky::solve(Eigen::MatrixXd& b) const {
  if (b.rows() != n_) throw Error(ErrorKind::InvalidArgument, "SparseCholesky::solve: wrong number of rows");
  const Eigen::Index c = b.cols();
  Eigen::MatrixXd x(n_, c);
  for (int p = 0; p < n_; ++p) x.row(p) = b.row(order_[p]);
  Eigen::MatrixXd tmp;
  for (const Node& node : nodes_) {  // forward: L y = b
    const int k = node.s1 - node.s0, u = static_cast<int>(node.border.size());
    auto xs = x.middleRows(node.s0, k);
    node.L.topRows(k).triangularView<Eigen::Lower>().solveInPlace(xs);
    if (u > 0) {
      tmp.noalias() = node.L.bottomRows(u) * xs;
      for (int j = 0; j < u; ++j) x.row(node.border[j]) -= tmp.row(j);
    }
  }
  for (auto it = nodes_.rbegin(); it != nodes_.rend(); ++it) {  // backward: L^T x = y
    const Node& node = *it;
    const int k = node.s1 - node.s0, u = static_cast<int>(node.border.size());
    auto xs = x.middleRows(node.s0, k);
    if (u > 0) {
      tmp.resize(u, c);
      for (int j = 0; j < u; ++j) tmp.row(j) = x.row(node.border[j]);
      xs.noalias() -= node.L.bottomRows(u).transpose() * tmp;
    }
    node.L.topRows(k).triangularView<Eigen::Lower>().transpose().solveInPlace(xs);
  }
  for (int p = 0; p < n_; ++p) b.row(order_[p]) = x.row(p);
}

}  // namespace igm
