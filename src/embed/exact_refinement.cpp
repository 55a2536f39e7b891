#include "igm/embed/exact_refinement.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <map>

#include "igm/core/error.h"
#include "igm/embed/sparse_cholesky.h"

// Convergence of the refinement (why the loop terminates, and its bound).
//
// Let A be the system matrix (symmetric positive definite, integer), b the exact rational
// right-hand side and x* = A^-1 b the exact solution; the callers' theorems (Tutte/Floater for
// the disk, Aigerman & Lipman for the orbifold) say the certificate holds at x* with a margin:
// every triangle has area >= alpha > 0.
//
// Each step computes r = b - A x EXACTLY (x is dyadic, A integer, b rational), then solves
// A d = r in double with the fixed Cholesky factor: backward stability of Cholesky gives
// ||d~ - d|| <= rho ||d|| with rho ~ c n u kappa(A) (u = 2^-53), and x + d~ is rounded to a grid
// 2^-50 ||d~|| fine. Hence ||x_{k+1} - x*|| <= (rho + 2^-49) ||x_k - x*||: linear convergence
// whenever rho < 1/2 (kappa(A) up to ~2^40), gaining log2(1/rho) bits per step. Triangle areas
// are Lipschitz in the coordinates (constant ~ the domain diameter), so once the error is below
// ~alpha / diam all triangles are positive and the loop stops. The number of steps is about
// log2(diam^2 / alpha) / log2(1/rho); it is bounded by RefinementOptions::max_iterations, after
// which small systems are solved exactly (the rational x* itself) and large ones are reported.

