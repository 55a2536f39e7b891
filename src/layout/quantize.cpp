#include "igm/layout/quantize.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <type_traits>

#include <CbcModel.hpp>
#include <CbcSolver.hpp>
#include <CoinPackedMatrix.hpp>
#include <OsiClpSolverInterface.hpp>

#include "igm/core/det_math.h"
#include "igm/core/error.h"
#include "igm/mesh/scale.h"

namespace igm {

namespace {

constexpr int kMaxLength = 1 << 20;

std::string str(std::int64_t x) { return std::to_string(x); }

int start_vertex(const SurfaceLayout& L, const ArcUse& u) {
  const auto& V = L.arcs[u.arc].vertices;
  return u.forward ? V.front() : V.back();
}

// The least sums of the side pairs (0, 2) and (1, 3) of patch p (minimum_arc_lengths).
std::array<int, 2> side_minimum(const SurfaceLayout& L, int p) {
  const LayoutPatch& P = L.patches[p];
  std::array<int, 2> m{1, 1};
  int corner[4];
  for (int k = 0; k < 4; ++k) corner[k] = start_vertex(L, P.sides[k].front());
  if (corner[0] == corner[2] || corner[1] == corner[3]) m = {2, 2};
  for (int k : {0, 1})  // an arc on sides k and k + 2: a grid line across from it closes on one vertex
    for (const ArcUse& u : P.sides[k])
      for (const ArcUse& w : P.sides[k + 2])
        if (u.arc == w.arc) m[1 - k] = 3;
  return m;
}

// One solve's outcome.
struct Solve {
  QuantizeStatus status = QuantizeStatus::NoSolution;
  std::vector<int> x;
  std::int64_t nodes = 0;
  double objective = 0;
  std::string why;  // why there is no solution, if not CBC's own verdict
  std::vector<double> relaxed;  // lp_only: the relaxation's lengths (empty if it has no optimum)
};

// The patches' rows over the arcs' lengths x_a (fixed; targets and weights change per solve).
struct Program {
  int arcs = 0;
  struct Row {
    std::vector<int> arc;
    std::vector<double> coef;
    double lower = 0, upper = 0;
  };
  std::vector<Row> rows;
  int equality_rows = 0;
  std::vector<int> minimum;
};

// Solves min sum_a w_a |x_a - t_a| over the rows. The deviation is modelled exactly on integers by
// its convex piecewise-linear interpolation with integer breakpoints: x_a = b_a + u_a + v_a - d_a
// with the base b_a = floor(t_a) clamped into [minimum, 2^20], u_a in [0, 1] at cost
// w_a (1 - 2 (t_a - b_a)) (w_a if b_a > t_a), v_a >= 0 and d_a in [0, b_a - minimum] at cost w_a.
// It equals w_a |x_a - t_a| at every integer x_a, so the integer optimum is the same; as the
// breakpoints are integers, the relaxation's optimal vertices are integral wherever the rows allow
// it (a T-mesh whose patch frames agree across every arc has a network matrix: always). So the
// relaxation is solved first (Clp's dual simplex); if its optimum is integral it is the answer,
// else CBC's branch and cut (CbcMain: presolve, cuts, heuristics but the feasibility pump) runs on
// it, at most `max_nodes` nodes, one thread, no time limit.
// lp_only: the relaxation only, its lengths in Solve::relaxed (for sizing rounds).
Solve solve(const Program& prog, const std::vector<double>& target, const std::vector<double>& weight, int max_nodes,
            bool lp_only = false) {
  const int n = prog.arcs;
  std::vector<double> base(n), col_lower(3 * n, 0.0), col_upper(3 * n), objective(3 * n);
  double constant = 0;
  for (int a = 0; a < n; ++a) {
    const double t = target[a];
    base[a] = std::clamp(std::floor(t), static_cast<double>(prog.minimum[a]), static_cast<double>(kMaxLength));
    const double room = kMaxLength - base[a];
    col_upper[a] = std::min(1.0, room);
    col_upper[n + a] = std::max(0.0, room - 1);
    col_upper[2 * n + a] = base[a] - prog.minimum[a];
    objective[a] = weight[a] * (base[a] > t ? 1.0 : 1 - 2 * (t - base[a]));
    objective[n + a] = objective[2 * n + a] = weight[a];
    constant += weight[a] * std::abs(base[a] - t);
  }
  std::vector<int> row_index, column_index;
  std::vector<double> element, row_lower, row_upper;
  for (std::size_t r = 0; r < prog.rows.size(); ++r) {
    const Program::Row& R = prog.rows[r];
    double shift = 0;
    for (std::size_t i = 0; i < R.arc.size(); ++i) {
      const int a = R.arc[i];
      shift += R.coef[i] * base[a];
      for (int c : {0, 1, 2}) {
        row_index.push_back(static_cast<int>(r));
        column_index.push_back(c * n + a);
        element.push_back(c == 2 ? -R.coef[i] : R.coef[i]);
      }
    }
    row_lower.push_back(R.lower - shift);
    row_upper.push_back(R.upper == COIN_DBL_MAX ? COIN_DBL_MAX : R.upper - shift);
  }
  CoinPackedMatrix matrix(false, row_index.data(), column_index.data(), element.data(),
                          static_cast<CoinBigIndex>(element.size()));
  matrix.setDimensions(static_cast<int>(prog.rows.size()), 3 * n);
  OsiClpSolverInterface solver;
  solver.messageHandler()->setLogLevel(0);
  solver.loadProblem(matrix, col_lower.data(), col_upper.data(), objective.data(), row_lower.data(), row_upper.data());
  for (int c = 0; c < 3 * n; ++c) solver.setInteger(c);
  Solve s;
  auto take = [&](const double* v, double value) {
    s.x.resize(n);
    for (int a = 0; a < n; ++a) s.x[a] = static_cast<int>(base[a] + std::llround(v[a] + v[n + a] - v[2 * n + a]));
    s.objective = value + constant;
  };
  solver.initialSolve();
  if (solver.isProvenPrimalInfeasible()) {
    s.status = QuantizeStatus::Infeasible;
    return s;
  }
  if (solver.isProvenOptimal()) {
    const double* v = solver.getColSolution();
    if (lp_only) {
      s.relaxed.resize(n);
      for (int a = 0; a < n; ++a) s.relaxed[a] = base[a] + v[a] + v[n + a] - v[2 * n + a];
    }
    bool integral = true;
    for (int c = 0; c < 3 * n && integral; ++c) integral = std::abs(v[c] - std::nearbyint(v[c])) < 1e-9;
    if (integral) {
      take(v, solver.getObjValue());
      s.status = QuantizeStatus::Optimal;
      return s;
    }
  }
  if (lp_only) return s;
  CbcModel model(solver);
  model.setLogLevel(0);
  model.messageHandler()->setLogLevel(0);
  CbcSolverUsefulData data;
  data.noPrinting_ = true;
  CbcMain0(model, data);
  const std::string nodes = std::to_string(max_nodes);
  // The feasibility pump off: measured on the field layouts of the shared meshes, the root node
  // then takes half the time (elephant 1.5 -> 0.6 s, dino 0.7 -> 0.4 s) with the same optima
  // (bench/README.md, "Quantization").
  const char* argv[] = {"igm",     "-log",         "0",   "-slog", "0", "-threads", "0", "-maxNodes",
                        nodes.c_str(), "-feas", "off", "-solve", "-quit"};
  CbcMain1(static_cast<int>(sizeof argv / sizeof argv[0]), argv, model, [](CbcModel*, int) { return 0; }, data);
  s.nodes = model.getNodeCount();
  if (const double* best = model.bestSolution()) {
    take(best, model.getObjValue());
    s.status = model.isProvenOptimal() ? QuantizeStatus::Optimal : QuantizeStatus::Feasible;
  } else {
    s.status = model.isProvenInfeasible() ? QuantizeStatus::Infeasible : QuantizeStatus::NoSolution;
  }
  return s;
}

// "" or why integer lengths x break a patch's constraints or a minimum.
std::string violation(const SurfaceLayout& L, const std::vector<int>& x, const std::vector<int>& minimum) {
  for (std::size_t a = 0; a < x.size(); ++a)
    if (x[a] < minimum[a] || x[a] > kMaxLength) return "arc " + str(static_cast<std::int64_t>(a)) + " got " + str(x[a]);
  for (std::size_t p = 0; p < L.patches.size(); ++p) {
    std::int64_t side[4] = {0, 0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (const ArcUse& u : L.patches[p].sides[k]) side[k] += x[u.arc];
    const std::array<int, 2> m = side_minimum(L, static_cast<int>(p));
    if (side[0] != side[2] || side[1] != side[3] || side[0] < m[0] || side[1] < m[1])
      return "patch " + str(static_cast<std::int64_t>(p)) + " gets sides " + str(side[0]) + ", " + str(side[1]) + ", " +
             str(side[2]) + ", " + str(side[3]);
  }
  return "";
}

}  // namespace

const char* to_string(QuantizeStatus s) {
  switch (s) {
    case QuantizeStatus::Optimal: return "optimal";
    case QuantizeStatus::Feasible: return "feasible";
    case QuantizeStatus::Infeasible: return "infeasible";
    case QuantizeStatus::NoSolution: return "no_solution";
  }
  return "?";
}

std::vector<int> minimum_arc_lengths(const SurfaceLayout& L) {
  const int na = static_cast<int>(L.arcs.size());
  std::vector<int> m(na, 1);
  std::map<std::pair<int, int>, std::vector<int>> by_ends;
  for (int a = 0; a < na; ++a) {
    const int u = L.arcs[a].vertices.front(), v = L.arcs[a].vertices.back();
    if (u == v) m[a] = 3;
    by_ends[{std::min(u, v), std::max(u, v)}].push_back(a);
  }
  for (const auto& [ends, list] : by_ends)
    if (list.size() > 1)
      for (int a : list) m[a] = std::max(m[a], 2);
  for (int p = 0; p < static_cast<int>(L.patches.size()); ++p) {
    const std::array<int, 2> s = side_minimum(L, p);
    for (int k = 0; k < 4; ++k)
      if (L.patches[p].sides[k].size() == 1) {
        int& x = m[L.patches[p].sides[k].front().arc];
        x = std::max(x, s[k % 2]);
      }
  }
  return m;
}

Quantization quantize_layout(const SurfaceLayout& L, const QuantizeOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  if (const std::string e = check_surface_layout(L); !e.empty())
    throw Error(ErrorKind::InvalidArgument, "quantize_layout: the layout is not valid: " + e);
  if (!(o.length_scale > 0) || !std::isfinite(o.length_scale))
    throw Error(ErrorKind::InvalidArgument, "quantize_layout: length_scale must be positive and finite");
  if (o.max_nodes < 0 || o.quad_corrections < 0 || o.quad_corrections > 20)
    throw Error(ErrorKind::InvalidArgument, "quantize_layout: max_nodes must be >= 0, quad_corrections in 0..20");
  if (o.resolution < 0 || o.resolution > kMaxLength || !(o.edge_length >= 0) || !std::isfinite(o.edge_length) ||
      o.quads < 0 || (o.resolution == 0 && o.edge_length == 0 && o.quads == 0))
    throw Error(ErrorKind::InvalidArgument, "quantize_layout: needs one of a resolution in 1..2^20, a finite edge length "
                                            "or a quad count, all >= 0");
  const int na = static_cast<int>(L.arcs.size()), np = static_cast<int>(L.patches.size());
  Program prog;
  prog.arcs = na;
  prog.minimum = o.minimum.empty() ? minimum_arc_lengths(L) : o.minimum;
  if (static_cast<int>(prog.minimum.size()) != na)
    throw Error(ErrorKind::InvalidArgument, "quantize_layout: one minimum per arc is needed");
  for (int a = 0; a < na; ++a)
    if (prog.minimum[a] < 1 || prog.minimum[a] > kMaxLength)
      throw Error(ErrorKind::InvalidArgument, "quantize_layout: arc " + str(a) + "'s minimum is not in 1..2^20", {a});
  for (int p = 0; p < np; ++p) {
    const LayoutPatch& P = L.patches[p];
    const std::array<int, 2> side_min = side_minimum(L, p);
    for (int k : {0, 1}) {
      std::map<int, int> coef;
      for (const ArcUse& u : P.sides[k]) ++coef[u.arc];
      for (const ArcUse& u : P.sides[k + 2]) --coef[u.arc];
      std::vector<int> idx;
      std::vector<double> val;
      for (const auto& [a, c] : coef)
        if (c != 0) idx.push_back(a), val.push_back(c);
      if (!idx.empty()) {
        prog.rows.push_back({idx, val, 0, 0});
        ++prog.equality_rows;
      }
      int least = 0;
      for (const ArcUse& u : P.sides[k]) least += prog.minimum[u.arc];
      if (least < side_min[k]) {
        idx.clear();
        val.clear();
        for (const ArcUse& u : P.sides[k]) idx.push_back(u.arc), val.push_back(1);
        prog.rows.push_back({idx, val, static_cast<double>(side_min[k]), COIN_DBL_MAX});
      }
    }
  }
  // 3D lengths and the area.
  std::vector<double> length(na, 0.0);
  for (int a = 0; a < na; ++a) {
    const auto& V = L.arcs[a].vertices;
    for (std::size_t k = 0; k + 1 < V.size(); ++k) length[a] += scaled_distance(L.positions[V[k]], L.positions[V[k + 1]], o.length_scale);
    if (!std::isfinite(length[a])) throw Error(ErrorKind::InvalidArgument, "quantize_layout: arc " + str(a) + "'s length is not finite", {a});
  }
  Quantization out;
  QuantizeStats& st = out.stats;
  st.arcs = na;
  st.patches = np;
  st.rows = prog.equality_rows;
  std::vector<double> target(na), weight(na);
  auto set_targets = [&](double H, int N) {
    for (int a = 0; a < na; ++a) {
      target[a] = N > 0 ? N : length[a] / H;
      weight[a] = o.weight == QuantizeWeight::Absolute ? 1.0 : 1.0 / std::max(target[a], 1.0);
    }
  };
  auto run = [&](double H, int N) {
    set_targets(H, N);
    ++st.solves;
    Solve s = solve(prog, target, weight, o.max_nodes);
    st.nodes += s.nodes;
    if (!s.x.empty()) {
      if (const std::string e = violation(L, s.x, prog.minimum); !e.empty()) {
        s.status = QuantizeStatus::NoSolution;
        s.x.clear();
        s.why = "CBC's solution, rounded to integers, breaks a constraint: " + e;
      }
    }
    return s;
  };
  // sum over patches of a b: in int64 for integer lengths, in double for the relaxation's.
  auto total = [&]<class T>(const std::vector<T>& x) {
    using Sum = std::conditional_t<std::is_integral_v<T>, std::int64_t, double>;
    Sum q = 0;
    for (const LayoutPatch& P : L.patches) {
      Sum a = 0, b = 0;
      for (const ArcUse& u : P.sides[0]) a += x[u.arc];
      for (const ArcUse& u : P.sides[1]) b += x[u.arc];
      q += a * b;
    }
    return q;
  };
  Solve kept;
  double kept_H = 0;
  if (o.resolution > 0) {
    kept = run(0, o.resolution);
  } else if (o.edge_length > 0) {
    kept_H = o.edge_length;
    kept = run(kept_H, 0);
  } else {
    double area = 0;
    for (const auto& T : L.triangles) {
      const Vec3d &p = L.positions[T[0]], &q = L.positions[T[1]], &r = L.positions[T[2]];
      const double ux = q.x - p.x, uy = q.y - p.y, uz = q.z - p.z, vx = r.x - p.x, vy = r.y - p.y, vz = r.z - p.z;
      const double cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
      area += 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
    }
    area *= o.length_scale * o.length_scale;
    double H = area > 0 && std::isfinite(area) ? std::sqrt(area / static_cast<double>(o.quads)) : 1.0;
    // Sizing rounds on the relaxation (Clp alone, milliseconds; QuantizeOptions::quads): its total
    // Q(H), then H from the two latest (H, Q) by the secant in log-log (Q ~ H^-alpha, alpha
    // clamped into [0.25, 4]; alpha = 2 before there are two), the H whose total is nearest to Q
    // kept; then one integer solve at that H.
    const double Q = static_cast<double>(o.quads);
    double best_H = H, best_gap = -1, prev_H = 0, prev_q = 0, integral_H = 0, integral_best = 0;
    Solve integral;  // the best integral relaxation (empty x: none)
    for (int round = 0; round <= o.quad_corrections; ++round) {
      set_targets(H, 0);
      ++st.relaxations;
      Solve r = solve(prog, target, weight, o.max_nodes, true);
      if (r.relaxed.empty()) break;  // infeasible (or unbounded): the integer solve says why
      const double q = total(r.relaxed);
      const double gap = std::abs(q - Q);
      if (best_gap < 0 || gap < best_gap) best_gap = gap, best_H = H;
      // An integral relaxation is the integer optimum at its H (solve): kept if its total is
      // within 1 % of Q more than the best seen, so that no integer program is needed.
      if (!r.x.empty() && violation(L, r.x, prog.minimum).empty()) {
        const double integral_gap = std::abs(static_cast<double>(total(r.x)) - Q);
        if (integral.x.empty() || integral_gap < integral_best) integral_best = integral_gap, integral_H = H, integral = std::move(r);
      }
      if (!(q > 0) || gap <= 0.002 * Q) break;
      double alpha = 2;
      if (prev_H > 0 && prev_H != H && prev_q > 0 && prev_q != q)
        alpha = std::clamp(det_log(prev_q / q) / det_log(H / prev_H), 0.25, 4.0);
      prev_H = H;
      prev_q = q;
      H *= det_exp(det_log(q / Q) / alpha);  // libm's log / pow differ by machine (core/det_math.h)
    }
    if (!integral.x.empty() && integral_best <= best_gap + 0.01 * Q) {
      kept = std::move(integral);
      kept_H = integral_H;
      ++st.solves;
    } else {
      kept = run(best_H, 0);
      kept_H = best_H;
    }
  }
  out.status = kept.status;
  if (kept.x.empty()) {
    out.reason = !kept.why.empty() ? kept.why
                 : kept.status == QuantizeStatus::Infeasible
                     ? "no arc lengths >= their minima give every patch equal opposite sides (infeasible: proved by Clp/CBC)"
                     : "CBC found no solution within " + str(o.max_nodes) + " branch-and-bound nodes";
  } else {
    out.arc_length = std::move(kept.x);
    out.patch_size.resize(np);
    for (int p = 0; p < np; ++p)
      for (int k : {0, 1})
        for (const ArcUse& u : L.patches[p].sides[k]) out.patch_size[p][k] += out.arc_length[u.arc];
    out.quads = total(out.arc_length);
    out.edge_length = kept_H;
    st.deviation = kept.objective;
  }
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace igm
