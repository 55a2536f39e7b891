// Close pairs of opposite cones (close_cone_pairs, cross_field.h) and their cancellation
// and the cone cleanup (clean_cones, field_internal.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <queue>
#include <set>
#include <utility>

#include "field_internal.h"
#include "../quality/vec3.h"

namespace igm {

namespace {

using quality_internal::norm;
using quality_internal::sub;

constexpr double kQuarter = std::numbers::pi / 2;

// Dijkstra along the edges from `sources` (distance 0) up to `radius`, interior edges only if
// `interior_only`, never through a vertex marked in `blocked` (one may be reached). dist / via must be INFINITY / -1 everywhere on entry; every vertex reached is
// listed in `touched` (to reset them: reset()). via[v]: the half-edge by which v was reached.
// Ties by (distance, vertex id): deterministic. Stops early once `stop` is settled (-1: never).
// Each vertex is settled once: O(k log k) for the k vertices within the radius.
void dijkstra(const TriMesh& mesh, const std::vector<Vec3d>& p, const std::vector<int>& sources, double radius,
              bool interior_only, int stop, const std::vector<char>* blocked, std::vector<double>& dist,
              std::vector<int>& via, std::vector<int>& touched) {
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (int s : sources)
    if (dist[s] != 0) {
      if (dist[s] == INFINITY) touched.push_back(s);
      dist[s] = 0;
      heap.push({0.0, s});
    }
  const int nh = mesh.num_halfedges();
  while (!heap.empty()) {
    const auto [d, v] = heap.top();
    heap.pop();
    if (d > dist[v]) continue;
    if (v == stop) return;
    if (blocked && (*blocked)[v] && d > 0) continue;  // reached, not passed through
    // The edges at v: each fan half-edge h leaving v (to target(h)) and prev(h) entering v (from
    // its origin); the latter is met again as the next fan half-edge's twin, except at the end
    // of an open fan, where it is the incoming boundary edge.
    const int first = mesh.vertex_halfedge(v);
    int h = first;
    for (int step = 0; step < nh && h >= 0; ++step) {
      const int in = TriMesh::prev(h);
      for (const auto [e, w] : {std::pair{h, mesh.target(h)}, std::pair{in, mesh.origin(in)}}) {
        if (interior_only && mesh.twin(e) < 0) continue;
        const double nd = d + norm(sub(p[w], p[v]));
        if (nd <= radius && nd < dist[w]) {
          if (dist[w] == INFINITY) touched.push_back(w);
          dist[w] = nd;
          via[w] = e;
          heap.push({nd, w});
        }
      }
      h = mesh.next_around_origin(h);
      if (h == first) break;
    }
  }
}

void reset(std::vector<double>& dist, std::vector<int>& via, std::vector<int>& touched) {
  for (int v : touched) {
    dist[v] = INFINITY;
    via[v] = -1;
  }
  touched.clear();
}

}  // namespace

std::vector<ConePair> close_cone_pairs(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                       const CrossField& field, double max_distance) {
  const int nv = mesh.num_vertices();
  const double mean = field_internal::mean_edge_length(mesh, positions);
  std::vector<ConePair> candidates;
  if (!(mean > 0) || !(max_distance >= 0)) return candidates;
  std::vector<double> dist(nv, INFINITY);
  std::vector<int> via(nv, -1), touched;
  for (const Cone& c : field.cones) {
    if (c.valence >= 4) continue;
    dijkstra(mesh, positions, {c.vertex}, max_distance * mean, false, -1, nullptr, dist, via, touched);
    for (int w : touched)
      if (!field.on_boundary[w] && field.valence[w] > 4 && field.valence[w] + c.valence == 8)
        candidates.push_back({c.vertex, w, dist[w] / mean});
    reset(dist, via, touched);
  }
  std::sort(candidates.begin(), candidates.end(), [](const ConePair& a, const ConePair& b) {
    if (a.distance != b.distance) return a.distance < b.distance;
    if (a.positive != b.positive) return a.positive < b.positive;
    return a.negative < b.negative;
  });
  std::vector<char> used(nv, 0);
  std::vector<ConePair> pairs;
  for (const ConePair& c : candidates)
    if (!used[c.positive] && !used[c.negative]) {
      used[c.positive] = used[c.negative] = 1;
      pairs.push_back(c);
    }
  return pairs;
}

namespace field_internal {

namespace {

// One close pair's cancellation: the period changes along its path and the faces to re-solve.
struct PairPlan {
  std::pair<int, int> move;  // the vertices (plus, minus): valence + 1 and valence - 1
  std::vector<int> plus;    // half-edges whose period gains 1 (their twins lose 1)
  std::vector<int> region;  // faces with a corner within the radius of the path (unconstrained)
};

// The angles on the faces marked in `region` minimizing
// sum_e w_e (theta_g - theta_f - rho_h - pi/2 p_h)^2 with every period p fixed and theta fixed
// outside the region (Ray, Vallet, Li, Levy 2008, "N-symmetry direction field design", the
// angle form); written into theta reduced to [0, pi/2). False (theta untouched) if the solve
// gives a non-finite angle.
bool solve_angles(const TriMesh& mesh, const System& sys, const FaceFrames& frames, const std::vector<int>& period,
                  const std::vector<char>& region, std::vector<double>& theta, double& factor_seconds) {
  const int nf = mesh.num_faces();
  std::vector<int> free_faces, slot(nf, -1);
  bool touches_outside = false;
  for (int f = 0; f < nf; ++f)
    if (region[f]) {
      slot[f] = static_cast<int>(free_faces.size());
      free_faces.push_back(f);
      for (int i = 0; i < 3; ++i) {
        const int t = mesh.twin(3 * f + i);
        if (t >= 0 && !region[TriMesh::face(t)]) touches_outside = true;
      }
    }
  if (!touches_outside && !free_faces.empty()) {  // the whole surface: pin its first face
    slot[free_faces.front()] = -1;
    free_faces.erase(free_faces.begin());
    for (std::size_t i = 0; i < free_faces.size(); ++i) slot[free_faces[i]] = static_cast<int>(i);
  }
  const int n = static_cast<int>(free_faces.size());
  if (n == 0) return true;
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    const int f = free_faces[i];
    double diag = 0;
    for (int k = 0; k < 3; ++k) {
      const int h = 3 * f + k, t = mesh.twin(h);
      if (t < 0) continue;
      const int g = TriMesh::face(t);
      const double w = sys.weight[h];
      diag += w;
      b[i] -= w * (frames.transport[h] + kQuarter * period[h]);
      if (slot[g] >= 0)
        trip.emplace_back(slot[g], i, -w);
      else
        b[i] += w * theta[g];
    }
    trip.emplace_back(i, i, diag * (1 + kRegularization));  // strictly dominant: field_internal.h
  }
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(trip.begin(), trip.end());
  Factor<double> factor;
  factor.compute(m, factor_seconds);
  const Eigen::VectorXd x = factor.solve(b);
  if (!x.allFinite()) return false;
  for (int i = 0; i < n; ++i) {
    const double t = x[i] - kQuarter * std::floor(x[i] / kQuarter);  // in [0, pi/2]
    theta[free_faces[i]] = t < kQuarter ? t : 0.0;
  }
  return true;
}

}  // namespace

namespace {

// Lexicographic score of a field's singularities, lower is better: the vertices no seamless map
// allows (interior valence < 1, boundary k < 1), the splits still to do (interior valence 1: two,
// valence 2 / 6: one, as asked), then the total deviation sum |4 - valence| + sum |2 - k|.
std::array<long long, 3> singularity_score(const CrossField& field, const CrossFieldOptions& o) {
  long long illegal = 0, halves = 0, deviation = 0;
  for (std::size_t v = 0; v < field.valence.size(); ++v) {
    const int val = field.valence[v];
    illegal += val < 1;
    if (!field.on_boundary[v])
      halves += 2 * (o.split_valence1 && val == 1) + (o.split_valence2 && val == 2) + (o.split_valence6 && val == 6) +
                (o.split_valence7 && val >= 7);
    deviation += std::abs((field.on_boundary[v] ? 2 : 4) - val);
  }
  return {illegal, halves, deviation};
}

}  // namespace

void clean_cones(const TriMesh& mesh, const std::vector<Vec3d>& p, const System& sys, const std::vector<char>& fixed,
                 const CrossFieldOptions& options, CrossField& field) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces(), nh = mesh.num_halfedges();
  const double mean = sys.mean_edge;
  CrossFieldStats& st = field.stats;
  std::vector<double> dist(nv, INFINITY);
  std::vector<int> via(nv, -1), touched;
  // Split and raise moves (plus, minus) whose re-solve was refused: a later round takes the next
  // candidate instead of the same one again.
  std::set<std::pair<int, int>> refused;
  for (int round = 0; round < options.cleanup_rounds; ++round) {
    const auto regular = [&](int v) { return field.valence[v] == (field.on_boundary[v] ? 2 : 4); };
    // Paths avoid every other singular vertex: the field twists most near a cone, where a quarter
    // turn more would not spread over a few faces.
    std::vector<char> singular(nv, 0);
    for (int v = 0; v < nv; ++v) singular[v] = !regular(v);
    // Moves (CrossFieldOptions): a quarter turn of index from `minus` (valence - 1) to `plus`
    // (valence + 1) along the shortest path of interior edges.
    struct Move {
      int plus, minus;
      double distance;  // in mean edge lengths, for the region's radius
    };
    std::vector<Move> moves;
    if (options.remove_close_pairs)
      for (const ConePair& pr : field.close_pairs)
        if (field.valence[pr.positive] == 3 && field.valence[pr.negative] == 5 &&
            !refused.count({pr.positive, pr.negative}))
          moves.push_back({pr.positive, pr.negative, pr.distance});
    for (int v = 0; v < nv; ++v) {
      const int val = field.valence[v];
      const bool raise = options.remove_close_pairs && val < 1;
      const bool split2 = ((options.split_valence2 && val == 2) || (options.split_valence1 && val == 1)) &&
                          !field.on_boundary[v];
      // v gives a quarter turn away (valence 6 into two 5s, or a valence >= 7).
      const bool gives = ((options.split_valence6 && val == 6) || (options.split_valence7 && val >= 7)) &&
                         !field.on_boundary[v];
      if (!raise && !split2 && !gives) continue;
      // The move with partner w, (plus, minus); w may take it if interior and not refused before.
      auto move_with = [&](int w) { return gives ? std::make_pair(w, v) : std::make_pair(v, w); };
      auto usable = [&](int w) { return w != v && !field.on_boundary[w] && !refused.count(move_with(w)); };
      // Candidates within 8 mean edges; ties by vertex id (sorted by (distance, id)). Paths avoid
      // the other singular vertices (`blocked`); a cone walled in by them (a spike of three tiny
      // faces whose neighbours are all cones) is given paths through them (a vertex inside a path
      // keeps its valence). Returns the partner (-1: none) with dist set for it.
      auto find_partner = [&](const std::vector<char>* blocked) {
        dijkstra(mesh, p, {v}, 8 * mean, true, -1, blocked, dist, via, touched);
        std::vector<int> near(touched);
        std::sort(near.begin(), near.end(), [&](int a, int b) { return dist[a] != dist[b] ? dist[a] < dist[b] : a < b; });
        if (raise)  // the nearest interior cone of valence >= 5, else the nearest regular vertex
          for (int kind = 0; kind < 2; ++kind)
            for (int w : near)
              if (usable(w) && (kind == 0 ? field.valence[w] >= 5 : regular(w))) return w;
        if (gives && val >= 7)  // the nearest interior cone of valence <= 3: both nearer regular
          for (int w : near)
            if (usable(w) && field.valence[w] <= 3) return w;
        if (split2 || gives)  // the nearest regular interior vertex at least split_distance away
          for (int w : near)
            if (usable(w) && regular(w) && dist[w] >= options.split_distance * mean) return w;
        return -1;
      };
      int partner = find_partner(&singular);
      if (partner < 0) {
        reset(dist, via, touched);
        partner = find_partner(nullptr);
      }
      if (partner >= 0) {
        const double d = dist[partner] / mean;
        const auto [plus, minus] = move_with(partner);
        moves.push_back({plus, minus, d});
      }
      reset(dist, via, touched);
    }
    std::vector<PairPlan> plans;
    std::vector<int> stamp(nf, -1);
    for (const Move& mv : moves) {
      dijkstra(mesh, p, {mv.plus}, (2 * mv.distance + 2) * mean, true, mv.minus, &singular, dist, via, touched);
      if (via[mv.minus] < 0) {  // walled in by other cones (above): through them
        reset(dist, via, touched);
        dijkstra(mesh, p, {mv.plus}, (2 * mv.distance + 2) * mean, true, mv.minus, nullptr, dist, via, touched);
      }
      PairPlan plan;
      plan.move = {mv.plus, mv.minus};
      std::vector<int> path;  // vertices, from `minus` back to `plus`
      if (via[mv.minus] >= 0) {
        for (int v = mv.minus, step = 0; v != mv.plus && step < nv; ++step) {
          path.push_back(v);
          const int e = via[v];
          v = mesh.origin(e) == v ? mesh.target(e) : mesh.origin(e);
          // p += 1 on the half-edge from the path vertex nearer `minus` to the one nearer `plus`
          // adds one to the latter's valence and takes one from the former's (cross_field.h,
          // Valence): along the whole path only the two ends change.
          plan.plus.push_back(mesh.origin(e) == path.back() ? e : mesh.twin(e));
        }
        path.push_back(mv.plus);
      }
      reset(dist, via, touched);
      if (plan.plus.empty()) continue;
      const double r = (round + 2) * std::max(mv.distance, 1.0) * mean;
      dijkstra(mesh, p, path, r, false, -1, nullptr, dist, via, touched);
      const int id = static_cast<int>(plans.size());
      for (int v : touched) {
        const int first = mesh.vertex_halfedge(v);
        int h = first;
        for (int step = 0; step < nh && h >= 0; ++step) {
          const int f = TriMesh::face(h);
          if (!fixed[f] && stamp[f] != id) {
            stamp[f] = id;
            plan.region.push_back(f);
          }
          h = mesh.next_around_origin(h);
          if (h == first) break;
        }
      }
      reset(dist, via, touched);
      plans.push_back(std::move(plan));
    }
    // Apply the plans together. A vertex that moves further from regular and ends outside
    // valence 3..5 (boundary: further from k = 2) means the solve could not spread some quarter
    // turn (rounding put it on one edge): the plans whose regions touch it are dropped and the
    // rest tried again (at most plans + 1 attempts). The round is kept if it lowers the
    // singularity score (singularity_score).
    std::vector<char> dropped(plans.size(), 0);
    bool kept = false;
    const std::size_t refused_before = refused.size();
    for (std::size_t attempt = 0; attempt <= plans.size(); ++attempt) {
      std::vector<int> period = field.period;
      std::vector<char> region(nf, 0);
      bool active = false;
      for (std::size_t i = 0; i < plans.size(); ++i) {
        if (dropped[i]) continue;
        active = true;
        for (int h : plans[i].plus) {
          ++period[h];
          --period[mesh.twin(h)];
        }
        for (int f : plans[i].region) region[f] = 1;
      }
      if (!active) break;
      CrossField trial = field;
      if (!solve_angles(mesh, sys, field.frames, period, region, trial.theta, st.factor_seconds)) break;
      derive_singularities(mesh, trial);
      std::vector<char> bad_face(nf, 0);
      bool bad = false;
      for (int v = 0; v < nv; ++v) {
        if (trial.valence[v] == field.valence[v]) continue;
        const int regular_valence = trial.on_boundary[v] ? 2 : 4;
        const bool worse = std::abs(trial.valence[v] - regular_valence) > std::abs(field.valence[v] - regular_valence);
        if (worse && (trial.on_boundary[v] || trial.valence[v] < 3 || trial.valence[v] > 5)) {
          bad = true;
          const int first = mesh.vertex_halfedge(v);
          int h = first;
          for (int step = 0; step < nh && h >= 0; ++step) {
            bad_face[TriMesh::face(h)] = 1;
            h = mesh.next_around_origin(h);
            if (h == first) break;
          }
        }
      }
      if (!bad) {
        // A move whose ends did not both change (the re-solve put its quarter turn elsewhere) is
        // refused: the next round tries another partner.
        for (std::size_t i = 0; i < plans.size(); ++i)
          if (!dropped[i]) {
            const auto [plus, minus] = plans[i].move;
            if (trial.valence[plus] == field.valence[plus] || trial.valence[minus] == field.valence[minus])
              refused.insert(plans[i].move);
          }
        if (singularity_score(trial, options) < singularity_score(field, options)) {
          field = std::move(trial);
          kept = true;
        }
        break;
      }
      bool excluded = false;
      for (std::size_t i = 0; i < plans.size(); ++i)
        if (!dropped[i])
          for (int f : plans[i].region)
            if (bad_face[f]) {
              dropped[i] = 1;
              excluded = true;
              ++st.cleanup_rejected;
              refused.insert(plans[i].move);
              break;
            }
      if (!excluded) break;
    }
    if (!kept) {
      if (refused.size() > refused_before) continue;  // the next round tries other partners
      break;
    }
    st.cleanup_rounds = round + 1;
    field.close_pairs = close_cone_pairs(mesh, p, field, options.close_pair_distance);
  }
}

}  // namespace field_internal

}  // namespace igm
