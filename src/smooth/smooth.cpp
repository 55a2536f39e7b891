#include "igm/smooth/smooth.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "igm/core/error.h"
#include "igm/embed/sparse_cholesky.h"
#include "symmetric_dirichlet.h"

namespace igm {

using smooth_detail::SdReference;

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kMaxTrials = 64;            // trial steps per line search
constexpr double kArmijo = 1e-4;          // sufficient decrease: E(x + a d) <= E(x) + kArmijo a g.d
constexpr double kRegularization = 1e-9;  // times the diagonal, added to the Hessian
constexpr double kTinyPivot = 1e-300;     // added to the diagonal: never exactly 0
constexpr int kMaxRegularizations = 6;    // each 1000 times the last, when a factorization fails
constexpr int kMaxSupernodalGenus = 8;    // above it, SimplicialLDLT with AMD (NewtonSolver)

// R^k as a matrix (R the rotation by +90 degrees): uv = R^k x + t, so d uv / d x = R^k.
constexpr double kRot[4][2][2] = {
    {{1, 0}, {0, 1}}, {{0, -1}, {1, 0}}, {{-1, 0}, {0, -1}}, {{0, 1}, {-1, 0}}};

void check_options(const SmoothOptions& o) {
  auto bad = [](const std::string& what) {
    throw Error(ErrorKind::InvalidArgument, "smooth: " + what);
  };
  if (o.max_iterations < 0) bad("max_iterations must be >= 0");
  if (!(o.time_budget_seconds >= 0)) bad("time_budget_seconds must be >= 0");
  if (!(o.tolerance >= 0)) bad("tolerance must be >= 0");
  if (!(o.step_fraction > 0 && o.step_fraction < 1)) bad("step_fraction must be in (0, 1)");
  if (!(o.stall_step >= 0 && o.stall_step < 1)) bad("stall_step must be in [0, 1)");
  if (o.stall_iterations < 1) bad("stall_iterations must be >= 1");
  if (!(o.min_reference_size > 0 && o.min_reference_size < 1))
    bad("min_reference_size must be in (0, 1)");
  if (!(o.min_reference_aspect > 0 && o.min_reference_aspect <= 1))
    bad("min_reference_aspect must be in (0, 1]");
}

// Factorizes and solves the Newton systems, symmetric positive definite in CSR form without the
// diagonal (as SparseCholesky takes them), by one of two factorizations chosen once by the
// surface's genus. The project's SparseCholesky (nested dissection by BFS level sets, dense fronts)
// is twice as fast as Eigen's SimplicialLDLT with AMD on a genus-3 IGM of 100k triangles, but its
// level sets wrap around every handle: on cheese (genus 133, 423k triangles) its largest front
// has 9,398 rows and a factorization takes 65 s, against 6 s with AMD.
class NewtonSolver {
 public:
  explicit NewtonSolver(bool supernodal) : supernodal_(supernodal) {}

  // Solves (A + diag) x = b for A given by xadj, adj, values. False if A + diag is not
  // numerically positive definite.
  bool solve(const std::vector<int>& xadj, const std::vector<int>& adj,
             const std::vector<double>& values, const std::vector<double>& diag,
             const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    if (supernodal_) {
      try {
        cholesky_.factorize(xadj, adj, values, diag);
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::Internal) throw;
        return false;
      }
      Eigen::MatrixXd rhs = b;
      cholesky_.solve(rhs);
      x = rhs.col(0);
      return true;
    }
    const int n = static_cast<int>(diag.size());
    if (lower_.rows() != n) {  // the lower triangle's pattern, once
      std::vector<Eigen::Triplet<double>> entries;
      for (int r = 0; r < n; ++r) {
        entries.emplace_back(r, r, 0.0);
        for (int k = xadj[r]; k < xadj[r + 1]; ++k)
          if (adj[k] > r) entries.emplace_back(adj[k], r, 0.0);
      }
      lower_.resize(n, n);
      lower_.setFromTriplets(entries.begin(), entries.end());
      lower_.makeCompressed();
      ldlt_.analyzePattern(lower_);
    }
    // Column r of the lower triangle holds row r's entries right of the diagonal, in order.
    const int* outer = lower_.outerIndexPtr();
    double* value = lower_.valuePtr();
    for (int r = 0; r < n; ++r) {
      int k = xadj[r + 1] - (outer[r + 1] - outer[r] - 1);  // the first entry right of r
      value[outer[r]] = diag[r];
      for (int p = outer[r] + 1; p < outer[r + 1]; ++p) value[p] = values[k++];
    }
    ldlt_.factorize(lower_);
    if (ldlt_.info() != Eigen::Success) return false;
    x = ldlt_.solve(b);
    return ldlt_.info() == Eigen::Success;
  }

