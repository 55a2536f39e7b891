#include "igm/embed/sparse_cholesky.h"

#include <cholmod.h>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/parallel_for_each.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <new>
#include <numeric>
#include <chrono>
#include <cstdint>
#include <string>

#include "igm/core/error.h"

// The supernodal numeric factorization (multifrontal; Duff & Reid 1983, Liu 1992) on CHOLMOD's
// symbolic supernodal factor (Chen, Davis, Hager, Rajamanickam 2008): supernode s owns the columns
// super[s] .. super[s+1]-1 of L (k of them) and the sorted rows s_rows[pi[s] .. pi[s+1]) (m, the k
// own columns first); its m x k block of L is stored column-major at Lx[px[s]]. Its front is that
// block plus the (m-k) x (m-k) update matrix U_s on its border rows: the original entries of its
// columns are scattered into the block, every child's U_c is added at the child's rows (extend-add,
// children in order), the k columns are factorized in panels of kDenseBlock columns (right-looking:
// panel LLT, triangular solve of the rows below, rank update of the rest of the front), and U_s
// goes to the parent. A supernode runs when all its children have: subtrees too small to be worth a
// task run as one serial unit; the panel solves and rank updates of large fronts split into fixed
// blocks of rows or columns. Every block is computed the same way whichever thread runs it, and
// nothing is summed across blocks, so the factor's bits do not depend on the threads.

namespace igm {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

using Long = SuiteSparse_long;
using Mat = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
constexpr int kB = SparseCholesky::kDenseBlock;
// A subtree of fewer flops runs as one serial unit; a front's panel work is split into blocks
// when its rank update has more flops than this.
constexpr double kSerialFlops = 4e6;
constexpr double kSplitFlops = 4e6;

[[noreturn]] void bad(const std::string& what) {
  throw Error(ErrorKind::InvalidArgument, "SparseCholesky: " + what);
}

Mat block(double* p, Long rows, Long cols, Long ld) {
  return Mat(p, static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols), Eigen::OuterStride<>(ld));
}

// Runs body(b) for b in [0, blocks), in parallel (isolated: a waiting thread runs only these
// blocks) when `parallel`. The blocks are independent.
template <class F>
void for_blocks(Long blocks, bool parallel, const F& body) {
  if (!parallel || blocks < 2) {
    for (Long b = 0; b < blocks; ++b) body(b);
    return;
  }
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(tbb::blocked_range<Long>(0, blocks, 1), [&](const tbb::blocked_range<Long>& r) {
      for (Long b = r.begin(); b != r.end(); ++b) body(b);
    }, tbb::simple_partitioner());
  });
}

