#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <set>

#include "igm/core/error.h"
#include "igm/core/threads.h"
#include "igm/embed/sparse_cholesky.h"
#include "test_data.h"

using namespace igm;

namespace {

struct Csr {
  std::vector<int> xadj{0}, adj;
  std::vector<double> val, diag;
};

// Laplacian-like SPD matrix of an undirected graph: off-diagonal -w, diagonal sum w + shift_i.
Csr from_edges(int n, const std::vector<std::pair<int, int>>& edges, std::mt19937_64& rng,
               const std::vector<double>& shift) {
  std::vector<std::vector<std::pair<int, double>>> rows(n);
  std::uniform_real_distribution<double> w(0.5, 2.0);
  Csr c;
  c.diag = shift;
  for (auto [a, b] : edges) {
    const double x = w(rng);
    rows[a].push_back({b, -x});
    rows[b].push_back({a, -x});
    c.diag[a] += x;
    c.diag[b] += x;
  }
  for (int i = 0; i < n; ++i) {
    for (auto [j, x] : rows[i]) {
      c.adj.push_back(j);
      c.val.push_back(x);
    }
    c.xadj.push_back(static_cast<int>(c.adj.size()));
  }
  return c;
}

double relative_residual(const Csr& c, const Eigen::MatrixXd& x, const Eigen::MatrixXd& b) {
  const int n = static_cast<int>(c.diag.size());
  Eigen::MatrixXd r = b;
  for (int i = 0; i < n; ++i) {
    r.row(i) -= c.diag[i] * x.row(i);
    for (int k = c.xadj[i]; k < c.xadj[i + 1]; ++k) r.row(i) -= c.val[k] * x.row(c.adj[k]);
  }
  return r.norm() / b.norm();
}

}  // namespace

TEST_CASE("sparse Cholesky solves grid Laplacians (Dirichlet rows) to double accuracy") {
  std::mt19937_64 rng(5);
  for (int n : {1, 2, 7, 40, 150}) {
    CAPTURE(n);
    const int N = n * n;
    std::vector<std::pair<int, int>> edges;
    auto id = [&](int i, int j) { return j * n + i; };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (i + 1 < n) edges.push_back({id(i, j), id(i + 1, j)});
        if (j + 1 < n) edges.push_back({id(i, j), id(i, j + 1)});
        if (i + 1 < n && j + 1 < n) edges.push_back({id(i, j), id(i + 1, j + 1)});
      }
    std::vector<double> shift(N, 0.0);
    for (int i = 0; i < n; ++i) shift[id(i, 0)] = shift[id(0, i)] = 1.0;  // boundary coupling
    const Csr c = from_edges(N, edges, rng, shift);
    SparseCholesky chol;
    chol.factorize(c.xadj, c.adj, c.val, c.diag);
    CHECK(chol.size() == N);
    Eigen::MatrixXd b = Eigen::MatrixXd::Random(N, 2);
    Eigen::MatrixXd x = b;
    chol.solve(x);
    CHECK(relative_residual(c, x, b) < 1e-9);
  }
}

TEST_CASE("sparse Cholesky on random sparse graphs, several components and isolated vertices") {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 1 + static_cast<int>(rng() % 600);
    std::set<std::pair<int, int>> es;
    const int m = static_cast<int>(rng() % (3 * n + 1));
    for (int k = 0; k < m; ++k) {
      int a = static_cast<int>(rng() % n), b = static_cast<int>(rng() % n);
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      es.insert({a, b});
    }
    std::vector<double> shift(n);
    for (double& s : shift) s = (rng() % 4 == 0) ? 0.5 : 0.01;
    const Csr c = from_edges(n, {es.begin(), es.end()}, rng, shift);
    SparseCholesky chol;
    chol.factorize(c.xadj, c.adj, c.val, c.diag);
    Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 3);
    Eigen::MatrixXd x = b;
    chol.solve(x);
    CAPTURE(n);
    CHECK(relative_residual(c, x, b) < 1e-8);
    CHECK(chol.max_front() <= n);
  }
}

TEST_CASE("sparse Cholesky rejects indefinite matrices and malformed input") {
  std::mt19937_64 rng(1);
  // Pure Laplacian of a path: singular (no shift) -> not positive definite.
  std::vector<std::pair<int, int>> path;
  for (int i = 0; i + 1 < 200; ++i) path.push_back({i, i + 1});
  Csr c = from_edges(200, path, rng, std::vector<double>(200, 0.0));
  c.diag[100] = -1.0;
  SparseCholesky chol;
  try {
    chol.factorize(c.xadj, c.adj, c.val, c.diag);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Internal);
  }
  c.adj[0] = 500;
  CHECK_THROWS_AS(chol.factorize(c.xadj, c.adj, c.val, c.diag), Error);
}