 private:
  bool supernodal_;
  SparseCholesky cholesky_;
  Eigen::SparseMatrix<double> lower_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt_;
};

// The projected Newton iteration on the free coordinates of a grid map's vertex UVs: both of an
// interior regular vertex, the sliding one of a straight boundary vertex, none of a cone or a
// boundary corner (seamless.h).
class Smoother {
 public:
  Smoother(const SeamlessStructure& s, GridMap map, const std::vector<Vec3d>& positions,
           const std::vector<std::array<int, 3>>& triangles, const SmoothOptions& options,
           SmoothStats& stats)
      : s_(s),
        map_(std::move(map)),
        options_(options),
        stats_(stats),
        solver_(s.genus <= kMaxSupernodalGenus) {
    stats_.supernodal = s.genus <= kMaxSupernodalGenus;
    const int nv = s_.num_vertices();
    unknown_.assign(nv, {-1, -1});
    for (int v = 0; v < nv; ++v) {  // unknowns in vertex order, u before v (2i, 2i + 1 if closed)
      if (s_.is_cone(v)) {
        ++(s_.boundary[v] ? stats_.boundary_corners : stats_.cones);
        continue;
      }
      for (int j = 0; j < 2; ++j)
        if (j != s_.isoline_axis[v]) unknown_[v][j] = n_++;
      ++(s_.slides(v) ? stats_.sliding_vertices : stats_.free_vertices);
    }
    grid_corners(s_, map_, corners_);
    double uv_area = 0;
    for (const auto& t : corners_)
      uv_area +=
          ((t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[1].y - t[0].y) * (t[2].x - t[0].x)) / 2;
    smooth_detail::SdReferenceStats rs;
    refs_ = smooth_detail::sd_references(positions, triangles, uv_area, options.min_reference_size,
                                         options.min_reference_aspect, rs);
    stats_.enlarged_references = rs.enlarged;
    stats_.fattened_references = rs.fattened;
  }

  const std::vector<std::array<Vec2d, 3>>& corners() const { return corners_; }

  double energy(const std::vector<std::array<Vec2d, 3>>& corners) const {
    double e = 0;
    for (std::size_t f = 0; f < corners.size() && e < HUGE_VAL; ++f)
      e += smooth_detail::sd_energy(refs_[f], corners[f][0], corners[f][1], corners[f][2]);
    return e;
  }

  /// Runs the iterations from the current map; returns why it stopped.
  SmoothStop run(Clock::time_point t0) {
    double e = energy(corners_);
    stats_.energy.push_back(e);
    if (!std::isfinite(e)) {
      stats_.reason =
          "the starting map's energy is not finite in doubles (a UV triangle too thin for them)";
      return SmoothStop::NotStarted;
    }
    if (options_.on_iterate) options_.on_iterate({0, e, &corners_});
    if (n_ == 0) return SmoothStop::NothingToMove;
    build_pattern();
    stats_.setup_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    int small_steps = 0;  // consecutive accepted steps below options_.stall_step
    for (int it = 1; it <= options_.max_iterations; ++it) {
      assemble();
      Eigen::VectorXd d;
      if (!solve(d)) return SmoothStop::NoDescent;
      const double gd = gradient_.dot(d);  // -d^T H d: <= 0 up to rounding
      if (!(-gd / 2 > options_.tolerance * e))
        return gd <= 0 ? SmoothStop::Converged : SmoothStop::NoDescent;
      double step = 0;
      if (!line_search(d, gd, e, step)) return SmoothStop::LineSearch;
      stats_.iterations = it;
      stats_.energy.push_back(e);
      const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      if (options_.on_iterate) options_.on_iterate({it, e, &corners_});
      if (options_.progress) options_.progress({it, e, step, seconds});
      if (options_.time_budget_seconds > 0 && seconds >= options_.time_budget_seconds)
        return SmoothStop::TimeBudget;
      small_steps = step < options_.stall_step ? small_steps + 1 : 0;
      if (small_steps >= options_.stall_iterations) return SmoothStop::Stalled;
    }
    return SmoothStop::IterationBudget;
  }

