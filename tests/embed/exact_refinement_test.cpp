// Tests of the shared certified solve on small integer SPD systems, with certificates that force
// each exit: the double solution, refinement steps, the exact fallback and the typed errors.
#include <doctest/doctest.h>

#include <string>

#include "igm/core/error.h"
#include "igm/embed/exact_refinement.h"

using namespace igm;

namespace {

// The path Laplacian on n unknowns with both ends tied to fixed values (Dirichlet): diag 2,
// off-diagonal -1; right-hand side 1/3 at the first row, (5, -7/11) at the last.
SpdSystem path_system(int n) {
  SpdSystem s;
  s.n = n;
  s.diag.assign(n, 2);
  s.xadj.push_back(0);
  for (int i = 0; i < n; ++i) {
    if (i > 0) s.adj.push_back(i - 1), s.val.push_back(-1);
    if (i + 1 < n) s.adj.push_back(i + 1), s.val.push_back(-1);
    s.xadj.push_back(static_cast<int>(s.adj.size()));
  }
  s.rhs_rows = {0, n - 1};
  s.rhs_x = {Rational(1, 3), Rational(5)};
  s.rhs_y = {Rational(0), Rational(-7, 11)};
  s.magnitude = 5;
  return s;
}

// max |A x - b| over rows and both coordinates, exactly.
Rational residual(const SpdSystem& s, const std::vector<Point2q>& x);
Rational residual(const SpdSystem& s, const RefinementResult& r) {
  std::vector<Point2q> x(s.n);
  for (int i = 0; i < s.n; ++i) x[i] = r.iterate().point(i);
  return residual(s, x);
}
Rational residual(const SpdSystem& s, const std::vector<Point2q>& x) {
  Rational worst = 0;
  for (int i = 0; i < s.n; ++i)
    for (int c = 0; c < 2; ++c) {
      Rational r = s.diag[i] * (c == 0 ? x[i].x : x[i].y);
      for (int k = s.xadj[i]; k < s.xadj[i + 1]; ++k) r += s.val[k] * (c == 0 ? x[s.adj[k]].x : x[s.adj[k]].y);
      for (std::size_t b = 0; b < s.rhs_rows.size(); ++b)
        if (s.rhs_rows[b] == i) r -= c == 0 ? s.rhs_x[b] : s.rhs_y[b];
      if (abs(r) > worst) worst = abs(r);
    }
  return worst;
}

const RefinementNames names{"test", "unknowns", "the exact solution"};

}  // namespace

TEST_CASE("exact refinement: the double solution when the certificate accepts it, steps when forced") {
  const SpdSystem s = path_system(7);
  int calls = 0;
  RefinementResult r = refine_until_certified(
      s, [&](const RefinementIterate&) { ++calls;
        return std::int64_t(0);
      }, {}, names);
  CHECK(calls == 1);
  CHECK(r.stats.iterations == 0);
  CHECK(residual(s, r) < Rational(1, 1 << 20));
  RefinementOptions o;
  o.min_iterations = 4;
  r = refine_until_certified(s, [](const RefinementIterate&) { return std::int64_t(0); }, o, names);
  CHECK(r.stats.iterations <= 4);  // may stop earlier on an exactly zero residual
  CHECK(residual(s, r) < Rational(1, 1 << 30) * Rational(1, 1 << 30));
}

TEST_CASE("exact refinement: a certificate that needs accuracy drives the steps, grid values are exact") {
  const SpdSystem s = path_system(9);
  // accept only once the exact residual is below 2^-120: needs several steps
  Rational tiny(1);
  mpq_div_2exp(tiny.get_mpq_t(), tiny.get_mpq_t(), 120);
  const RefinementResult r = refine_until_certified(
      s,
      [&](const RefinementIterate& x) {
        std::vector<Point2q> p(s.n);
        for (int i = 0; i < s.n; ++i) p[i] = x.point(i);
        return std::int64_t(residual(s, p) < tiny ? 0 : 1);
      },
      {}, names);
  CHECK(residual(s, r) < tiny);
  CHECK(r.stats.iterations >= 2);
  CHECK(r.stats.flips_per_iteration.back() == 0);
  CHECK(r.stats.grid_exponent > 100);
}

TEST_CASE("exact refinement: the bound, then the exact fallback, or a typed error when too large") {
  const SpdSystem s = path_system(6);
  RefinementOptions o;
  o.max_iterations = 3;
  auto only_exact = [](const RefinementIterate& x) {
    return std::int64_t(x.mode == RefinementIterate::Mode::Exact ? 0 : 1);
  };
  const RefinementResult r = refine_until_certified(s, only_exact, o, names);
  CHECK(r.stats.exact_fallback);
  CHECK(r.stats.iterations == 3);
  CHECK(residual(s, r) == 0);
  o.exact_fallback_max_unknowns = 5;
  try {
    refine_until_certified(s, only_exact, o, names);
    FAIL("no error past the fallback limit");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Internal);
    CHECK(std::string(e.what()).find("unknowns 6") != std::string::npos);
  }
  try {
    refine_until_certified(s, [](const RefinementIterate&) { return std::int64_t(2); }, RefinementOptions{}, names);
    FAIL("an uncertifiable solution was returned");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Internal);
    CHECK(std::string(e.what()).find("the exact solution has 2") != std::string::npos);
  }
  RefinementOptions wrong;
  wrong.min_iterations = 5;
  wrong.max_iterations = 4;
  CHECK_THROWS_AS(refine_until_certified(s, only_exact, wrong, names), Error);
  SpdSystem singular = s;
  singular.diag.assign(s.n, 0);  // not positive definite
  CHECK_THROWS_AS(refine_until_certified(singular, only_exact, {}, names), Error);
}
