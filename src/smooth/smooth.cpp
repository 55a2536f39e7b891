#include "igm/smooth/smooth.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "../core/parallel.h"
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
// Parallel work on faces and vertices in chunks of fixed size (core/parallel.h); the assembly
// computes kAssembleBatch faces' terms in parallel, then adds them up in face order.
constexpr std::int64_t kChunk = 4096;
constexpr std::int64_t kAssembleBatch = 8 * kChunk;

// R^k as a matrix (R the rotation by +90 degrees): uv = R^k x + t, so d uv / d x = R^k.
constexpr double kRot[4][2][2] = {
    {{1, 0}, {0, 1}}, {{0, -1}, {1, 0}}, {{-1, 0}, {0, -1}}, {{0, 1}, {-1, 0}}};

void check_options(const SmoothOptions& o) {
  auto bad = [](const std::string& what) {
    throw Error(ErrorKind::InvalidArgument, "smooth: " + what);
  };
  if (o.max_iterations < 0) bad("max_iterations must be >= 0");
  if (!(o.time_budget_seconds >= 0)) bad("time_budget_seconds must be >= 0");
  if (!(o.min_relative_decrease >= 0 && o.min_relative_decrease < 1)) bad("min_relative_decrease must be in [0, 1)");
  if (!(o.tolerance >= 0)) bad("tolerance must be >= 0");
  if (!(o.step_fraction > 0 && o.step_fraction < 1)) bad("step_fraction must be in (0, 1)");
  if (!(o.stall_step >= 0 && o.stall_step < 1)) bad("stall_step must be in [0, 1)");
  if (o.stall_iterations < 1) bad("stall_iterations must be >= 1");
  if (!(o.min_reference_size > 0 && o.min_reference_size < 1))
    bad("min_reference_size must be in (0, 1)");
  if (!(o.min_reference_aspect > 0 && o.min_reference_aspect <= 1))
    bad("min_reference_aspect must be in (0, 1]");
}

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
        stats_(stats) {
    const int nv = s_.num_vertices();
    unknown_.assign(nv, {-1, -1});
    for (int v = 0; v < nv; ++v) {  // unknowns in vertex order, u before v (2i, 2i + 1 if closed)
      if (s_.is_cone(v)) {
        ++(s_.boundary[v] ? stats_.boundary_corners : stats_.cones);
        continue;
      }
      const unsigned held = s_.fixed_axes.empty() ? 0u : s_.fixed_axes[v];
      for (int j = 0; j < 2; ++j)
        if (j != s_.isoline_axis[v] && !((held >> j) & 1u)) unknown_[v][j] = n_++;
      ++(s_.slides(v) || held != 0 ? stats_.sliding_vertices : stats_.free_vertices);
    }
    grid_corners(s_, map_, map_.vertex_uv, corners_);
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

  // The energy: chunk sums added in chunk order (core/parallel.h), the same bits for any threads.
  double energy(const std::vector<std::array<Vec2d, 3>>& corners) const {
    return parallel::sum_chunks<double>(static_cast<std::int64_t>(corners.size()), kChunk, [&](std::int64_t b, std::int64_t e) {
      double sum = 0;
      for (std::int64_t f = b; f < e; ++f)
        sum += smooth_detail::sd_energy(refs_[f], corners[f][0], corners[f][1], corners[f][2]);
      return sum;
    });
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
      const double before = e;
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
      if (before - e < options_.min_relative_decrease * before) return SmoothStop::SmallDecrease;
    }
    return SmoothStop::IterationBudget;
  }

 private:
  // The n x n Hessian's pattern (unknown unknown_[v][j]: coordinate j of x_v) in CSR form without
  // the diagonal (rows sorted), and the factorization's analysis of it.
  void build_pattern() {
    const int nf = s_.mesh.num_faces(), nv = s_.num_vertices(), m = n_;
    // The vertices' neighbours (CSR, sorted, each once, the vertex itself included), then per
    // unknown the unknowns of its vertex's neighbours: unknowns are numbered by vertex, so the
    // columns come out sorted.
    std::vector<int> begin(nv + 1, 0), nbr;
    for (int f = 0; f < nf; ++f)
      for (int i = 0; i < 3; ++i) begin[s_.mesh.origin(3 * f + i) + 1] += 3;
    for (int v = 0; v < nv; ++v) begin[v + 1] += begin[v];
    nbr.resize(begin[nv]);
    {
      std::vector<int> fill(begin.begin(), begin.end() - 1);
      for (int f = 0; f < nf; ++f)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) nbr[fill[s_.mesh.origin(3 * f + i)]++] = s_.mesh.origin(3 * f + j);
    }
    xadj_.assign(m + 1, 0);
    adj_.clear();
    for (int v = 0; v < nv; ++v) {
      auto b = nbr.begin() + begin[v], e = nbr.begin() + begin[v + 1];
      std::sort(b, e);
      e = std::unique(b, e);
      for (int j = 0; j < 2; ++j) {
        const int r = unknown_[v][j];
        if (r < 0) continue;
        for (auto w = b; w != e; ++w)
          for (int c : unknown_[*w])
            if (c >= 0 && c != r) adj_.push_back(c);
        xadj_[r + 1] = static_cast<int>(adj_.size());
      }
    }
    std::vector<int>().swap(nbr);
    std::vector<int>().swap(begin);
    // Where each face's Hessian entries go, found once (face_terms reads them every iteration).
    // Row r of vertex a lists the unknowns of a's neighbours in vertex order; a's two rows differ
    // only in a's own entry (each holds the other unknown of a, at the same place), so a
    // neighbour b's columns sit at the same offset from the row's start in both rows of a:
    // pair_offset_[6 f + p] for the p-th ordered pair (i, j), i != j, of f's corners, and
    // self_offset_[a] for the entry (u_a, v_a).
    auto first_unknown = [&](int v) { return unknown_[v][0] >= 0 ? unknown_[v][0] : unknown_[v][1]; };
    auto offset = [&](int r, int c) {
      const auto row = adj_.begin() + xadj_[r], end = adj_.begin() + xadj_[r + 1];
      const auto it = std::lower_bound(row, end, c);
      if (it == end || *it != c) throw Error(ErrorKind::Internal, "smooth: an entry missing from the Hessian's pattern");
      return static_cast<int>(it - row);
    };
    pair_offset_.assign(6 * static_cast<std::size_t>(nf), -1);
    for (int f = 0; f < nf; ++f)
      for (int i = 0; i < 3; ++i) {
        const int ra = first_unknown(s_.mesh.origin(3 * f + i));
        if (ra < 0) continue;
        for (int k = 1; k <= 2; ++k) {
          const int cb = first_unknown(s_.mesh.origin(3 * f + (i + k) % 3));
          if (cb >= 0) pair_offset_[6 * static_cast<std::size_t>(f) + 2 * i + k - 1] = offset(ra, cb);
        }
      }
    self_offset_.assign(nv, -1);
    for (int v = 0; v < nv; ++v)
      if (unknown_[v][0] >= 0 && unknown_[v][1] >= 0) self_offset_[v] = offset(unknown_[v][0], unknown_[v][1]);
    values_.assign(adj_.size(), 0.0);
    diag_.assign(m, 0.0);
    // the factorization's analysis, once: both unknowns of a vertex ordered together
    {
      std::vector<int> group(m), id(s_.num_vertices(), -1);
      int groups = 0;
      for (int v = 0; v < s_.num_vertices(); ++v)
        for (int j = 0; j < 2; ++j)
          if (unknown_[v][j] >= 0) {
            if (id[v] < 0) id[v] = groups++;
            group[unknown_[v][j]] = id[v];
          }
      solver_.analyze(xadj_, adj_, group);
      const SparseCholeskyStats& fs = solver_.stats();
      stats_.supernodal = fs.supernodal;
      stats_.factor_entries = fs.factor_entries;
      stats_.analyze_seconds = fs.seconds_analyze;
    }
  }

  // Where entry (row r of corner i, column c of corner j) of face f's Hessian goes: an index
  // into the off-diagonal values, -2 - ga on the diagonal, -1 if either is a fixed coordinate.
  int slot(int f, int i, int r, int j, int c) const {
    const int a = s_.mesh.origin(3 * f + i), b = s_.mesh.origin(3 * f + j);
    const int ga = unknown_[a][r], gb = unknown_[b][c];
    if (ga < 0 || gb < 0) return -1;
    if (i == j) return r == c ? -2 - ga : xadj_[ga] + self_offset_[a];
    const int k = (j - i + 3) % 3;  // 1 or 2
    return xadj_[ga] + pair_offset_[6 * static_cast<std::size_t>(f) + 2 * i + k - 1] +
           (c == 1 && unknown_[b][0] >= 0 ? 1 : 0);
  }

  // One face's gradient and projected Hessian in its corners' free coordinates, with where they go.
  struct FaceTerms {
    double gx[6], hx[36];
    int unknown[6], slot[36];
  };

  // Gradient and projected Hessian at the current map, in the free coordinates: corner c of
  // vertex v is R^k x_v + t, so its derivatives pull back by R^k. The faces' terms are computed in
  // parallel, a batch at a time, and added in face order (the same sums for any thread count).
  void assemble() {
    gradient_.setZero(n_);
    std::fill(values_.begin(), values_.end(), 0.0);
    std::fill(diag_.begin(), diag_.end(), 0.0);
    const std::int64_t nf = s_.mesh.num_faces();
    terms_.resize(static_cast<std::size_t>(std::min(nf, kAssembleBatch)));
    for (std::int64_t b0 = 0; b0 < nf; b0 += kAssembleBatch) {
      const std::int64_t b1 = std::min(nf, b0 + kAssembleBatch);
      parallel::for_each_index(b1 - b0, kChunk / 8, [&](std::int64_t i) { face_terms(static_cast<int>(b0 + i), terms_[i]); });
      for (std::int64_t f = b0; f < b1; ++f) {
        const FaceTerms& t = terms_[f - b0];
        for (int a = 0; a < 6; ++a)
          if (t.unknown[a] >= 0) gradient_[t.unknown[a]] += t.gx[a];
        for (int k = 0; k < 36; ++k) {
          const int sl = t.slot[k];
          if (sl >= 0)
            values_[sl] += t.hx[k];
          else if (sl <= -2)
            diag_[-2 - sl] += t.hx[k];
        }
      }
    }
  }

  void face_terms(int f, FaceTerms& t) const {
    double g[6], h[36];
    smooth_detail::sd_derivatives(refs_[f], corners_[f], g, h);
    const double(*R[3])[2];
    for (int i = 0; i < 3; ++i) {
      R[i] = kRot[map_.corner_motion[3 * f + i].k & 3];
      const std::array<int, 2>& u = unknown_[s_.mesh.origin(3 * f + i)];
      t.unknown[2 * i] = u[0];
      t.unknown[2 * i + 1] = u[1];
    }
    // gx_i = R_i^T g_i; hx_ij = R_i^T h_ij R_j
    for (int i = 0; i < 3; ++i)
      for (int r = 0; r < 2; ++r)
        t.gx[2 * i + r] = R[i][0][r] * g[2 * i] + R[i][1][r] * g[2 * i + 1];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c) {
            double sum = 0;
            for (int p = 0; p < 2; ++p)
              for (int q = 0; q < 2; ++q)
                sum += R[i][p][r] * h[6 * (2 * i + p) + 2 * j + q] * R[j][q][c];
            t.hx[6 * (2 * i + r) + 2 * j + c] = sum;
          }
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) t.slot[6 * a + b] = slot(f, a / 2, a % 2, b / 2, b % 2);
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
      const bool factorized = solver_.factorize_numeric(values_, diag);
      stats_.factorize_seconds += solver_.stats().seconds_factorize;
      if (!factorized) continue;
      Eigen::MatrixXd x = -gradient_;
      solver_.solve(x);
      d = x.col(0);
      if (d.allFinite()) return true;
    }
    return false;
  }

  // Backtracking from step_fraction of the first degeneracy (capped at 1): accepts the first
  // step whose grid map lowers the energy by Armijo's rule and passes the exact checks (every
  // triangle positive, every angle kept: check_map). Updates the map, its corners and e.
  bool line_search(const Eigen::VectorXd& d, double gd, double& e, double& step) {
    const std::int64_t nf = s_.mesh.num_faces(), nv = s_.num_vertices();
    const double first = parallel::reduce_chunks<double>(
        nf, kChunk, std::numeric_limits<double>::infinity(),
        [&](std::int64_t b, std::int64_t end) {
          double m = std::numeric_limits<double>::infinity();
          for (std::int64_t f = b; f < end; ++f) {
            std::array<Vec2d, 3> duv;
            for (int i = 0; i < 3; ++i) {
              const int c = static_cast<int>(3 * f + i);
              const Vec2d dv = step_of(s_.mesh.origin(c), d);
              const double(*R)[2] = kRot[map_.corner_motion[c].k & 3];
              duv[i] = {R[0][0] * dv.x + R[0][1] * dv.y, R[1][0] * dv.x + R[1][1] * dv.y};
            }
            m = std::min(m, smooth_detail::first_degeneracy(corners_[f], duv));
          }
          return m;
        },
        [](double a, double b) { return std::min(a, b); });
    double alpha = std::min(1.0, options_.step_fraction * first);
    trial_uv_ = map_.vertex_uv;
    for (int t = 0; t < kMaxTrials; ++t, alpha /= 2, ++stats_.step_halvings) {
      // every moving vertex onto the grid; a fixed coordinate (the isoline's integer of a sliding
      // vertex) stays as it is
      const int outside = parallel::reduce_chunks<int>(
          nv, kChunk, 0,
          [&](std::int64_t b, std::int64_t end) {
            int out = 0;
            for (std::int64_t v = b; v < end; ++v) {
              const std::array<int, 2>& i = unknown_[v];
              if (i[0] < 0 && i[1] < 0) continue;
              const Vec2d& x = map_.vertex_uv[v];
              const auto u = i[0] < 0 ? x.x : round_to_grid(x.x + alpha * d[i[0]], map_.grid);
              const auto w = i[1] < 0 ? x.y : round_to_grid(x.y + alpha * d[i[1]], map_.grid);
              if (u && w)
                trial_uv_[v] = {*u, *w};
              else
                ++out;
            }
            return out;
          },
          [](int a, int b) { return a + b; });
      if (outside > 0) continue;
      grid_corners(s_, map_, trial_uv_, trial_corners_);
      const double et = energy(trial_corners_);
      if (!(et <= e + kArmijo * alpha * gd)) continue;
      if (!check_map(s_, trial_corners_).valid()) {
        ++stats_.exact_rejections;
        continue;
      }
      map_.vertex_uv.swap(trial_uv_);
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
  std::vector<int> pair_offset_, self_offset_;  // slot offsets (build_pattern)
  std::vector<double> values_, diag_;
  SparseCholesky solver_;
  Eigen::VectorXd gradient_;
  std::vector<FaceTerms> terms_;  // a batch of faces' terms (assemble)
  std::vector<Vec2d> trial_uv_;   // the line search's trial vertex UVs
};

}  // namespace