 private:
  // The n x n Hessian's pattern (unknown unknown_[v][j]: coordinate j of x_v) in CSR form without
  // the diagonal, and per face where each of its 36 corner-coordinate pairs goes: an index into
  // the off-diagonal values, -2 - i for diagonal entry i, or -1 (a fixed coordinate).
  void build_pattern() {
    const int nf = s_.mesh.num_faces(), m = n_;
    auto global = [&](int f, int a) {  // a = 2 i + j: coordinate j of corner i of face f
      return unknown_[s_.mesh.origin(3 * f + a / 2)][a % 2];
    };
    std::vector<std::vector<int>> rows(m);
    for (int f = 0; f < nf; ++f)
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) {
          const int ga = global(f, a), gb = global(f, b);
          if (ga >= 0 && gb >= 0 && ga != gb) rows[ga].push_back(gb);
        }
    xadj_.assign(m + 1, 0);
    adj_.clear();
    for (int r = 0; r < m; ++r) {
      std::sort(rows[r].begin(), rows[r].end());
      rows[r].erase(std::unique(rows[r].begin(), rows[r].end()), rows[r].end());
      adj_.insert(adj_.end(), rows[r].begin(), rows[r].end());
      xadj_[r + 1] = static_cast<int>(adj_.size());
    }
    values_.assign(adj_.size(), 0.0);
    diag_.assign(m, 0.0);
    slots_.assign(nf, {});
    for (int f = 0; f < nf; ++f)
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) {
          const int ga = global(f, a), gb = global(f, b);
          int& slot = slots_[f][6 * a + b];
          if (ga < 0 || gb < 0)
            slot = -1;
          else if (ga == gb)
            slot = -2 - ga;
          else
            slot = static_cast<int>(
                std::lower_bound(adj_.begin() + xadj_[ga], adj_.begin() + xadj_[ga + 1], gb) -
                adj_.begin());
        }
  }

  // Gradient and projected Hessian at the current map, in the free coordinates: corner c of
  // vertex v is R^k x_v + t, so its derivatives pull back by R^k.
  void assemble() {
    gradient_.setZero(n_);
    std::fill(values_.begin(), values_.end(), 0.0);
    std::fill(diag_.begin(), diag_.end(), 0.0);
    const int nf = s_.mesh.num_faces();
    double g[6], h[36], gx[6], hx[36];
    for (int f = 0; f < nf; ++f) {
      smooth_detail::sd_derivatives(refs_[f], corners_[f], g, h);
      const double(*R[3])[2];
      const std::array<int, 2>* v[3];
      for (int i = 0; i < 3; ++i) {
        R[i] = kRot[map_.corner_motion[3 * f + i].k & 3];
        v[i] = &unknown_[s_.mesh.origin(3 * f + i)];
      }
      // gx_i = R_i^T g_i; hx_ij = R_i^T h_ij R_j
      for (int i = 0; i < 3; ++i)
        for (int r = 0; r < 2; ++r)
          gx[2 * i + r] = R[i][0][r] * g[2 * i] + R[i][1][r] * g[2 * i + 1];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int r = 0; r < 2; ++r)
            for (int c = 0; c < 2; ++c) {
              double sum = 0;
              for (int p = 0; p < 2; ++p)
                for (int q = 0; q < 2; ++q)
                  sum += R[i][p][r] * h[6 * (2 * i + p) + 2 * j + q] * R[j][q][c];
              hx[6 * (2 * i + r) + 2 * j + c] = sum;
            }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 2; ++j)
          if ((*v[i])[j] >= 0) gradient_[(*v[i])[j]] += gx[2 * i + j];
      for (int k = 0; k < 36; ++k) {
        const int slot = slots_[f][k];
        if (slot >= 0)
          values_[slot] += hx[k];
        else if (slot <= -2)
          diag_[-2 - slot] += hx[k];
      }
    }
  }

  // d = -H^-1 g for H + mu diag(H) (Levenberg-Marquardt with the diagonal's scale: the entries of
  // thin triangles and ordinary ones differ by many orders of magnitude, and Cholesky's accuracy
  // depends on the diagonally scaled matrix), mu = kRegularization, raised 1000 times while the
  // factorization fails or the solution is not finite (at most kMaxRegularizations times).
  bool solve(Eigen::VectorXd& d) {
    std::vector<double> diag(diag_.size());
    double mu = kRegularization;
    for (int attempt = 0; attempt < kMaxRegularizations; ++attempt, mu *= 1e3) {
      ++stats_.factorizations;
      for (std::size_t i = 0; i < diag.size(); ++i) diag[i] = diag_[i] * (1 + mu) + kTinyPivot;
      // not numerically positive definite or not finite: more regularization
      if (solver_.solve(xadj_, adj_, values_, diag, -gradient_, d) && d.allFinite()) return true;
    }
    return false;
  }

  // Backtracking from step_fraction of the first degeneracy (capped at 1): accepts the first
  // step whose grid map lowers the energy by Armijo's rule and passes the exact checks (every
  // triangle positive, every angle kept: check_map). Updates the map, its corners and e.
  bool line_search(const Eigen::VectorXd& d, double gd, double& e, double& step) {
    const int nf = s_.mesh.num_faces();
    double first = std::numeric_limits<double>::infinity();
    for (int f = 0; f < nf; ++f) {
      std::array<Vec2d, 3> duv;
      for (int i = 0; i < 3; ++i) {
        const int c = 3 * f + i;
        const Vec2d dv = step_of(s_.mesh.origin(c), d);
        const double(*R)[2] = kRot[map_.corner_motion[c].k & 3];
        duv[i] = {R[0][0] * dv.x + R[0][1] * dv.y, R[1][0] * dv.x + R[1][1] * dv.y};
      }
      first = std::min(first, smooth_detail::first_degeneracy(corners_[f], duv));
    }
    double alpha = std::min(1.0, options_.step_fraction * first);
    GridMap trial = map_;
    const int nv = s_.num_vertices();
    for (int t = 0; t < kMaxTrials; ++t, alpha /= 2, ++stats_.step_halvings) {
      bool inside = true;
      for (int v = 0; v < nv && inside; ++v) {
        const std::array<int, 2>& i = unknown_[v];
        if (i[0] < 0 && i[1] < 0) continue;
        // a fixed coordinate (the isoline's integer of a sliding vertex) stays as it is
        const Vec2d& x = map_.vertex_uv[v];
        const auto u = i[0] < 0 ? x.x : round_to_grid(x.x + alpha * d[i[0]], map_.grid);
        const auto w = i[1] < 0 ? x.y : round_to_grid(x.y + alpha * d[i[1]], map_.grid);
        inside = u && w;
        if (inside) trial.vertex_uv[v] = {*u, *w};
      }
      if (!inside) continue;
      grid_corners(s_, trial, trial_corners_);
      const double et = energy(trial_corners_);
      if (!(et <= e + kArmijo * alpha * gd)) continue;
      if (!check_map(s_, trial_corners_).valid()) {
        ++stats_.exact_rejections;
        continue;
      }
      map_.vertex_uv.swap(trial.vertex_uv);
      corners_.swap(trial_corners_);
      e = et;
      step = alpha;
      return true;
    }
    return false;
  }

  // The step of vertex v's x_v along the direction d (0 in its fixed coordinates).
  Vec2d step_of(int v, const Eigen::VectorXd& d) const {
    const std::array<int, 2>& i = unknown_[v];
    return {i[0] < 0 ? 0.0 : d[i[0]], i[1] < 0 ? 0.0 : d[i[1]]};
  }

  const SeamlessStructure& s_;
  GridMap map_;
  const SmoothOptions& options_;
  SmoothStats& stats_;
  std::vector<std::array<int, 2>> unknown_;  // per vertex and coordinate: its unknown, or -1
  int n_ = 0;                                // unknowns
  std::vector<SdReference> refs_;
  std::vector<std::array<Vec2d, 3>> corners_, trial_corners_;
  std::vector<int> xadj_, adj_;
  std::vector<double> values_, diag_;
  NewtonSolver solver_;
  Eigen::VectorXd gradient_;
  std::vector<std::array<int, 36>> slots_;
};

}  // namespace

