#include <doctest/doctest.h>

#include <random>
#include <set>

#include "igm/core/error.h"
#include "igm/embed/sparse_cholesky.h"

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