const char* to_string(SmoothStop stop) {
  switch (stop) {
    case SmoothStop::Converged:
      return "converged";
    case SmoothStop::IterationBudget:
      return "iteration_budget";
    case SmoothStop::SmallDecrease:
      return "small_decrease";
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

namespace {

// smooth_igm; with `release`, *release (the input's exact UVs) is freed once the map is on its
// double grid.
SmoothResult smooth(const IgmMesh& igm, const SmoothOptions& options, std::vector<std::array<Point2q, 3>>* release) {
  const Clock::time_point t0 = Clock::now();
  check_options(options);
  for (std::size_t v = 0; v < igm.positions.size(); ++v) {
    const Vec3d& p = igm.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(ErrorKind::NonFinite,
                  "smooth: vertex " + std::to_string(v) + " has a non-finite position",
                  {static_cast<std::int64_t>(v)});
  }
  SeamlessStructure s = seamless_structure(igm);
  if (!options.isoline_edges.empty()) hold_isoline_edges(s, options.isoline_edges);
  SmoothResult result;
  SmoothStats& stats = result.stats;
  std::optional<GridMap> map;
  std::vector<std::array<Vec2d, 3>> corners;
  stats.dyadic = place_on_grid(s, map, corners);
  stats.structure_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (!stats.dyadic.on_grid) {
    stats.stop = SmoothStop::NotStarted;
    stats.returned = SmoothReturned::InputExact;
    stats.reason = "the input stays exact: " + stats.dyadic.reason;
    result.corner_uv = release ? std::move(*release) : igm.corner_uv;
    stats.dyadic.max_uv_bits = max_uv_bits(result.corner_uv);
  } else {
    // What the iterations need of the exact data is in the grid map now.
    if (release) std::vector<std::array<Point2q, 3>>().swap(*release);
    std::vector<GridMotion>().swap(s.transition);
    std::vector<GridMotion>().swap(s.corner_motion);
    std::vector<Point2q>().swap(s.vertex_uv);
    std::vector<std::array<Vec2d, 3>>().swap(corners);
    Smoother smoother(s, std::move(*map), igm.positions, igm.triangles, options, stats);
    stats.stop = smoother.run(t0);
    stats.returned = stats.iterations > 0 ? SmoothReturned::Smoothed : SmoothReturned::InputOnGrid;
    if (stats.reason.empty())
      stats.reason = std::string("stopped: ") + to_string(stats.stop) + " after " +
                     std::to_string(stats.iterations) + " iterations";
    stats.reason += std::string("; returned ") + to_string(stats.returned);
    result.corner_uv = to_exact(smoother.corners());
    stats.dyadic.max_uv_bits = max_uv_bits(result.corner_uv);
  }
  if (options.certify) {
    const Clock::time_point tc = Clock::now();
    certify::Options co;  // what the input is: open, several components (closed: the defaults)
    co.allow_boundary = s.boundary_loops > 0;
    co.allow_components = s.components > 1;
    co.threads = options.threads;
    result.report = certify::certify_igm(certify_input(igm, result.corner_uv), co);
    stats.certified = result.report.valid();
    stats.certify_seconds = std::chrono::duration<double>(Clock::now() - tc).count();
  }
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return result;
}

}  // namespace

SmoothResult smooth_igm(const IgmMesh& igm, const SmoothOptions& options) { return smooth(igm, options, nullptr); }

SmoothResult smooth_igm_releasing(IgmMesh& igm, const SmoothOptions& options) {
  return smooth(igm, options, &igm.corner_uv);
}

}  // namespace igm