// Nested-dissection elimination order by BFS level-set separators: BFS from a pseudo-peripheral
// vertex (the last vertex of a first BFS); among the levels preceded by 30% .. 70% of the
// vertices the smallest becomes the separator, eliminated after both sides, which are ordered
// the same way (explicit task stack). Disconnected parts are split into components; parts of
// <= kLeaf vertices are leaves in BFS order. Every task either emits its vertices (leaf),
// emits a non-empty separator and two strictly smaller parts, or splits into two non-empty
// components: at most 2n tasks, each O(size) work; O(n log n) for balanced splits.
// Output: order[p] = vertex at position p. (The project's first factorization ordered by this; it
// is kept as Ordering::LevelSets, the cheapest good order of a disk's Laplacian: bench/README.md.)
void level_set_order(const std::vector<int>& xadj, const std::vector<int>& adj, std::vector<Long>& order) {
  struct NdNode {
    int s0, s1, parent;
  };
  std::vector<NdNode> nodes;
  constexpr int kLeaf = 32;
  const int n = static_cast<int>(xadj.size()) - 1;
  order.assign(n, -1);
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

// Eigen's triangular solves with several right-hand sides block by L1 / (4 x its panel's bytes)
// (KcFactor 4 in SolveTriangular.h): at least 48 for any L1 >= 16 KB. Triangles of at most kTri,
// the rest by products (blocked by L1 / 1x: >= 200 > kDenseBlock).
constexpr Long kTri = 32;

// X <- X L^-T for the w x w lower triangle L (w <= kDenseBlock) and the rows x w block X.
void solve_xlt(const double* L, Long ldl, Long w, double* X, Long rows, Long ldx) {
  for (Long c0 = 0; c0 < w; c0 += kTri) {
    const Long c1 = std::min(w, c0 + kTri), bw = c1 - c0;
    Mat Xc = block(X + c0 * ldx, rows, bw, ldx);
    if (c0 > 0)
      Xc.noalias() -= block(X, rows, c0, ldx) * block(const_cast<double*>(L) + c0, bw, c0, ldl).transpose();
    block(const_cast<double*>(L) + c0 + c0 * ldl, bw, bw, ldl)
        .triangularView<Eigen::Lower>()
        .transpose()
        .solveInPlace<Eigen::OnTheRight>(Xc);
  }
}

// y <- L^-1 y (forward) or L^-T y (backward) for the w x w lower triangle L and the w x nc y.
template <class Y>
void solve_l(const double* L, Long ldl, Long w, Y&& y, bool transposed) {
  double* Lp = const_cast<double*>(L);
  if (!transposed) {
    for (Long c0 = 0; c0 < w; c0 += kTri) {
      const Long c1 = std::min(w, c0 + kTri), bw = c1 - c0;
      if (c0 > 0) y.middleRows(c0, bw).noalias() -= block(Lp + c0, bw, c0, ldl) * y.topRows(c0);
      block(Lp + c0 + c0 * ldl, bw, bw, ldl).triangularView<Eigen::Lower>().solveInPlace(y.middleRows(c0, bw));
    }
  } else {
    for (Long c0 = ((w - 1) / kTri) * kTri; c0 >= 0; c0 -= kTri) {
      const Long c1 = std::min(w, c0 + kTri), bw = c1 - c0;
      if (c1 < w) y.middleRows(c0, bw).noalias() -= block(Lp + c1 + c0 * ldl, w - c1, bw, ldl).transpose() * y.bottomRows(w - c1);
      block(Lp + c0 + c0 * ldl, bw, bw, ldl).triangularView<Eigen::Lower>().transpose().solveInPlace(y.middleRows(c0, bw));
    }
  }
}

// C -= A B^T on the lower trapezoid of C (nr x nc, nr >= nc, entries i >= j), B = the first nc
// rows of A (nr x w, w <= kB): per column block of kB, its diagonal block by a symmetric rank
// update and the rows below it by a product; the blocks are independent.
void lower_update(double* C, Long ldc, Long nr, Long nc, const double* A, Long lda, Long w) {
  if (nc <= 0 || w <= 0) return;
  const Long blocks = (nc + kB - 1) / kB;
  const bool parallel = static_cast<double>(nr) * static_cast<double>(nc) * static_cast<double>(w) > kSplitFlops;
  for_blocks(blocks, parallel, [&](Long b) {
    const Long j0 = b * kB, j1 = std::min(nc, j0 + kB), bw = j1 - j0;
    const Mat Aj = block(const_cast<double*>(A) + j0, bw, w, lda);
    block(C + j0 + j0 * ldc, bw, bw, ldc).selfadjointView<Eigen::Lower>().rankUpdate(Aj, -1.0);
    if (nr > j1) {
      const Mat Ab = block(const_cast<double*>(A) + j1, nr - j1, w, lda);
      block(C + j1 + j0 * ldc, nr - j1, bw, ldc).noalias() -= Ab * Aj.transpose();
    }
  });
}

}  // namespace

struct SparseCholesky::Impl {
  cholmod_common cm;
  Long n = 0;
  std::size_t nnz = 0;  // off-diagonal entries of the analyzed pattern
  // The matrix for CHOLMOD (lower triangle, original order) and where each input value goes:
  // off-diagonal entry k of the CSR input at A->x[to_a[k]] (-1: its mirror is the one stored),
  // diagonal i at A->x[diag_a[i]].
  cholmod_sparse* A = nullptr;
  std::vector<Long> to_a, diag_a;
  cholmod_factor* L = nullptr;  // CHOLMOD's simplicial factor (supernodal: freed after the analysis)
  bool supernodal = false;
  bool factorized = false;
  // Supernodal: CHOLMOD's symbolic factor, copied.
  Long ns = 0;
  std::vector<Long> perm, super, pi, px;
  std::vector<std::int32_t> rows;  // the supernodes' rows (n < 2^31: the input is CSR of int)
  std::vector<Long> parent, child_begin, children;  // children in increasing order
  std::vector<std::int32_t> rel;  // per border row of a supernode: its position in the parent's rows
  std::vector<Long> first;     // first supernode of each subtree (postorder: the subtree is [first, s])
  // per supernode, the input values it holds: entry_src (k >= 0: off-diagonal value k, -1 - i:
  // diagonal i) goes to its block's offset entry_dst
  std::vector<Long> entry_begin;
  std::vector<std::int32_t> entry_src, entry_dst;
  std::vector<Long> units;     // roots of the units of work (serial subtrees or single supernodes)
  std::vector<Long> unit_of;   // per supernode: its unit (the unit's root)
  std::vector<char> unit_serial;
  std::vector<double> Lx;

