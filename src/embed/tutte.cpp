#include "igm/embed/tutte.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <map>
#include <numeric>
#include <string>

#include "igm/core/error.h"
#include "igm/embed/polygon.h"
#include "igm/embed/sparse_cholesky.h"

// Convergence of the refinement (why the loop terminates, and its bound).
//
// Let A = L_II be the uniform Laplacian restricted to interior vertices (symmetric positive
// definite: weakly diagonally dominant, strictly on rows next to the boundary, and irreducible
// because the disk is connected), b the exact rational right-hand side (sums of boundary
// positions) and x* = A^-1 b the exact Tutte solution. By Tutte's theorem in Floater's form
// (convex boundary traversed once, convex-combination weights, no interior edge between two
// vertices of one side) x* is an embedding: every triangle has area >= alpha > 0 at x*.
//
// Each step computes r = b - A x EXACTLY (x is dyadic, A integer, b rational), then solves
// A d = r in double with the fixed Cholesky factor: backward stability of Cholesky gives
// ||d~ - d|| <= rho ||d|| with rho ~ c n u kappa(A) (u = 2^-53), and x + d~ is rounded to a grid
// 2^-50 ||d~|| fine. Hence ||x_{k+1} - x*|| <= (rho + 2^-49) ||x_k - x*||: linear convergence
// whenever rho < 1/2 (kappa(A) up to ~2^40), gaining log2(1/rho) bits per step. Triangle areas
// are Lipschitz in the coordinates (constant ~ the polygon diameter), so once the error is below
// ~alpha / diam all triangles are positive and the loop stops. The number of steps is about
// log2(diam^2 / alpha) / log2(1/rho); it is bounded by TutteOptions::max_iterations, after
// which small meshes are solved exactly (the rational x* itself) and large ones are reported.