namespace igm {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Sign of p*q - r*s for big integers: exact __int128 when all fit in 63 bits, else a double
// filter on (mantissa, exponent) pairs with a proven bound, else exact GMP products.
Sign det_sign(GridScratch& t) {
  if (mpz_fits_slong_p(t.p.get_mpz_t()) && mpz_fits_slong_p(t.q.get_mpz_t()) &&
      mpz_fits_slong_p(t.r.get_mpz_t()) && mpz_fits_slong_p(t.s.get_mpz_t())) {
    const __int128 det = static_cast<__int128>(mpz_get_si(t.p.get_mpz_t())) * mpz_get_si(t.q.get_mpz_t()) -
                         static_cast<__int128>(mpz_get_si(t.r.get_mpz_t())) * mpz_get_si(t.s.get_mpz_t());
    return det > 0 ? Sign::Positive : (det < 0 ? Sign::Negative : Sign::Zero);
  }
  // mpz_get_d_2exp truncates: mantissa m in [0.5, 1) (signed) with relative error < 2^-52.
  long ep, eq, er, es;
  const double mp = mpz_get_d_2exp(&ep, t.p.get_mpz_t()), mq = mpz_get_d_2exp(&eq, t.q.get_mpz_t());
  const double mr = mpz_get_d_2exp(&er, t.r.get_mpz_t()), ms = mpz_get_d_2exp(&es, t.s.get_mpz_t());
  const int sa = (mp > 0) == (mq > 0) ? 1 : -1;  // sign of p*q when both non-zero
  const int sb = (mr > 0) == (ms > 0) ? 1 : -1;
  const bool za = mp == 0 || mq == 0, zb = mr == 0 || ms == 0;  // zero is exact
  if (za && zb) return Sign::Zero;
  if (za) return sb > 0 ? Sign::Negative : Sign::Positive;
  if (zb) return sa > 0 ? Sign::Positive : Sign::Negative;
  const long ea = ep + eq, eb = er + es;
  // |p q| >= 2^(ea-2) and |r s| < 2^eb: a gap of 3 in the exponents decides.
  if (ea >= eb + 3) return sa > 0 ? Sign::Positive : Sign::Negative;
  if (eb >= ea + 3) return sb > 0 ? Sign::Negative : Sign::Positive;
  const long m = std::max(ea, eb);
  const double A = std::ldexp(mp * mq, static_cast<int>(ea - m));  // exact scaling by 2^0..2^-2
  const double B = std::ldexp(mr * ms, static_cast<int>(eb - m));
  const double det = A - B;
  // |A - Atrue| <= ((1+2u)^2(1+u) - 1)|Atrue| < 5.1u |Atrue|, same for B, plus u|A - B| for the
  // subtraction: total < 6.2u (|A| + |B|) < 2^-50 fl(|A| + |B|).
  const double err = 0x1p-50 * (std::fabs(A) + std::fabs(B));
  if (det > err) return Sign::Positive;
  if (-det > err) return Sign::Negative;
  mpz_mul(t.t1.get_mpz_t(), t.p.get_mpz_t(), t.q.get_mpz_t());
  mpz_mul(t.t2.get_mpz_t(), t.r.get_mpz_t(), t.s.get_mpz_t());
  const int c = cmp(t.t1, t.t2);
  return c > 0 ? Sign::Positive : (c < 0 ? Sign::Negative : Sign::Zero);
}

// Exact value Y * 2^-e.
Rational grid_value(const mpz_class& Y, std::int64_t e) {
  Rational q(Y);
  if (e >= 0)
    mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
  else
    mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
  return q;
}

// (mantissa, exponent) of a non-zero rational num/den as a double pair; value = m * 2^e.
void rational_to_me(const mpz_class& num, const mpz_class& den, double& m, long& e) {
  long en, ed;
  const double dn = mpz_get_d_2exp(&en, num.get_mpz_t());
  const double dd = mpz_get_d_2exp(&ed, den.get_mpz_t());
  m = dn / dd;
  e = en - ed;
}

// acc += v * z for a small integer v (the common values +-1 without a multiplication).
void add_scaled(mpz_class& acc, int v, const mpz_class& z) {
  if (v == -1)
    mpz_sub(acc.get_mpz_t(), acc.get_mpz_t(), z.get_mpz_t());
  else if (v == 1)
    mpz_add(acc.get_mpz_t(), acc.get_mpz_t(), z.get_mpz_t());
  else if (v > 0)
    mpz_addmul_ui(acc.get_mpz_t(), z.get_mpz_t(), static_cast<unsigned long>(v));
  else if (v < 0)
    mpz_submul_ui(acc.get_mpz_t(), z.get_mpz_t(), static_cast<unsigned long>(-static_cast<long>(v)));
}

// Exact solution of A x = b by sparse symmetric elimination in rationals along a minimum-degree
// (AMD) order: row k keeps its entries in columns >= k (the upper factor U = D L^T).
std::vector<Point2q> exact_solve(const SpdSystem& S, const std::string& who) {
  const int m = S.n;
  Eigen::SparseMatrix<double> A(m, m);
  {
    std::vector<Eigen::Triplet<double>> trip;
    for (int i = 0; i < m; ++i) {
      trip.emplace_back(i, i, static_cast<double>(S.diag[i]));
      for (int k = S.xadj[i]; k < S.xadj[i + 1]; ++k) trip.emplace_back(i, S.adj[k], static_cast<double>(S.val[k]));
    }
    A.setFromTriplets(trip.begin(), trip.end());
  }
  Eigen::AMDOrdering<int> amd;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm;
  amd(A, perm);
  std::vector<int> pos(m);  // elimination position of unknown i
  for (int k = 0; k < m; ++k) pos[perm.indices()(k)] = k;
  std::vector<std::map<int, Rational>> row(m);
  std::vector<Rational> rx(m), ry(m);
  for (int i = 0; i < m; ++i) {
    const int pi = pos[i];
    row[pi][pi] += S.diag[i];
    for (int k = S.xadj[i]; k < S.xadj[i + 1]; ++k) {
      const int pj = pos[S.adj[k]];
      if (pj > pi) row[pi][pj] += S.val[k];
    }
  }
  for (std::size_t k = 0; k < S.rhs_rows.size(); ++k) {
    rx[pos[S.rhs_rows[k]]] = S.rhs_x[k];
    ry[pos[S.rhs_rows[k]]] = S.rhs_y[k];
  }
  for (int k = 0; k < m; ++k) {  // O(sum over pivots of (row length)^2) rational operations
    const Rational pivot = row[k].at(k);
    if (sgn(pivot) <= 0) throw Error(ErrorKind::Internal, who + ": non-positive pivot in exact solve");
    for (auto it = row[k].upper_bound(k); it != row[k].end(); ++it) {
      const int j = it->first;
      const Rational f = it->second / pivot;
      for (auto jt = it; jt != row[k].end(); ++jt) {
        Rational& a = row[j][jt->first];
        a -= f * jt->second;
      }
      rx[j] -= f * rx[k];
      ry[j] -= f * ry[k];
    }
  }
  std::vector<Rational> sx(m), sy(m);
  for (int k = m - 1; k >= 0; --k) {
    Rational ax = rx[k], ay = ry[k];
    for (auto it = row[k].upper_bound(k); it != row[k].end(); ++it) {
      ax -= it->second * sx[it->first];
      ay -= it->second * sy[it->first];
    }
    sx[k] = ax / row[k].at(k);
    sy[k] = ay / row[k].at(k);
  }
  std::vector<Point2q> x(m);
  for (int i = 0; i < m; ++i) x[i] = Point2q{sx[pos[i]], sy[pos[i]]};
  return x;
}

}  // namespace