  Impl() {
    cholmod_l_start(&cm);
    cm.print = 0;  // the library never prints
    cm.error_handler = nullptr;
  }
  ~Impl() {
    if (L) cholmod_l_free_factor(&L, &cm);
    if (A) cholmod_l_free_sparse(&A, &cm);
    cholmod_l_finish(&cm);
  }

  Long k_of(Long s) const { return super[s + 1] - super[s]; }
  Long m_of(Long s) const { return pi[s + 1] - pi[s]; }

  void setup_supernodal(SparseCholeskyStats& st, const std::vector<int>& xadj, const std::vector<int>& adj);
  bool factorize_supernodal(const std::vector<double>& val, const std::vector<double>& diag);
  bool front(Long s, const std::vector<double>& val, const std::vector<double>& diag,
             std::vector<std::vector<double>>& update, std::atomic<bool>& failed);
  void solve_supernodal(Eigen::MatrixXd& b) const;
};

SparseCholesky::SparseCholesky() = default;
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::analyze(const std::vector<int>& xadj, const std::vector<int>& adj, const std::vector<int>& group,
                             Ordering ordering) {
  const auto t0 = Clock::now();
  const Long n = static_cast<Long>(xadj.size()) - 1;
  if (n < 0 || xadj.front() != 0 || xadj.back() != static_cast<int>(adj.size())) bad("inconsistent CSR sizes");
  for (Long i = 0; i < n; ++i) {
    if (xadj[i + 1] < xadj[i]) bad("row pointers decrease");
    for (int k = xadj[i]; k < xadj[i + 1]; ++k)
      if (adj[k] < 0 || adj[k] >= n || adj[k] == i) bad("column out of range or on the diagonal");
  }
  if (!group.empty() && static_cast<Long>(group.size()) != n) bad("one group per unknown needed");
  impl_ = std::make_unique<Impl>();
  Impl& I = *impl_;
  cholmod_common& cm = I.cm;
  I.n = n;
  I.nnz = adj.size();
  stats_ = SparseCholeskyStats{};
  stats_.n = static_cast<int>(n);

  // --- the fill-reducing order, on the graph of groups ---
  Long ng = n;
  std::vector<Long> gbegin, gmembers;  // members of each group, increasing
  if (!group.empty()) {
    ng = 0;
    for (int g : group) {
      if (g < 0) bad("negative group id");
      ng = std::max<Long>(ng, g + 1);
    }
    gbegin.assign(ng + 1, 0);
    for (int g : group) ++gbegin[g + 1];
    for (Long g = 0; g < ng; ++g) {
      if (gbegin[g + 1] == 0) bad("group " + std::to_string(g) + " has no unknown");
      gbegin[g + 1] += gbegin[g];
    }
    gmembers.resize(n);
    std::vector<Long> fill(gbegin.begin(), gbegin.end() - 1);
    for (Long i = 0; i < n; ++i) gmembers[fill[group[i]]++] = i;
  }
  auto gid = [&](Long i) { return group.empty() ? i : static_cast<Long>(group[i]); };
  std::vector<Long> gperm(ng);
  if (n > 0) {
    // Upper triangle of the group graph's pattern, column by column (rows increasing, once each).
    std::vector<Long> colp(ng + 1, 0);
    for (Long i = 0; i < n; ++i)
      for (int k = xadj[i]; k < xadj[i + 1]; ++k)
        if (gid(i) < gid(adj[k])) ++colp[gid(adj[k]) + 1];
    for (Long j = 0; j < ng; ++j) colp[j + 1] += colp[j];
    std::vector<Long> rowi(colp[ng]);
    {
      std::vector<Long> fill(colp.begin(), colp.end() - 1);
      for (Long i = 0; i < n; ++i)
        for (int k = xadj[i]; k < xadj[i + 1]; ++k)
          if (gid(i) < gid(adj[k])) rowi[fill[gid(adj[k])]++] = gid(i);
    }
    cholmod_sparse* G = cholmod_l_allocate_sparse(ng, ng, std::max<Long>(colp[ng], 1), 1, 1, 1, CHOLMOD_PATTERN, &cm);
    if (!G) throw std::bad_alloc();
    Long* gp = static_cast<Long*>(G->p);
    Long* gi = static_cast<Long*>(G->i);
    gp[0] = 0;
    for (Long j = 0; j < ng; ++j) {  // rows sorted, duplicates (from groups) dropped
      Long* b = rowi.data() + colp[j];
      Long* e = rowi.data() + colp[j + 1];
      std::sort(b, e);
      e = std::unique(b, e);
      gp[j + 1] = gp[j] + (e - b);
      std::copy(b, e, gi + gp[j]);
    }
    std::vector<Long>().swap(rowi);
    stats_.metis = ordering == Ordering::Metis || (ordering == Ordering::Automatic && n >= kMetisMinUnknowns);
    int ok = 1;
    if (ordering == Ordering::LevelSets && group.empty())
      level_set_order(xadj, adj, gperm);
    else
      ok = stats_.metis ? cholmod_l_metis(G, nullptr, 0, 0, gperm.data(), &cm)
                        : cholmod_l_amd(G, nullptr, 0, gperm.data(), &cm);
    cholmod_l_free_sparse(&G, &cm);
    if (!ok && cm.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
    if (!ok) throw Error(ErrorKind::Internal, "SparseCholesky: CHOLMOD's ordering failed (status " + std::to_string(cm.status) + ")");
  }
  std::vector<Long> uperm;  // the order of the unknowns: each group's members together
  uperm.reserve(n);
  for (Long g : gperm) {
    if (group.empty())
      uperm.push_back(g);
    else
      for (Long k = gbegin[g]; k < gbegin[g + 1]; ++k) uperm.push_back(gmembers[k]);
  }

  // --- the matrix for CHOLMOD: upper triangle (column j: rows i < j, then the diagonal), CHOLMOD's
  // own orientation (no transpose in its analysis) ---
  {
    std::vector<Long> count(n + 1, 0);
    for (Long i = 0; i < n; ++i) {
      ++count[i + 1];  // diagonal
      for (int k = xadj[i]; k < xadj[i + 1]; ++k)
        if (adj[k] > i) ++count[adj[k] + 1];
    }
    for (Long j = 0; j < n; ++j) count[j + 1] += count[j];
    I.A = cholmod_l_allocate_sparse(n, n, std::max<Long>(count[n], 1), 1, 1, 1, CHOLMOD_REAL, &cm);
    if (!I.A) throw std::bad_alloc();
    Long* ap = static_cast<Long*>(I.A->p);
    Long* ai = static_cast<Long*>(I.A->i);
    std::copy(count.begin(), count.end(), ap);
    std::vector<Long> fill(count.begin(), count.end() - 1);
    I.diag_a.resize(n);
    I.to_a.assign(adj.size(), -1);
    for (Long i = 0; i < n; ++i) {  // rows increasing: each column's rows come out sorted
      I.diag_a[i] = fill[i];  // column i's rows < i are in already
      ai[fill[i]++] = i;
      for (int k = xadj[i]; k < xadj[i + 1]; ++k)
        if (adj[k] > i) {
          I.to_a[k] = fill[adj[k]];
          ai[fill[adj[k]]++] = i;
        }
    }
  }

  // --- CHOLMOD's symbolic analysis with that order (postordered), simplicial or supernodal ---
  cm.nmethods = 1;
  cm.method[0].ordering = CHOLMOD_GIVEN;
  cm.postorder = 1;
  cm.supernodal = CHOLMOD_AUTO;
  cm.final_ll = 1;  // simplicial: LL^T, whose pivots must be positive
  I.L = cholmod_l_analyze_p(I.A, n > 0 ? uperm.data() : nullptr, nullptr, 0, &cm);
  if (cm.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
  if (!I.L) throw Error(ErrorKind::Internal, "SparseCholesky: CHOLMOD's analysis failed (status " + std::to_string(cm.status) + ")");
  stats_.flops = cm.fl;
  stats_.factor_entries = static_cast<std::size_t>(cm.lnz);
  I.supernodal = I.L->is_super;
  stats_.supernodal = I.supernodal;
  if (I.supernodal) {  // CHOLMOD's matrix and factor only served the analysis
    I.setup_supernodal(stats_, xadj, adj);
    cholmod_l_free_sparse(&I.A, &cm);
    std::vector<Long>().swap(I.to_a);
    std::vector<Long>().swap(I.diag_a);
    cholmod_l_free_factor(&I.L, &cm);
  }
  stats_.seconds_analyze = since(t0);
}

void SparseCholesky::Impl::setup_supernodal(SparseCholeskyStats& st, const std::vector<int>& xadj,
                                            const std::vector<int>& adj) {
  ns = static_cast<Long>(L->nsuper);
  const Long* Lperm = static_cast<const Long*>(L->Perm);
  perm.assign(Lperm, Lperm + n);
  super.assign(static_cast<const Long*>(L->super), static_cast<const Long*>(L->super) + ns + 1);
  pi.assign(static_cast<const Long*>(L->pi), static_cast<const Long*>(L->pi) + ns + 1);
  rows.assign(static_cast<const Long*>(L->s), static_cast<const Long*>(L->s) + pi[ns]);  // each < n
  px.assign(ns + 1, 0);
  for (Long s = 0; s < ns; ++s) px[s + 1] = px[s] + k_of(s) * m_of(s);
  st.supernodes = static_cast<int>(ns);
  st.factor_entries = static_cast<std::size_t>(px[ns]);
  std::vector<Long> col_super(n);
  for (Long s = 0; s < ns; ++s)
    for (Long j = super[s]; j < super[s + 1]; ++j) col_super[j] = s;
  // the tree of supernodes, its postorder checked (each subtree a contiguous range [first, s])
  parent.assign(ns, -1);
  child_begin.assign(ns + 1, 0);
  for (Long s = 0; s < ns; ++s) {
    const Long k = k_of(s), m = m_of(s);
    st.max_front = std::max<int>(st.max_front, static_cast<int>(m));
    for (Long a = 0; a < m; ++a)  // its own columns first, then the border, increasing
      if ((a < k && rows[pi[s] + a] != super[s] + a) || (a > 0 && rows[pi[s] + a] <= rows[pi[s] + a - 1]))
        throw Error(ErrorKind::Internal, "SparseCholesky: unexpected supernode row structure");
    if (m > k) {
      parent[s] = col_super[rows[pi[s] + k]];
      if (parent[s] <= s) throw Error(ErrorKind::Internal, "SparseCholesky: supernodes not in postorder");
      ++child_begin[parent[s] + 1];
    }
  }
  for (Long s = 0; s < ns; ++s) child_begin[s + 1] += child_begin[s];
  children.resize(child_begin[ns]);
  {
    std::vector<Long> fill(child_begin.begin(), child_begin.end() - 1);
    for (Long s = 0; s < ns; ++s)
      if (parent[s] >= 0) children[fill[parent[s]]++] = s;
  }
  first.resize(ns);
  std::vector<Long> size(ns, 1);
  for (Long s = 0; s < ns; ++s) {
    first[s] = s;
    for (Long c = child_begin[s]; c < child_begin[s + 1]; ++c) {
      first[s] = std::min(first[s], first[children[c]]);
      size[s] += size[children[c]];
    }
    if (size[s] != s - first[s] + 1) throw Error(ErrorKind::Internal, "SparseCholesky: supernodes not in postorder");
  }
  // relative positions of each border row in the parent's rows
  rel.assign(pi[ns], -1);
  {
    std::vector<Long> where(n, -1);
    for (Long p = 0; p < ns; ++p) {
      for (Long a = 0; a < m_of(p); ++a) where[rows[pi[p] + a]] = a;
      for (Long c = child_begin[p]; c < child_begin[p + 1]; ++c) {
        const Long ch = children[c], kc = k_of(ch);
        for (Long a = kc; a < m_of(ch); ++a) {
          const Long r = rows[pi[ch] + a];
          const Long w = where[r];
          if (w < 0 || rows[pi[p] + w] != r) throw Error(ErrorKind::Internal, "SparseCholesky: a child's row is not its parent's");
          rel[pi[ch] + a] = static_cast<std::int32_t>(w);
        }
      }
    }
  }
  // where every input value goes: (row, column) permuted, lower, in its supernode's block
  std::vector<Long> iperm(n);
  for (Long k = 0; k < n; ++k) iperm[perm[k]] = k;
  auto offset = [&](Long r, Long c) {  // r >= c, permuted
    const Long s = col_super[c], k = k_of(s), m = m_of(s);
    Long a;
    if (r < super[s + 1]) {
      a = r - super[s];
    } else {
      const std::int32_t* b = rows.data() + pi[s] + k;
      const std::int32_t* e = rows.data() + pi[s] + m;
      const std::int32_t* it = std::lower_bound(b, e, r);
      if (it == e || *it != r) throw Error(ErrorKind::Internal, "SparseCholesky: an entry outside the symbolic factor");
      a = k + (it - b);
    }
    return std::pair<Long, Long>{s, (c - super[s]) * m + a};
  };
  // two passes: count per supernode, then place (counting sort: each supernode's entries in input
  // order)
  entry_begin.assign(ns + 1, 0);
  for (Long i = 0; i < n; ++i) {
    ++entry_begin[col_super[iperm[i]] + 1];
    for (int k = xadj[i]; k < xadj[i + 1]; ++k)
      if (iperm[i] > iperm[adj[k]]) ++entry_begin[col_super[iperm[adj[k]]] + 1];
  }
  for (Long s = 0; s < ns; ++s) entry_begin[s + 1] += entry_begin[s];
  entry_src.resize(entry_begin[ns]);
  entry_dst.resize(entry_begin[ns]);
  std::vector<Long> fill(entry_begin.begin(), entry_begin.end() - 1);
  auto place = [&](const std::pair<Long, Long>& e, Long src) {
    const Long slot = fill[e.first]++;
    if (e.second > INT32_MAX) throw Error(ErrorKind::Internal, "SparseCholesky: a supernode too large for 32-bit offsets");
    entry_dst[slot] = static_cast<std::int32_t>(e.second);
    entry_src[slot] = static_cast<std::int32_t>(src);
  };
  for (Long i = 0; i < n; ++i) {
    place(offset(iperm[i], iperm[i]), -1 - i);
    for (int k = xadj[i]; k < xadj[i + 1]; ++k) {
      const Long r = iperm[i], c = iperm[adj[k]];
      if (r > c) place(offset(r, c), k);  // else its mirror (the same value) is stored
    }
  }
  // units of work: a subtree of fewer than kSerialFlops runs serially as one unit
  std::vector<double> work(ns, 0.0);
  for (Long s = 0; s < ns; ++s) {
    const double k = static_cast<double>(k_of(s)), u = static_cast<double>(m_of(s) - k_of(s));
    work[s] += k * k * k / 3 + k * k * u + k * u * u;
    if (parent[s] >= 0) work[parent[s]] += work[s];
  }
  unit_of.assign(ns, -1);
  unit_serial.assign(ns, 0);
  for (Long s = ns - 1; s >= 0; --s) {  // parents first
    if (unit_of[s] >= 0) continue;
    units.push_back(s);
    if (work[s] < kSerialFlops) {
      unit_serial[s] = 1;
      for (Long t = first[s]; t <= s; ++t) unit_of[t] = s;
    } else {
      unit_of[s] = s;
    }
  }
  std::reverse(units.begin(), units.end());
}

bool SparseCholesky::Impl::front(Long s, const std::vector<double>& val, const std::vector<double>& diag,
                                 std::vector<std::vector<double>>& update, std::atomic<bool>& failed) {
  const Long k = k_of(s), m = m_of(s), u = m - k;
  double* F = Lx.data() + px[s];
  std::fill(F, F + k * m, 0.0);
  for (Long e = entry_begin[s]; e < entry_begin[s + 1]; ++e) {
    const Long src = entry_src[e];
    F[entry_dst[e]] = src >= 0 ? val[src] : diag[-1 - src];
  }
  std::vector<double> U(static_cast<std::size_t>(u * u), 0.0);
  for (Long c = child_begin[s]; c < child_begin[s + 1]; ++c) {  // extend-add, children in order
    const Long ch = children[c], kc = k_of(ch), uc = m_of(ch) - kc;
    const std::int32_t* r = rel.data() + pi[ch] + kc;
    std::vector<double>& Uc = update[ch];
    const bool parallel = static_cast<double>(uc) * static_cast<double>(uc) > 2 * kSplitFlops;
    for_blocks((uc + kB - 1) / kB, parallel, [&](Long bb) {  // each column of Uc lands in its own column
      for (Long b = bb * kB; b < std::min(uc, bb * kB + kB); ++b) {
        const Long cb = r[b];
        const double* src = Uc.data() + b * uc;
        if (cb < k) {
          double* dst = F + cb * m;
          for (Long a = b; a < uc; ++a) dst[r[a]] += src[a];
        } else {
          double* dst = U.data() + (cb - k) * u;
          for (Long a = b; a < uc; ++a) dst[r[a] - k] += src[a];
        }
      }
    });
    std::vector<double>().swap(Uc);
  }
  for (Long c0 = 0; c0 < k; c0 += kB) {
    if (failed.load(std::memory_order_relaxed)) return false;
    const Long c1 = std::min(k, c0 + kB), w = c1 - c0;
    Mat D = block(F + c0 + c0 * m, w, w, m);
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd, 0, Eigen::OuterStride<>>> llt(D);
    if (llt.info() != Eigen::Success) return false;
    const Long below = m - c1;  // rows under the panel's diagonal block
    if (below > 0) {
      const bool parallel = static_cast<double>(below) * static_cast<double>(w) * static_cast<double>(w) > kSplitFlops;
      const Long rb = 2 * kB;
      for_blocks((below + rb - 1) / rb, parallel, [&](Long b) {
        const Long r0 = c1 + b * rb, r1 = std::min(m, r0 + rb);
        solve_xlt(F + c0 + c0 * m, m, w, F + r0 + c0 * m, r1 - r0, m);
      });
      const double* P = F + c1 + c0 * m;
      lower_update(F + c1 + c1 * m, m, below, k - c1, P, m, w);  // the supernode's later columns
      lower_update(U.data(), u, u, u, P + (k - c1), m, w);        // the border: U -= P_b P_b^T
    }
  }
  if (u > 0) update[s] = std::move(U);
  return true;
}

bool SparseCholesky::Impl::factorize_supernodal(const std::vector<double>& val, const std::vector<double>& diag) {
  Lx.resize(px[ns]);  // every front sets its own block
  std::vector<std::vector<double>> update(ns);
  std::atomic<bool> failed{false};
  // pending child units of each unit; a unit runs when all have
  std::vector<std::atomic<Long>> pending(ns);
  for (Long s = 0; s < ns; ++s) pending[s].store(0, std::memory_order_relaxed);
  std::vector<Long> ready;
  for (Long s : units) {
    if (parent[s] >= 0) pending[unit_of[parent[s]]].fetch_add(1, std::memory_order_relaxed);
  }
  for (Long s : units)
    if (pending[s].load(std::memory_order_relaxed) == 0) ready.push_back(s);
  auto run_unit = [&](Long s, auto& feeder) {
    if (!failed.load(std::memory_order_relaxed)) {
      const Long from = unit_serial[s] ? first[s] : s;
      for (Long t = from; t <= s; ++t)
        if (!front(t, val, diag, update, failed)) {
          failed.store(true);
          break;
        }
    }
    if (parent[s] >= 0) {
      const Long p = unit_of[parent[s]];
      if (pending[p].fetch_sub(1) == 1) feeder.add(p);
    }
  };
  tbb::parallel_for_each(ready.begin(), ready.end(),
                         [&](Long s, tbb::feeder<Long>& feeder) { run_unit(s, feeder); });
  return !failed.load();
}

void SparseCholesky::Impl::solve_supernodal(Eigen::MatrixXd& b) const {
  const Eigen::Index nc = b.cols();
  Eigen::MatrixXd y(n, nc);
  for (Long p = 0; p < n; ++p) y.row(p) = b.row(perm[p]);
  Eigen::MatrixXd z;
  for (Long s = 0; s < ns; ++s) {  // forward: L z = y, supernode by supernode, panel by panel
    const Long k = k_of(s), m = m_of(s);
    const std::int32_t* R = rows.data() + pi[s];
    z.resize(m, nc);
    for (Long a = 0; a < m; ++a) z.row(a) = y.row(R[a]);
    double* F = const_cast<double*>(Lx.data()) + px[s];
    for (Long c0 = 0; c0 < k; c0 += kB) {
      const Long c1 = std::min(k, c0 + kB), w = c1 - c0;
      solve_l(F + c0 + c0 * m, m, w, z.middleRows(c0, w), false);
      if (m > c1) z.bottomRows(m - c1).noalias() -= block(F + c1 + c0 * m, m - c1, w, m) * z.middleRows(c0, w);
    }
    for (Long a = 0; a < m; ++a) y.row(R[a]) = z.row(a);
  }
  for (Long s = ns - 1; s >= 0; --s) {  // backward: L^T x = z
    const Long k = k_of(s), m = m_of(s);
    const std::int32_t* R = rows.data() + pi[s];
    z.resize(m, nc);
    for (Long a = 0; a < m; ++a) z.row(a) = y.row(R[a]);
    double* F = const_cast<double*>(Lx.data()) + px[s];
    for (Long c0 = ((k - 1) / kB) * kB; c0 >= 0; c0 -= kB) {
      const Long c1 = std::min(k, c0 + kB), w = c1 - c0;
      for (Long r0 = c1; r0 < m; r0 += kB) {  // inner dimension at most kB, in a fixed order
        const Long r1 = std::min(m, r0 + kB);
        z.middleRows(c0, w).noalias() -= block(F + r0 + c0 * m, r1 - r0, w, m).transpose() * z.middleRows(r0, r1 - r0);
      }
      solve_l(F + c0 + c0 * m, m, w, z.middleRows(c0, w), true);
    }
    for (Long a = 0; a < k; ++a) y.row(R[a]) = z.row(a);
  }
  for (Long p = 0; p < n; ++p) b.row(perm[p]) = y.row(p);
}

bool SparseCholesky::factorize_numeric(const std::vector<double>& val, const std::vector<double>& diag) {
  if (!impl_) throw Error(ErrorKind::InvalidArgument, "SparseCholesky: factorize_numeric before analyze");
  Impl& I = *impl_;
  if (static_cast<Long>(diag.size()) != I.n || val.size() != I.nnz)
    bad("the values do not match the analyzed pattern");
  const auto t0 = Clock::now();
  I.factorized = false;
  bool ok = true;
  if (I.n == 0) {
    ok = true;
  } else if (I.supernodal) {
    ok = I.factorize_supernodal(val, diag);
  } else {
    double* ax = static_cast<double*>(I.A->x);
    for (Long i = 0; i < I.n; ++i) ax[I.diag_a[i]] = diag[i];
    for (std::size_t k = 0; k < val.size(); ++k)
      if (I.to_a[k] >= 0) ax[I.to_a[k]] = val[k];
    ok = cholmod_l_factorize(I.A, I.L, &I.cm) && I.cm.status == CHOLMOD_OK &&
         static_cast<Long>(I.L->minor) == I.n;
    if (I.cm.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
  }
  stats_.seconds_factorize = since(t0);
  I.factorized = ok;
  return ok;
}

void SparseCholesky::factorize(const std::vector<int>& xadj, const std::vector<int>& adj, const std::vector<double>& val,
                               const std::vector<double>& diag, Ordering ordering) {
  if (xadj.size() != diag.size() + 1 || adj.size() != val.size()) bad("inconsistent CSR sizes");
  analyze(xadj, adj, {}, ordering);
  if (!factorize_numeric(val, diag))
    throw Error(ErrorKind::Internal, "SparseCholesky: matrix not numerically positive definite");
}

void SparseCholesky::release_numeric() {
  if (!impl_ || !impl_->supernodal) return;
  impl_->factorized = false;
  std::vector<double>().swap(impl_->Lx);
}

void SparseCholesky::solve(Eigen::MatrixXd& b) const {
  if (!impl_ || !impl_->factorized) throw Error(ErrorKind::InvalidArgument, "SparseCholesky::solve without a factorization");
  const Impl& I = *impl_;
  if (b.rows() != I.n) throw Error(ErrorKind::InvalidArgument, "SparseCholesky::solve: wrong number of rows");
  if (I.n == 0 || b.cols() == 0) return;
  if (I.supernodal) {
    I.solve_supernodal(b);
    return;
  }
  cholmod_dense B;
  B.nrow = static_cast<std::size_t>(I.n);
  B.ncol = static_cast<std::size_t>(b.cols());
  B.nzmax = B.nrow * B.ncol;
  B.d = B.nrow;
  B.x = b.data();
  B.z = nullptr;
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  cholmod_common& cm = const_cast<cholmod_common&>(I.cm);
  cholmod_dense* X = cholmod_l_solve(CHOLMOD_A, I.L, &B, &cm);
  if (!X && cm.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
  if (!X) throw Error(ErrorKind::Internal, "SparseCholesky: CHOLMOD's solve failed");
  std::copy(static_cast<const double*>(X->x), static_cast<const double*>(X->x) + B.nzmax, b.data());
  cholmod_l_free_dense(&X, &cm);
}

}  // namespace igm