namespace igm {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

[[noreturn]] void bad(const std::string& message, std::vector<std::int64_t> elements) {
  throw Error(ErrorKind::InvalidArgument, "tutte_embed: " + message, std::move(elements));
}

std::string edge_str(int a, int b) {
  std::string s = "(";  // appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on "(" + to_string(a)
  s.append(std::to_string(a)).append(", ").append(std::to_string(b)).append(")");
  return s;
}

// Half-edge structure of the input disk. Half-edge 3f+i runs from triangles[f][i] to
// triangles[f][(i+1)%3]; twin is -1 on the boundary.
struct Disk {
  int nv = 0, nf = 0;
  std::vector<int> origin, twin;
  std::vector<int> out_begin, out;  // CSR: half-edges leaving each vertex, sorted by target
  std::vector<int> out_target;      // target of out[k]
  int target(int h) const { return origin[h % 3 == 2 ? h - 2 : h + 1]; }
  static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
};

// Which polygon sides each boundary position lies on: side_in[i] is the side of the boundary
// edge ending at i, side_out[i] the side of the edge starting at i (equal except at corners).
struct Sides {
  std::vector<int> side_in, side_out;
  bool share(int i, int j) const {
    return side_in[i] == side_in[j] || side_in[i] == side_out[j] || side_out[i] == side_in[j] ||
           side_out[i] == side_out[j];
  }
  bool has(int i, int s) const { return side_in[i] == s || side_out[i] == s; }
};

Sides check_boundary_polygon(const std::vector<int>& boundary, const std::vector<Point2q>& P) {
  const int n = static_cast<int>(P.size());
  std::vector<char> corner(n, 0);
  std::vector<Point2q> corners;
  int first_corner = -1;
  for (int i = 0; i < n; ++i) {
    const Point2q& a = P[(i + n - 1) % n];
    const Point2q& b = P[i];
    const Point2q& c = P[(i + 1) % n];
    const Sign s = orient2d(a, b, c);
    if (s == Sign::Negative)
      bad("boundary polygon turns clockwise (not convex counter-clockwise) at boundary vertex " +
              std::to_string(boundary[i]),
          {boundary[i]});
    if (s == Sign::Zero) {
      const Rational dot = (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y);
      if (sgn(dot) <= 0)
        bad("boundary position of vertex " + std::to_string(boundary[i]) +
                " repeats or goes back along its side",
            {boundary[i]});
    } else {
      corner[i] = 1;
      corners.push_back(b);
      if (first_corner < 0) first_corner = i;
    }
  }
  if (corners.size() < 3 || !is_strictly_convex_ccw(corners))
    bad("boundary positions do not form a convex polygon traversed once counter-clockwise", {});
  Sides sides;
  sides.side_in.assign(n, -1);
  sides.side_out.assign(n, -1);
  int side = 0;
  for (int k = 0; k < n; ++k) {
    const int i = (first_corner + k) % n;
    if (corner[i] && k > 0) ++side;
    sides.side_out[i] = side;
    sides.side_in[(i + 1) % n] = side;
  }
  return sides;
}

Disk build_and_check_disk(int nv, const std::vector<std::array<int, 3>>& tris,
                          const std::vector<int>& boundary, std::vector<int>& bpos) {
  Disk d;
  d.nv = nv;
  d.nf = static_cast<int>(tris.size());
  const int nh = 3 * d.nf;
  d.origin.resize(nh);
  for (int f = 0; f < d.nf; ++f) {
    const auto& t = tris[f];
    for (int i = 0; i < 3; ++i) {
      if (t[i] < 0 || t[i] >= nv)
        bad("triangle " + std::to_string(f) + " refers to vertex " + std::to_string(t[i]) +
                " outside 0.." + std::to_string(nv - 1),
            {f});
      d.origin[3 * f + i] = t[i];
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      bad("triangle " + std::to_string(f) + " repeats a vertex", {f});
  }
  // CSR of outgoing half-edges, each bucket sorted by target: O(F log valence).
  d.out_begin.assign(nv + 1, 0);
  for (int h = 0; h < nh; ++h) ++d.out_begin[d.origin[h] + 1];
  for (int v = 0; v < nv; ++v) d.out_begin[v + 1] += d.out_begin[v];
  {
    // Sort keys (target << 32 | half-edge) inside each bucket: contiguous integer sorts.
    std::vector<std::uint64_t> key(nh);
    std::vector<int> fill(d.out_begin.begin(), d.out_begin.end() - 1);
    for (int h = 0; h < nh; ++h)
      key[fill[d.origin[h]]++] = (static_cast<std::uint64_t>(d.target(h)) << 32) | static_cast<std::uint32_t>(h);
    d.out.resize(nh);
    d.out_target.resize(nh);
    for (int v = 0; v < nv; ++v) {
      if (d.out_begin[v] == d.out_begin[v + 1])
        bad("vertex " + std::to_string(v) + " is used by no triangle", {v});
      std::sort(key.begin() + d.out_begin[v], key.begin() + d.out_begin[v + 1]);
      for (int k = d.out_begin[v]; k < d.out_begin[v + 1]; ++k) {
        d.out[k] = static_cast<int>(key[k] & 0xffffffffu);
        d.out_target[k] = static_cast<int>(key[k] >> 32);
        if (k > d.out_begin[v] && d.out_target[k] == d.out_target[k - 1])
          bad("edge " + edge_str(v, d.out_target[k]) +
                  " has two triangles in the same direction (non-manifold or inconsistently oriented)",
              {v, d.out_target[k]});
      }
    }
  }
  d.twin.assign(nh, -1);
  int num_boundary_he = 0;
  for (int h = 0; h < nh; ++h) {
    const int a = d.origin[h], b = d.target(h);
    auto first = d.out_target.begin() + d.out_begin[b], last = d.out_target.begin() + d.out_begin[b + 1];
    auto it = std::lower_bound(first, last, a);
    if (it != last && *it == a)
      d.twin[h] = d.out[it - d.out_target.begin()];
    else
      ++num_boundary_he;
  }
  // The boundary loop must be exactly the given cycle, in the given orientation.
  const int nb = static_cast<int>(boundary.size());
  bpos.assign(nv, -1);
  for (int i = 0; i < nb; ++i) {
    const int v = boundary[i];
    if (v < 0 || v >= nv)
      bad("boundary entry " + std::to_string(i) + " is vertex " + std::to_string(v) +
              ", outside 0.." + std::to_string(nv - 1),
          {v});
    if (bpos[v] >= 0) bad("vertex " + std::to_string(v) + " appears twice in the boundary cycle", {v});
    bpos[v] = i;
  }
  for (int v = 0; v < nv; ++v) {
    int count = 0, to = -1;
    for (int k = d.out_begin[v]; k < d.out_begin[v + 1]; ++k)
      if (d.twin[d.out[k]] < 0) {
        ++count;
        to = d.target(d.out[k]);
      }
    if (bpos[v] < 0) {
      if (count > 0)
        bad("edge " + edge_str(v, to) + " is on the mesh boundary but vertex " + std::to_string(v) +
                " is not in the boundary cycle (several boundary loops?)",
            {v, to});
      continue;
    }
    const int expect = boundary[(bpos[v] + 1) % nb];
    if (count == 0)
      bad("boundary vertex " + std::to_string(v) + " is interior in the mesh", {v});
    if (count > 1) bad("vertex " + std::to_string(v) + " lies on the mesh boundary twice (pinched)", {v});
    if (to != expect)
      bad("mesh boundary runs " + edge_str(v, to) + " but the boundary cycle runs " +
              edge_str(v, expect) + " (other loop or opposite orientation)",
          {v, to});
  }
  if (num_boundary_he != nb)
    bad("the mesh has " + std::to_string(num_boundary_he) + " boundary edges, the cycle has " +
            std::to_string(nb),
        {});
  // One fan per vertex: rotating counter-clockwise (h -> twin(prev(h))) from the outgoing
  // boundary half-edge (or any half-edge of an interior vertex) must visit every triangle at v.
  // Each walk takes at most valence + 1 steps.
  for (int v = 0; v < nv; ++v) {
    const int deg = d.out_begin[v + 1] - d.out_begin[v];
    int start = d.out[d.out_begin[v]];
    if (bpos[v] >= 0)
      for (int k = d.out_begin[v]; k < d.out_begin[v + 1]; ++k)
        if (d.twin[d.out[k]] < 0) start = d.out[k];
    int h = start, visited = 0;
    while (visited <= deg) {
      ++visited;
      const int t = d.twin[Disk::prev(h)];
      if (t < 0 || t == start) break;
      h = t;
    }
    if (visited != deg)
      bad("vertex " + std::to_string(v) + " is non-manifold (its triangles form several fans)", {v});
  }
  // Connected, and Euler characteristic 1: with one boundary loop this is a disk.
  {
    std::vector<char> seen(d.nf, 0);
    std::vector<int> stack{0};
    seen[0] = 1;
    int reached = 1;
    while (!stack.empty()) {  // each face pushed once: O(F)
      const int f = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const int t = d.twin[3 * f + i];
        if (t >= 0 && !seen[t / 3]) {
          seen[t / 3] = 1;
          ++reached;
          stack.push_back(t / 3);
        }
      }
    }
    if (reached != d.nf) {
      int f = 0;
      while (seen[f]) ++f;
      bad("the mesh is not connected (triangle " + std::to_string(f) + " is not reached from triangle 0)",
          {f});
    }
  }
  const std::int64_t edges = (std::int64_t(nh) + num_boundary_he) / 2;
  const std::int64_t chi = std::int64_t(nv) - edges + d.nf;
  if (chi != 1)
    bad("Euler characteristic is " + std::to_string(chi) + ", a disk has 1 (handles inside?)", {});
  return d;
}

// Scratch integers for the grid orientation test (no allocation per triangle).
struct Scratch {
  mpz_class p, q, r, s, t1, t2;
};

// Sign of p*q - r*s for big integers: exact __int128 when all fit in 63 bits, else a double
// filter on (mantissa, exponent) pairs with a proven bound, else exact GMP products.
Sign det_sign(Scratch& t) {
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

// Exact position of interior vertex i on the grid: Y * 2^-e.
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

}  // namespace

TutteResult tutte_embed(int num_vertices, const std::vector<std::array<int, 3>>& triangles,
                        const std::vector<int>& boundary, const std::vector<Point2q>& boundary_uv,
                        const TutteOptions& options) {
  const auto t_start = Clock::now();
  TutteResult result;
  TutteStats& st = result.stats;
  if (num_vertices < 3) bad("needs at least 3 vertices, got " + std::to_string(num_vertices), {});
  if (triangles.empty()) bad("no triangles", {});
  if (boundary.size() < 3) bad("the boundary cycle needs at least 3 vertices", {});
  if (boundary.size() != boundary_uv.size())
    bad(std::to_string(boundary.size()) + " boundary vertices but " +
            std::to_string(boundary_uv.size()) + " boundary positions",
        {});
  if (options.max_iterations < 0) bad("max_iterations must be >= 0", {});
  if (options.min_iterations > options.max_iterations)
    bad("min_iterations must be <= max_iterations", {});

  // ---------------- pre-conditions ----------------
  std::vector<int> bpos;
  const Disk d = build_and_check_disk(num_vertices, triangles, boundary, bpos);
  const Sides sides = check_boundary_polygon(boundary, boundary_uv);
  for (int f = 0; f < d.nf; ++f) {
    const auto& t = triangles[f];
    if (bpos[t[0]] < 0 || bpos[t[1]] < 0 || bpos[t[2]] < 0) continue;
    const int i = bpos[t[0]], j = bpos[t[1]], k = bpos[t[2]];
    for (int s : {sides.side_in[i], sides.side_out[i]})
      if (sides.has(j, s) && sides.has(k, s))
        bad("triangle " + std::to_string(f) + " has its three vertices on polygon side " +
                std::to_string(s) + " (degenerate; split first)",
            {f});
  }

  for (int h = 0; h < 3 * d.nf; ++h) {
    const int a = d.origin[h], b = d.target(h);
    if (d.twin[h] >= 0 && a < b && bpos[a] >= 0 && bpos[b] >= 0 && sides.share(bpos[a], bpos[b]))
      bad("interior edge " + edge_str(a, b) +
              " joins two boundary vertices on the same polygon side (split it first)",
          {a, b});
  }
  // ---------------- interior system ----------------
  const int nv = num_vertices;
  std::vector<int> idx(nv, -1), vert;
  for (int v = 0; v < nv; ++v)
    if (bpos[v] < 0) {
      idx[v] = static_cast<int>(vert.size());
      vert.push_back(v);
    }
  const int m = static_cast<int>(vert.size());
  st.seconds_validate = since(t_start);
  const auto t_assemble = Clock::now();
  st.interior_vertices = m;
  st.boundary_vertices = static_cast<int>(boundary.size());
  st.triangles = d.nf;
  // Interior neighbours in CSR; degrees; exact right-hand side on rows next to the boundary.
  std::vector<int> nb_begin(m + 1, 0), nb;
  std::vector<int> deg(m);
  std::vector<int> brow;            // interior rows with boundary neighbours
  std::vector<Rational> bx, by;     // their exact right-hand sides
  nb.reserve(3 * static_cast<std::size_t>(d.nf));
  for (int i = 0; i < m; ++i) {
    const int v = vert[i];
    deg[i] = d.out_begin[v + 1] - d.out_begin[v];  // interior vertex: one out-edge per neighbour
    Rational sx = 0, sy = 0;
    bool touches = false;
    for (int k = d.out_begin[v]; k < d.out_begin[v + 1]; ++k) {
      const int w = d.out_target[k];
      if (idx[w] >= 0)
        nb.push_back(idx[w]);
      else {
        touches = true;
        sx += boundary_uv[bpos[w]].x;
        sy += boundary_uv[bpos[w]].y;
      }
    }
    nb_begin[i + 1] = static_cast<int>(nb.size());
    if (touches) {
      brow.push_back(i);
      bx.push_back(sx);
      by.push_back(sy);
    }
  }
  st.seconds_assemble = since(t_assemble);

  // Orientation checks. Triangles with a boundary vertex use exact rationals; the others the
  // filter of the current representation (doubles, or the common grid 2^-e).
  enum class Mode { Double, Grid, Exact };
  std::vector<double> xd, yd;                   // Mode::Double
  std::vector<mpz_class> X, Y;                  // Mode::Grid: x = X * 2^-e
  std::int64_t e = 0;
  std::vector<Point2q> exact_interior;          // Mode::Exact
  auto point_of = [&](int v, Mode mode) -> Point2q {
    if (bpos[v] >= 0) return boundary_uv[bpos[v]];
    const int i = idx[v];
    if (mode == Mode::Double) return Point2q{to_rational(xd[i]), to_rational(yd[i])};
    if (mode == Mode::Grid) return Point2q{grid_value(X[i], e), grid_value(Y[i], e)};
    return exact_interior[i];
  };
  auto count_flips = [&](Mode mode) -> std::int64_t {
    const auto t0 = Clock::now();
    std::int64_t flips = 0;
    Scratch s;
    for (int f = 0; f < d.nf; ++f) {
      const auto& t = triangles[f];
      Sign o;
      if (mode == Mode::Exact || bpos[t[0]] >= 0 || bpos[t[1]] >= 0 || bpos[t[2]] >= 0) {
        o = orient2d(point_of(t[0], mode), point_of(t[1], mode), point_of(t[2], mode));
      } else {
        const int a = idx[t[0]], b = idx[t[1]], c = idx[t[2]];
        if (mode == Mode::Double) {
          o = orient2d(Vec2d{xd[a], yd[a]}, Vec2d{xd[b], yd[b]}, Vec2d{xd[c], yd[c]});
        } else {
          mpz_sub(s.p.get_mpz_t(), X[a].get_mpz_t(), X[c].get_mpz_t());
          mpz_sub(s.q.get_mpz_t(), Y[b].get_mpz_t(), Y[c].get_mpz_t());
          mpz_sub(s.r.get_mpz_t(), Y[a].get_mpz_t(), Y[c].get_mpz_t());
          mpz_sub(s.s.get_mpz_t(), X[b].get_mpz_t(), X[c].get_mpz_t());
          o = det_sign(s);  // the common factor 2^-2e does not change the sign
        }
      }
      if (o != Sign::Positive) ++flips;
    }
    st.seconds_checks += since(t0);
    return flips;
  };
  auto finish = [&](Mode mode) {
    result.uv.resize(nv);
    for (int v = 0; v < nv; ++v) result.uv[v] = point_of(v, mode);
    std::size_t bits = 0;
    for (const Point2q& p : result.uv) bits = std::max({bits, bit_size(p.x), bit_size(p.y)});
    st.max_bits = bits;
    st.seconds_total = since(t_start);
  };

  if (m == 0) {  // every vertex on the boundary: the placement is the embedding
    st.flips_double = count_flips(Mode::Exact);
    if (st.flips_double != 0)
      throw Error(ErrorKind::Internal, "tutte_embed: a triangle of an all-boundary disk is not positive");
    finish(Mode::Exact);
    return result;
  }

  // ---------------- double solve ----------------
  auto t0 = Clock::now();
  SparseCholesky chol;
  {
    std::vector<double> val(nb.size(), -1.0), diag(m);
    for (int i = 0; i < m; ++i) diag[i] = static_cast<double>(deg[i]);
    chol.factorize(nb_begin, nb, val, diag);  // throws Internal if not positive definite
  }
  st.factor_entries = chol.factor_entries();
  st.seconds_factorization = since(t0);

  t0 = Clock::now();
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, 2);
  for (std::size_t k = 0; k < brow.size(); ++k) {
    rhs(brow[k], 0) = to_double(bx[k]);
    rhs(brow[k], 1) = to_double(by[k]);
  }
  Eigen::MatrixXd sol = rhs;
  chol.solve(sol);
  xd.resize(m);
  yd.resize(m);
  for (int i = 0; i < m; ++i) {
    xd[i] = sol(i, 0);
    yd[i] = sol(i, 1);
    if (!std::isfinite(xd[i]) || !std::isfinite(yd[i]))
      throw Error(ErrorKind::Internal, "tutte_embed: the double solve produced a non-finite value");
  }
  st.seconds_solve = since(t0);