const char* to_string(SmoothStop stop) {
  switch (stop) {
    case SmoothStop::Converged:
      return "converged";
    case SmoothStop::IterationBudget:
      return "iteration_budget";
    case SmoothStop::TimeBudget:
      return "time_budget";
    case SmoothStop::NoDescent:
      return "no_descent";
    case SmoothStop::LineSearch:
      return "line_search";
    case SmoothStop::Stalled:
      return "stalled";
    case SmoothStop::NothingToMove:
      return "nothing_to_move";
    case SmoothStop::NotStarted:
      return "not_started";
  }
  return "?";
}

const char* to_string(SmoothReturned returned) {
  switch (returned) {
    case SmoothReturned::Smoothed:
      return "smoothed";
    case SmoothReturned::InputOnGrid:
      return "input_on_grid";
    case SmoothReturned::InputExact:
      return "input_exact";
  }
  return "?";
}

SmoothResult smooth_igm(const IgmMesh& igm, const SmoothOptions& options) {
  const Clock::time_point t0 = Clock::now();
  check_options(options);
  for (std::size_t v = 0; v < igm.positions.size(); ++v) {
    const Vec3d& p = igm.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(ErrorKind::NonFinite,
                  "smooth: vertex " + std::to_string(v) + " has a non-finite position",
                  {static_cast<std::int64_t>(v)});
  }
  const SeamlessStructure s = seamless_structure(igm);
  SmoothResult result;
  SmoothStats& stats = result.stats;
  DyadicResult start = round_to_dyadic(igm, s);
  stats.dyadic = start.stats;
  if (!start.stats.on_grid) {
    stats.stop = SmoothStop::NotStarted;
    stats.returned = SmoothReturned::InputExact;
    stats.reason = "the input stays exact: " + start.stats.reason;
    result.corner_uv = std::move(start.corner_uv);
  } else {
    Smoother smoother(s, *round_to_grid(s), igm.positions, igm.triangles, options, stats);
    stats.stop = smoother.run(t0);
    stats.returned = stats.iterations > 0 ? SmoothReturned::Smoothed : SmoothReturned::InputOnGrid;
    if (stats.reason.empty())
      stats.reason = std::string("stopped: ") + to_string(stats.stop) + " after " +
                     std::to_string(stats.iterations) + " iterations";
    stats.reason += std::string("; returned ") + to_string(stats.returned);
    if (stats.returned == SmoothReturned::Smoothed) {
      result.corner_uv = to_exact(smoother.corners());
      stats.dyadic.max_uv_bits = max_uv_bits(result.corner_uv);
    } else {
      result.corner_uv = std::move(start.corner_uv);
    }
  }
  if (options.certify) {
    const Clock::time_point tc = Clock::now();
    certify::Options co;  // what the input is: open, several components (closed: the defaults)
    co.allow_boundary = s.boundary_loops > 0;
    co.allow_components = s.components > 1;
    result.report = certify::certify_igm(certify_input(igm, result.corner_uv), co);
    stats.certified = result.report.valid();
    stats.certify_seconds = std::chrono::duration<double>(Clock::now() - tc).count();
  }
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return result;
}

}  // namespace igm