Point2q RefinementIterate::point(int i) const {
  switch (mode) {
    case Mode::Double: return Point2q{to_rational((*xd)[i]), to_rational((*yd)[i])};
    case Mode::Grid: return Point2q{grid_value((*X)[i], e), grid_value((*Y)[i], e)};
    default: return (*exact)[i];
  }
}

Sign grid_orient(const mpz_class& ax, const mpz_class& ay, const mpz_class& bx, const mpz_class& by,
                 const mpz_class& cx, const mpz_class& cy, GridScratch& s) {
  mpz_sub(s.p.get_mpz_t(), ax.get_mpz_t(), cx.get_mpz_t());
  mpz_sub(s.q.get_mpz_t(), by.get_mpz_t(), cy.get_mpz_t());
  mpz_sub(s.r.get_mpz_t(), ay.get_mpz_t(), cy.get_mpz_t());
  mpz_sub(s.s.get_mpz_t(), bx.get_mpz_t(), cx.get_mpz_t());
  return det_sign(s);
}

RefinementResult refine_until_certified(const SpdSystem& S, const RefinementCertificate& certificate,
                                        const RefinementOptions& options, const RefinementNames& names) {
  RefinementResult result;
  RefinementStats& st = result.stats;
  const int m = S.n;
  const std::string& who = names.who;
  if (m < 1) throw Error(ErrorKind::Internal, who + ": empty system");
  if (options.max_iterations < 0 || options.min_iterations > options.max_iterations)
    throw Error(ErrorKind::InvalidArgument, who + ": need 0 <= min_iterations <= max_iterations, got " +
                                                std::to_string(options.min_iterations) + " and " +
                                                std::to_string(options.max_iterations));
  std::vector<double>&xd = result.xd, &yd = result.yd;
  std::vector<mpz_class>&X = result.X, &Y = result.Y;
  std::vector<Point2q>& exact = result.exact;
  std::int64_t& e = result.e;
  auto check = [&](RefinementIterate::Mode mode) {
    const auto t0 = Clock::now();
    result.mode = mode;
    const std::int64_t bad = certificate(result.iterate());
    st.seconds_checks += since(t0);
    return bad;
  };
  auto finish = [&](RefinementIterate::Mode mode) {
    result.mode = mode;
    return std::move(result);
  };

  // ---------------- double solve ----------------
  auto t0 = Clock::now();
  SparseCholesky chol;
  {
    std::vector<double> val(S.val.begin(), S.val.end()), diag(S.diag.begin(), S.diag.end());
    // one factorization of a disk's Laplacian: the BFS level sets (sparse_cholesky.h, Ordering)
    chol.factorize(S.xadj, S.adj, val, diag, SparseCholesky::Ordering::LevelSets);  // throws Internal if not PD
  }
  st.factor_entries = chol.factor_entries();
  st.seconds_factorization = since(t0);

  t0 = Clock::now();
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, 2);
  for (std::size_t k = 0; k < S.rhs_rows.size(); ++k) {
    rhs(S.rhs_rows[k], 0) = to_double(S.rhs_x[k]);
    rhs(S.rhs_rows[k], 1) = to_double(S.rhs_y[k]);
  }
  Eigen::MatrixXd sol = rhs;
  chol.solve(sol);
  xd.resize(m);
  yd.resize(m);
  for (int i = 0; i < m; ++i) {
    xd[i] = sol(i, 0);
    yd[i] = sol(i, 1);
    if (!std::isfinite(xd[i]) || !std::isfinite(yd[i]))
      throw Error(ErrorKind::Internal, who + ": the double solve produced a non-finite value");
  }
  st.seconds_solve = since(t0);

  st.flips_double = check(RefinementIterate::Mode::Double);
  if (st.flips_double == 0 && options.min_iterations <= 0) return finish(RefinementIterate::Mode::Double);

  // ---------------- mixed-precision refinement ----------------
  const auto t_ref = Clock::now();
  const double seconds_checks_before = st.seconds_checks;
  {
    // Initial grid: 2^-e with max |coordinate| * 2^e ~ 2^52, so the doubles round to int64.
    double M = 0;
    for (int i = 0; i < m; ++i) M = std::max({M, std::fabs(xd[i]), std::fabs(yd[i])});
    M = std::max(M, S.magnitude);
    int ex = 0;
    std::frexp(M, &ex);  // M < 2^ex
    e = 52 - ex;
    X.resize(m);
    Y.resize(m);
    for (int i = 0; i < m; ++i) {
      X[i] = static_cast<long>(std::llround(std::ldexp(xd[i], static_cast<int>(e))));
      Y[i] = static_cast<long>(std::llround(std::ldexp(yd[i], static_cast<int>(e))));
    }
  }
  std::vector<double> rm(2 * static_cast<std::size_t>(m));  // residual mantissas (x then y)
  std::vector<long> re(2 * static_cast<std::size_t>(m));    // and exponents
  mpz_class acc, num, den, dY;
  bool done = false, zero_residual = false;
  // Bound: at most options.max_iterations steps (each O(nnz) big-integer operations).
  for (int iter = 0; iter < options.max_iterations && !done; ++iter) {
    // Exact residual in grid units: R = 2^e b - A Y.
    long emax = LONG_MIN;
    std::size_t bk = 0;
    for (int i = 0; i < m; ++i) {
      const bool has_b = bk < S.rhs_rows.size() && S.rhs_rows[bk] == i;
      for (int c = 0; c < 2; ++c) {
        const std::vector<mpz_class>& Z = c == 0 ? X : Y;
        mpz_mul_si(acc.get_mpz_t(), Z[i].get_mpz_t(), S.diag[i]);
        for (int k = S.xadj[i]; k < S.xadj[i + 1]; ++k) add_scaled(acc, S.val[k], Z[S.adj[k]]);
        double mant;
        long ex;
        if (has_b) {
          const Rational& b = c == 0 ? S.rhs_x[bk] : S.rhs_y[bk];
          // R = (2^e num(b) - den(b) acc) / den(b)   (e >= 0), or with 2^-e on the other side.
          if (e >= 0) {
            mpz_mul_2exp(num.get_mpz_t(), b.get_num_mpz_t(), static_cast<mp_bitcnt_t>(e));
            mpz_submul(num.get_mpz_t(), b.get_den_mpz_t(), acc.get_mpz_t());
            den = b.get_den();
          } else {
            mpz_mul_2exp(den.get_mpz_t(), b.get_den_mpz_t(), static_cast<mp_bitcnt_t>(-e));
            num = b.get_num();
            mpz_submul(num.get_mpz_t(), den.get_mpz_t(), acc.get_mpz_t());
          }
          if (sgn(num) == 0) {
            mant = 0;
            ex = 0;
          } else {
            rational_to_me(num, den, mant, ex);
          }
        } else {
          mant = -mpz_get_d_2exp(&ex, acc.get_mpz_t());
        }
        rm[2 * i + c] = mant;
        re[2 * i + c] = ex;
        if (mant != 0) emax = std::max(emax, ex);
      }
      if (has_b) ++bk;
    }
    if (emax == LONG_MIN) {  // residual exactly zero: x is the exact solution
      zero_residual = true;
      break;
    }
    // Scaled residual (max ~1) solved in double with the same factorization.
    for (int i = 0; i < m; ++i)
      for (int c = 0; c < 2; ++c) {
        const long sh = re[2 * i + c] - emax;
        rhs(i, c) = rm[2 * i + c] == 0 || sh < -1100 ? 0.0 : std::ldexp(rm[2 * i + c], static_cast<int>(sh));
      }
    sol = rhs;
    chol.solve(sol);
    double dmax = 0;
    for (int i = 0; i < m; ++i) dmax = std::max({dmax, std::fabs(sol(i, 0)), std::fabs(sol(i, 1))});
    if (!std::isfinite(dmax)) throw Error(ErrorKind::Internal, who + ": non-finite correction in refinement");
    if (dmax == 0) throw Error(ErrorKind::Internal, who + ": zero correction for a non-zero residual");
    int dex = 0;
    std::frexp(dmax, &dex);
    // New grid 2^-(e+s): the largest correction becomes ~2^50 new grid units.
    const long s = std::max(0L, 50L - dex - emax);
    const long scale = emax + s;  // correction in new grid units = sol * 2^scale
    for (int i = 0; i < m; ++i)
      for (int c = 0; c < 2; ++c) {
        mpz_class& Z = c == 0 ? X[i] : Y[i];
        mpz_mul_2exp(Z.get_mpz_t(), Z.get_mpz_t(), static_cast<mp_bitcnt_t>(s));
        const double v = sol(i, c);
        if (v == 0) continue;
        if (scale > 2000 || scale < -2000)
          throw Error(ErrorKind::Internal,
                      who + ": correction scale 2^" + std::to_string(scale) + " out of range in refinement");
        const double scaled = std::nearbyint(std::ldexp(v, static_cast<int>(scale)));
        if (!std::isfinite(scaled)) throw Error(ErrorKind::Internal, who + ": correction out of range in refinement");
        if (std::fabs(scaled) < 0x1p62) {
          const long q = static_cast<long>(scaled);
          if (q >= 0)
            mpz_add_ui(Z.get_mpz_t(), Z.get_mpz_t(), static_cast<unsigned long>(q));
          else
            mpz_sub_ui(Z.get_mpz_t(), Z.get_mpz_t(), static_cast<unsigned long>(-q));
        } else {
          mpz_set_d(dY.get_mpz_t(), scaled);
          mpz_add(Z.get_mpz_t(), Z.get_mpz_t(), dY.get_mpz_t());
        }
      }
    e += s;
    st.iterations = iter + 1;
    const std::int64_t flips = check(RefinementIterate::Mode::Grid);
    st.flips_per_iteration.push_back(flips);
    if (flips == 0 && st.iterations >= options.min_iterations) done = true;
  }
  st.grid_exponent = e;
  st.seconds_refinement = since(t_ref) - (st.seconds_checks - seconds_checks_before);
  if (done || (!st.flips_per_iteration.empty() && st.flips_per_iteration.back() == 0))
    return finish(RefinementIterate::Mode::Grid);
  if (zero_residual) {
    // X, Y are the exact solution, which the caller's theorem says is certified.
    const std::int64_t flips = check(RefinementIterate::Mode::Grid);
    if (flips != 0)
      throw Error(ErrorKind::Internal, who + ": " + names.solution + " has " + std::to_string(flips) +
                                           " non-positive triangles (pre-condition missed?)");
    return finish(RefinementIterate::Mode::Grid);
  }

  // ---------------- exact fallback ----------------
  if (m > options.exact_fallback_max_unknowns)
    throw Error(ErrorKind::Internal,
                who + ": refinement did not certify all triangles after " + std::to_string(st.iterations) + " steps (" +
                    names.unknowns + " " + std::to_string(m) + ", flips after double " +
                    std::to_string(st.flips_double) + ", last flips " +
                    (st.flips_per_iteration.empty() ? std::string("n/a")
                                                    : std::to_string(st.flips_per_iteration.back())) +
                    ", grid exponent " + std::to_string(e) + "); too large for the exact fallback (limit " +
                    std::to_string(options.exact_fallback_max_unknowns) + ")");
  const auto t_fb = Clock::now();
  st.exact_fallback = true;
  exact = exact_solve(S, who);
  st.seconds_fallback = since(t_fb);
  const std::int64_t flips = check(RefinementIterate::Mode::Exact);
  if (flips != 0)
    throw Error(ErrorKind::Internal, who + ": " + names.solution + " has " + std::to_string(flips) +
                                         " non-positive triangles (pre-condition missed?)");
  return finish(RefinementIterate::Mode::Exact);
}

}  // namespace igm