  st.flips_double = count_flips(Mode::Double);
  if (st.flips_double == 0 && options.min_iterations <= 0) {
    finish(Mode::Double);
    return result;
  }

  // ---------------- mixed-precision refinement ----------------
  const auto t_ref = Clock::now();
  double seconds_checks_before = st.seconds_checks;
  {
    // Initial grid: 2^-e with max |coordinate| * 2^e ~ 2^52, so the doubles round to int64.
    double M = 0;
    for (int i = 0; i < m; ++i) M = std::max({M, std::fabs(xd[i]), std::fabs(yd[i])});
    for (const Point2q& p : boundary_uv) M = std::max({M, std::fabs(to_double(p.x)), std::fabs(to_double(p.y))});
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
  // Bound: at most options.max_iterations steps (each O(F) big-integer operations).
  for (int it = 0; it < options.max_iterations && !done; ++it) {
    // Exact residual in grid units: R = 2^e b - A Y.
    long emax = LONG_MIN;
    std::size_t bk = 0;
    for (int i = 0; i < m; ++i) {
      const bool has_b = bk < brow.size() && brow[bk] == i;
      for (int c = 0; c < 2; ++c) {
        const std::vector<mpz_class>& Z = c == 0 ? X : Y;
        mpz_mul_si(acc.get_mpz_t(), Z[i].get_mpz_t(), deg[i]);
        for (int k = nb_begin[i]; k < nb_begin[i + 1]; ++k) mpz_sub(acc.get_mpz_t(), acc.get_mpz_t(), Z[nb[k]].get_mpz_t());
        double mant;
        long ex;
        if (has_b) {
          const Rational& b = c == 0 ? bx[bk] : by[bk];
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
    if (emax == LONG_MIN) {  // residual exactly zero: x is the exact Tutte solution
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
    if (!std::isfinite(dmax))
      throw Error(ErrorKind::Internal, "tutte_embed: non-finite correction in refinement");
    if (dmax == 0)
      throw Error(ErrorKind::Internal, "tutte_embed: zero correction for a non-zero residual");
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
          throw Error(ErrorKind::Internal, "tutte_embed: correction scale 2^" + std::to_string(scale) +
                                               " out of range in refinement");
        const double scaled = std::nearbyint(std::ldexp(v, static_cast<int>(scale)));
        if (!std::isfinite(scaled))
          throw Error(ErrorKind::Internal, "tutte_embed: correction out of range in refinement");
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
    st.iterations = it + 1;
    const std::int64_t flips = count_flips(Mode::Grid);
    st.flips_per_iteration.push_back(flips);
    if (flips == 0 && st.iterations >= options.min_iterations) done = true;
  }
  st.grid_exponent = e;
  st.seconds_refinement = since(t_ref) - (st.seconds_checks - seconds_checks_before);
  if (done || (!st.flips_per_iteration.empty() && st.flips_per_iteration.back() == 0)) {
    finish(Mode::Grid);
    return result;
  }
  if (zero_residual) {
    // X, Y are the exact Tutte solution, which Tutte/Floater say is an embedding.
    const std::int64_t flips = count_flips(Mode::Grid);
    if (flips != 0)
      throw Error(ErrorKind::Internal, "tutte_embed: the exact Tutte solution has " +
                                           std::to_string(flips) +
                                           " non-positive triangles (pre-condition missed?)");
    finish(Mode::Grid);
    return result;
  }

  // ---------------- exact fallback ----------------
  if (m > options.exact_fallback_max_interior)
    throw Error(ErrorKind::Internal,
                "tutte_embed: refinement did not certify all triangles after " +
                    std::to_string(st.iterations) + " steps (interior vertices " + std::to_string(m) +
                    ", flips after double " + std::to_string(st.flips_double) + ", last flips " +
                    (st.flips_per_iteration.empty() ? std::string("n/a")
                                                    : std::to_string(st.flips_per_iteration.back())) +
                    ", grid exponent " + std::to_string(e) +
                    "); too large for the exact fallback (limit " +
                    std::to_string(options.exact_fallback_max_interior) + ")");
  const auto t_fb = Clock::now();
  st.exact_fallback = true;
  {
    // Sparse symmetric elimination in rationals along a minimum-degree (AMD) order: row k keeps
    // its entries in columns >= k (the upper factor U = D L^T after elimination).
    Eigen::SparseMatrix<double> A(m, m);
    {
      std::vector<Eigen::Triplet<double>> trip;
      for (int i = 0; i < m; ++i) {
        trip.emplace_back(i, i, static_cast<double>(deg[i]));
        for (int k = nb_begin[i]; k < nb_begin[i + 1]; ++k) trip.emplace_back(i, nb[k], -1.0);
      }
      A.setFromTriplets(trip.begin(), trip.end());
    }
    Eigen::AMDOrdering<int> amd;
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm;
    amd(A, perm);
    std::vector<int> pos(m);  // elimination position of interior index i
    for (int k = 0; k < m; ++k) pos[perm.indices()(k)] = k;
    std::vector<std::map<int, Rational>> row(m);
    std::vector<Rational> rx(m), ry(m);
    for (int i = 0; i < m; ++i) {
      const int pi = pos[i];
      row[pi][pi] = deg[i];
      for (int k = nb_begin[i]; k < nb_begin[i + 1]; ++k) {
        const int pj = pos[nb[k]];
        if (pj > pi) row[pi][pj] = -1;
      }
    }
    for (std::size_t k = 0; k < brow.size(); ++k) {
      rx[pos[brow[k]]] = bx[k];
      ry[pos[brow[k]]] = by[k];
    }
    for (int k = 0; k < m; ++k) {  // O(sum over pivots of (row length)^2) rational operations
      const Rational pivot = row[k].at(k);
      if (sgn(pivot) <= 0) throw Error(ErrorKind::Internal, "tutte_embed: non-positive pivot in exact solve");
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
    exact_interior.resize(m);
    for (int i = 0; i < m; ++i) exact_interior[i] = Point2q{sx[pos[i]], sy[pos[i]]};
  }
  st.seconds_fallback = since(t_fb);
  const std::int64_t flips = count_flips(Mode::Exact);
  if (flips != 0)
    throw Error(ErrorKind::Internal, "tutte_embed: the exact Tutte solution has " + std::to_string(flips) +
                                         " non-positive triangles (pre-condition missed?)");
  finish(Mode::Exact);
  return result;
}

}  // namespace igm