namespace {

// The Newton-like system of an n x n grid of vertices: 2 unknowns per vertex (grouped), 2 x 2
// blocks between neighbours (the triangulated grid), diagonally dominant.
struct Blocks {
  Csr c;
  std::vector<int> group;
};

Blocks grid_blocks(int n, std::mt19937_64& rng) {
  Blocks b;
  std::uniform_real_distribution<double> w(0.5, 2.0);
  auto id = [&](int i, int j) { return j * n + i; };
  std::vector<std::vector<std::pair<int, double>>> rows(2 * n * n);
  auto couple = [&](int u, int v) {
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) {
        const double x = (r == c ? -1.0 : 0.2) * w(rng);
        rows[2 * u + r].push_back({2 * v + c, x});
        rows[2 * v + c].push_back({2 * u + r, x});
      }
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i + 1 < n) couple(id(i, j), id(i + 1, j));
      if (j + 1 < n) couple(id(i, j), id(i, j + 1));
      if (i + 1 < n && j + 1 < n) couple(id(i, j), id(i + 1, j + 1));
      const double x = 0.3 * w(rng);  // the vertex's own 2 x 2 block
      rows[2 * id(i, j)].push_back({2 * id(i, j) + 1, x});
      rows[2 * id(i, j) + 1].push_back({2 * id(i, j), x});
    }
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::sort(rows[r].begin(), rows[r].end());
    double sum = 0.01;
    for (auto [col, x] : rows[r]) {
      b.c.adj.push_back(col);
      b.c.val.push_back(x);
      sum += std::abs(x);
    }
    b.c.xadj.push_back(static_cast<int>(b.c.adj.size()));
    b.c.diag.push_back(sum);
    b.group.push_back(static_cast<int>(r / 2));
  }
  return b;
}

}  // namespace

TEST_CASE("sparse Cholesky: the supernodal factorization of a grouped system, analysed once and factorized twice") {
  std::mt19937_64 rng(3);
  const Blocks b = grid_blocks(igm_test::kSanitized ? 60 : 160, rng);  // 51,200 unknowns: METIS, supernodal
  SparseCholesky chol;
  chol.analyze(b.c.xadj, b.c.adj, b.group);
  CHECK(chol.stats().supernodal);
  CHECK(chol.stats().supernodes > 1);
  CHECK(chol.stats().metis == (b.c.diag.size() >= SparseCholesky::kMetisMinUnknowns));
  const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(static_cast<Eigen::Index>(b.c.diag.size()), 2);
  for (double scale : {1.0, 3.0}) {  // new values on the same pattern: no new analysis
    Csr c = b.c;
    for (double& x : c.val) x *= scale;
    for (double& x : c.diag) x *= scale;
    REQUIRE(chol.factorize_numeric(c.val, c.diag));
    Eigen::MatrixXd x = rhs;
    chol.solve(x);
    CHECK(relative_residual(c, x, rhs) < 1e-12);
  }
  // Not positive definite: false, the pattern still usable afterwards.
  Csr bad = b.c;
  bad.diag[bad.diag.size() / 2] = -1;
  CHECK_FALSE(chol.factorize_numeric(bad.val, bad.diag));
  CHECK(chol.factorize_numeric(b.c.val, b.c.diag));
  // The numeric factor released: no solve until the next factorization, which gives the same bits.
  Eigen::MatrixXd before = rhs;
  chol.solve(before);
  chol.release_numeric();
  Eigen::MatrixXd after = rhs;
  CHECK_THROWS_AS(chol.solve(after), Error);
  REQUIRE(chol.factorize_numeric(b.c.val, b.c.diag));
  chol.solve(after);
  CHECK(after == before);
  // Values that do not match the pattern, or a solve before any analysis.
  CHECK_THROWS_AS(chol.factorize_numeric(std::vector<double>(3), b.c.diag), Error);
  SparseCholesky none;
  Eigen::MatrixXd x = rhs;
  CHECK_THROWS_AS(none.solve(x), Error);
}

TEST_CASE("sparse Cholesky: the same bits for 1, 2 and 3 threads and for any L1 cache size Eigen assumes") {
  std::mt19937_64 rng(8);
  const Blocks b = grid_blocks(igm_test::kSanitized ? 50 : 110, rng);  // fronts of several panels
  const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(static_cast<Eigen::Index>(b.c.diag.size()), 2);
  auto solve = [&](int threads) {
    Eigen::MatrixXd x = rhs;
    igm::with_threads(threads, [&] {
      SparseCholesky chol;
      chol.analyze(b.c.xadj, b.c.adj, b.group);
      REQUIRE(chol.stats().supernodal);
      REQUIRE(chol.factorize_numeric(b.c.val, b.c.diag));
      chol.solve(x);
    });
    return x;
  };
  const Eigen::MatrixXd one = solve(1);
  CHECK(relative_residual(b.c, one, rhs) < 1e-12);
  for (int threads : {2, 3}) {
    CAPTURE(threads);
    const Eigen::MatrixXd x = solve(threads);
    CHECK(std::memcmp(x.data(), one.data(), sizeof(double) * static_cast<std::size_t>(x.size())) == 0);
  }
  // Eigen blocks its products by the L1 cache size it reads from the CPU; every product here has an
  // inner dimension of at most kDenseBlock, below any blocking Eigen derives from 16..64 KB.
  std::ptrdiff_t l1 = 0, l2 = 0, l3 = 0;
  Eigen::internal::manage_caching_sizes(Eigen::GetAction, &l1, &l2, &l3);
  for (std::ptrdiff_t kb : {16, 32, 48, 64}) {
    CAPTURE(kb);
    Eigen::setCpuCacheSizes(kb * 1024, l2, l3);
    const Eigen::MatrixXd x = solve(2);
    CHECK(std::memcmp(x.data(), one.data(), sizeof(double) * static_cast<std::size_t>(x.size())) == 0);
  }
  Eigen::setCpuCacheSizes(l1, l2, l3);
}
