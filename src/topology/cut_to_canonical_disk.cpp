#include "igm/topology/cut_to_canonical_disk.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "igm/core/error.h"
#include "igm/topology/handle_slides.h"
#include "igm/topology/ring_bound.h"
#include "igm/topology/tighten_loops.h"
#include "normal_form.h"

namespace igm {

namespace {

using namespace topology_internal;

// The positions scaled by one power of two so that the largest |coordinate| is in [1, 2): edge
// lengths and path sums are then finite (at most 2*sqrt(3) per edge) whatever the input's
// magnitude (1e300 would overflow the squares to inf, and Dijkstra would reach nothing), and a
// power-of-two scale changes no comparison except by underflow to 0, which only makes ties.
// The lengths only choose among homotopy bases: any finite non-negative lengths are correct.
// Throws NonFinite for a NaN or infinite coordinate.
std::vector<Vec3d> unit_scaled(const std::vector<Vec3d>& positions) {
  double m = 0;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const Vec3d& p = positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(ErrorKind::NonFinite, "vertex " + std::to_string(v) + " has a non-finite coordinate",
                  {static_cast<std::int64_t>(v)});
    m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  }
  if (m == 0) return positions;
  const int e = std::ilogb(m);  // m in [2^e, 2^(e+1))
  std::vector<Vec3d> out(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v)
    out[v] = {std::ldexp(positions[v].x, -e), std::ldexp(positions[v].y, -e), std::ldexp(positions[v].z, -e)};
  return out;
}

// Cuts the surface along res.loops: fills disk_triangles, disk_to_surface, boundary and sides.
// The boundary walk starts with the cut half-edge `first` leaving the root (any if -1). O(n).
void build_cut(CutResult& res, int first) {
  const int root = res.root;
  const int nloops = static_cast<int>(res.loops.size());
  const int genus = res.genus;
  res.disk_triangles.clear();
  res.disk_to_surface.clear();
  res.boundary.clear();
  res.sides.clear();
  {
    const auto& Mm = res.surface.mesh;
    const int nh = Mm.num_halfedges();
    std::vector<int> loop_of(Mm.num_vertices(), -1), pos_in_loop(Mm.num_vertices(), -1);
    std::vector<char> is_cut(nh, 0);
    for (int i = 0; i < nloops; ++i) {
      const auto& L = res.loops[i];
      for (std::size_t j = 0; j < L.size(); ++j) {
        const int h = find_he(Mm, L[j], L[(j + 1) % L.size()]);
        if (is_cut[h]) internal("loop edge used twice", {L[j]});
        is_cut[h] = is_cut[Mm.twin(h)] = 1;
        if (j > 0) {
          if (loop_of[L[j]] >= 0) internal("loops share a vertex other than the root", {L[j]});
          loop_of[L[j]] = i, pos_in_loop[L[j]] = static_cast<int>(j);
        }
      }
    }
    std::vector<int> wedge(nh, -1);
    auto& d2s = res.disk_to_surface;
    for (int v = 0; v < Mm.num_vertices(); ++v) {
      const int h0 = Mm.vertex_halfedge(v);
      int start = h0;
      for (int h = Mm.next_around_origin(h0);; h = Mm.next_around_origin(h)) {  // <= valence steps
        if (is_cut[h]) { start = h; break; }
        if (h == h0) break;
      }
      int copy = static_cast<int>(d2s.size());
      d2s.push_back(v);
      int h = start;
      do {  // one turn around v: valence steps
        wedge[h] = copy;
        h = Mm.next_around_origin(h);
        if (h != start && is_cut[h]) {
          copy = static_cast<int>(d2s.size());
          d2s.push_back(v);
        }
      } while (h != start);
    }
    res.disk_triangles.resize(Mm.num_faces());
    for (int f = 0; f < Mm.num_faces(); ++f)
      res.disk_triangles[f] = {wedge[3 * f], wedge[3 * f + 1], wedge[3 * f + 2]};
    // Boundary: cut half-edges, chained through the fan of their target (clockwise).
    int ncut = 0;
    for (int h = 0; h < nh; ++h)
      if (is_cut[h]) {
        ++ncut;
        if (first < 0 && Mm.origin(h) == root) first = h;
      }
    if (first < 0 || !is_cut[first] || Mm.origin(first) != root) internal("bad start of the boundary walk");
    std::vector<int> bh;
    int h = first;
    do {
      bh.push_back(h);
      if (static_cast<int>(bh.size()) > ncut) internal("disk boundary does not close");
      int g = TriMesh::next(h);
      int guard = 0;
      while (!is_cut[g]) {
        g = TriMesh::next(Mm.twin(g));
        if (++guard > nh) internal("boundary walk lost");
      }
      h = g;
    } while (h != first);
    if (static_cast<int>(bh.size()) != ncut) internal("the cut has more than one boundary cycle");
    for (int x : bh) res.boundary.push_back(wedge[x]);
    // Sides.
    for (std::size_t i = 0; i < bh.size(); ++i) {
      if (Mm.origin(bh[i]) == root) res.sides.push_back({});
      res.sides.back().disk_vertices.push_back(wedge[bh[i]]);
    }
    for (std::size_t s = 0; s < res.sides.size(); ++s) {
      auto& S = res.sides[s];
      S.disk_vertices.push_back(res.sides[(s + 1) % res.sides.size()].disk_vertices.front());
      if (S.disk_vertices.size() < 3) internal("side without interior vertex");
      int x = d2s[S.disk_vertices[1]];
      S.loop = loop_of[x];
      if (S.loop < 0) internal("side leaves the root off a loop", {x});
      S.inverse = pos_in_loop[x] != 1;
    }
    if (static_cast<int>(res.sides.size()) != 4 * genus)
      internal("boundary has " + std::to_string(res.sides.size()) + " sides, expected " + std::to_string(4 * genus));
    for (std::size_t s = 0; s < res.sides.size(); ++s)
      for (std::size_t t = 0; t < res.sides.size(); ++t)
        if (t != s && res.sides[t].loop == res.sides[s].loop) res.sides[s].mate = static_cast<int>(t);
  }
}

Word word_of(const CutResult& res) {
  Word w;
  for (const auto& s : res.sides) w.push_back({s.loop, s.inverse});
  return w;
}

// The embedding pre-conditions (embed/tutte.h, Floater 2003), made to hold by edge splits at
// midpoints on the disk that build_cut made: no interior disk edge joins two vertices of one
// polygon side (a root copy lies on its two sides). This also excludes triangles with three
// vertices on one side (such a triangle has an interior edge). Triangles with boundary vertices on
// several sides, e.g. a root wedge that is one triangle, are fixed by the strictly convex boundary
// and positive, so they need no split. A split vertex is interior to the disk, so no split creates
// a new violation: one pass. Pre: build_cut(res) done. Post: the cut must be rebuilt. Returns the
// number of splits. O(n).
int precondition_pass(CutResult& res) {
  auto& rs = res.surface;
  auto& Mm = rs.mesh;
  const int nd = static_cast<int>(res.disk_to_surface.size());
  std::vector<int> side_a(nd, -1), side_b(nd, -1);  // the (at most two) sides through a disk vertex
  for (int s = 0; s < static_cast<int>(res.sides.size()); ++s)
    for (int d : res.sides[s].disk_vertices) (side_a[d] < 0 ? side_a[d] : side_b[d]) = s;
  auto share_side = [&](int p, int q) {
    if (side_a[p] < 0 || side_a[q] < 0) return false;
    return side_a[p] == side_a[q] || side_a[p] == side_b[q] || (side_b[p] >= 0 && (side_b[p] == side_a[q] || side_b[p] == side_b[q]));
  };
  std::vector<char> is_cut(Mm.num_halfedges(), 0);
  for (const auto& L : res.loops)
    for (std::size_t j = 0; j < L.size(); ++j) {
      const int h = find_he(Mm, L[j], L[(j + 1) % L.size()]);
      is_cut[h] = is_cut[Mm.twin(h)] = 1;
    }
  auto disk_corner = [&](int h) { return res.disk_triangles[TriMesh::face(h)][h % 3]; };
  std::vector<std::pair<int, int>> todo;
  for (int h = 0; h < Mm.num_halfedges(); ++h)
    if (!is_cut[h] && h < Mm.twin(h) && share_side(disk_corner(h), disk_corner(TriMesh::next(h))))
      todo.push_back({Mm.origin(h), Mm.target(h)});
  for (auto [a, b] : todo) rs.split_edge(find_he(Mm, a, b), make_rational(1, 2));
  return static_cast<int>(todo.size());
}

// Renumbers and reorients res.loops so that the word `cur` (the loops' word up to rotation, in g
// commutator blocks) reads exactly L0 L1 L0^-1 L1^-1 L2 L3 ... Throws Internal if it is not in
// blocks. O(n).
void relabel_blocks(CutResult& res, const Word& cur) {
  const int r = commutator_rotation(cur);
  if (r < 0) internal("word is not in commutator blocks: " + to_string(cur));
  const int n = static_cast<int>(cur.size());
  std::vector<std::vector<int>> loops(res.loops.size());
  for (int k = 0; k < n / 4; ++k)
    for (int t = 0; t < 2; ++t) {
      const Letter l = cur[(r + 4 * k + t) % n];
      auto L = res.loops[l.loop];
      if (l.inverse) std::reverse(L.begin() + 1, L.end());
      loops[2 * k + t] = std::move(L);
    }
  res.loops = std::move(loops);
}

// How many root candidates the normal form tries (root = -1, CutOptions::normal_form_roots = -1):
// clamp(min(2e5 / F, 4e6 / (F g)), 1, 12). A candidate's construction costs about its output,
// which grows with g as well as F (the crosses on cheese, g133 on 17.8k faces: 1.7-3.5 s each, 31 s
// for the 11 roots that 2e5 / F alone gives, 148.4k vertices; one root: 160.8k, 2-3.5 s, since
// stop 24 1.6-1.9 s). Up to g = 20 it is 2e5 / F as before.
long normal_form_root_count(const TriMesh& mesh, int genus) {
  const long long f = std::max(1, mesh.num_faces());
  return std::clamp<long>(static_cast<long>(std::min(200000LL / f, 4000000LL / (f * std::max(genus, 1)))), 1L, 12L);
}

// Root candidates: the vertex of maximum valence (lowest id among ties), then vertices i * V / k
// for i = 1..k-1 (without repeats). O(V).
std::vector<int> root_candidates(const TriMesh& mesh, long k) {
  const int nv = mesh.num_vertices();
  int first = 0, best_valence = -1;
  for (int v = 0; v < nv; ++v)
    if (mesh.valence(v) > best_valence) best_valence = mesh.valence(v), first = v;
  std::vector<int> roots{first};
  for (long i = 1; i < k; ++i) {
    const int v = static_cast<int>(i * nv / k);
    if (std::find(roots.begin(), roots.end(), v) == roots.end()) roots.push_back(v);
  }
  return roots;
}

// The ring deficit of r: the sum of max(0, 4g - |ring_j|) over the hop rings ring_1, ring_2, ...
// around r before the first with at least 4g vertices, each such level a place where the 4g strands
// leaving r must share vertices (ring_bound.h's floor without its disk test, which the ring search
// would cost too much for). `rings` on the mesh; the search stops after 20,000 vertices:
// O(min(V, 20000)).
long ring_deficit(HopRings& rings, int root, int genus) {
  long deficit = 0, visited = 1;
  rings.start(root);
  while (visited < 20000 && rings.next()) {  // each ring is new: at most 20,000 vertices in all
    const long size = static_cast<long>(rings.ring().size());
    visited += size;
    if (size >= 4L * genus) break;
    deficit += 4L * genus - size;
  }
  return deficit;
}

// Root candidates for the basis without the normal form (and for step 3c's start): the vertex of
// maximum valence, then of a spread sample (root_candidates, min(V, 50 k) of them) the k - 1 others
// with the least ring deficit, the sample's order breaking ties. O(50 k min(V, 20000) + V).
// Measured: on the shared meshes of genus <= 9 and generated genus 2-12 (16 meshes) the cut adds
// 1,204 vertices in all instead of 1,595 with the spread candidates (couplingdown 134 -> 106); with
// the normal form (step 3's own candidates) it does not help (couplingdown 300 -> 393; stop 36,
// with steps 3c-3d: the 36 generated meshes 5,664 -> 5,593, couplingdown 129 either way), so step
// 3 keeps the spread.
std::vector<int> root_candidates_by_ring_deficit(const TriMesh& mesh, long k, int genus) {
  const int nv = mesh.num_vertices();
  const std::vector<int> sample = root_candidates(mesh, std::min<long>(nv, 50 * k));
  HopRings rings(mesh);
  std::vector<std::pair<long, int>> score;  // (deficit, position in the sample)
  for (int i = 0; i < static_cast<int>(sample.size()); ++i) score.push_back({ring_deficit(rings, sample[i], genus), i});
  // The vertex of maximum valence (the sample's first) stays a candidate, the others by deficit.
  std::stable_sort(score.begin() + 1, score.end());
  std::vector<int> roots;
  for (long i = 0; i < k && i < static_cast<long>(score.size()); ++i) roots.push_back(sample[score[i].second]);
  return roots;
}

}  // namespace

std::string CutResult::word() const { return to_string(word_of(*this)); }

namespace {

// Step 3 (options.normal_form): the root and metric (the given root, step 3c's root, or among
// deterministic candidates), the construction of each (the rounds, the crosses, or both raced), the
// kept one's congestion reweighting and its detaching, drawn: fills res.root, res.loops,
// res.surface and res.stats. `unit`: the positions unit-scaled; t_start: when the stage began (for
// the stats); slides_root >= 0 (with options.root = -1): the root step 3c's greedy system chose,
// tried with both metrics instead of the candidates. Throws Unsupported if no candidate stays
// within the growth bounds.
void normal_form_system(const TriMesh& mesh, const std::vector<Vec3d>& positions, const std::vector<Vec3d>& unit,
                        const CutOptions& options, int genus, Clock::time_point t_start, CutResult& res,
                        int slides_root = -1) {
  const int nv0 = mesh.num_vertices();
  RefinedSurface& rs = res.surface;
  // Root and metric: the given root with 3D lengths, step 3c's root with 3D lengths and hop
  // counts, or among K deterministic candidates
  // (root_candidates, K = normal_form_root_count) with 3D lengths and hop counts (one root: hop
  // counts only), the pair whose planned detaching ends with the fewest vertices
  // (planned_vertices; only that one is drawn); a candidate stops once it has more than the best
  // so far. Per candidate (Best): the rounds, bounded by max_rounds_growth; if they pass it, the
  // crosses (a lone candidate: both at once, see run_candidate). After two candidates whose
  // rounds passed it, only the crosses.
  const long limit = nv0 + static_cast<long>(options.max_normal_form_growth * nv0);
  const long rounds_limit = std::min(limit, nv0 + static_cast<long>(options.max_rounds_growth * nv0));
  std::vector<std::pair<int, bool>> candidates;
  if (options.root >= 0) {
    candidates.push_back({options.root, false});
  } else if (slides_root >= 0) {
    candidates = {{slides_root, false}, {slides_root, true}};
  } else {
    const long k = options.normal_form_roots > 0 ? std::min<long>(options.normal_form_roots, nv0)
                                                  : normal_form_root_count(mesh, genus);
    // One root: hop counts, which count the vertices the normal form pays for (cheese's root 2:
    // 161.9k planned vertices, against 257k with 3D lengths; the 1M-face g20: 536.6k, 538.6k).
    for (int c : root_candidates(mesh, k))
      for (bool hops : {false, true})
        if (hops || k > 1) candidates.push_back({c, hops});
  }
  using C = CutOptions::Construction;
  // Each candidate is only planned (its detaching counted, not drawn); the kept one is realized
  // once at the end. Candidates go in chunks of two, in order: the two of a chunk are bounded by
  // the best of the chunks before it and run concurrently (options.parallel), then are merged in
  // order (a candidate is kept if it plans strictly fewer vertices), so that the result does not
  // depend on the threads.
  // A plan of the congestion reweighting, with its construction's stats.
  struct Ranked {
    DetachPlan plan;
    CutStats stats;
    int round = 0;  // of the reweighting (0: the first plan)
  };
  struct Outcome {
    bool ok = false, rounds_passed = false, crosses = false, hops = false;
    bool reweighted = false;  // a rounds plan already reweighted (in a race)
    CutStats stats;
    DetachPlan plan;
    std::vector<Ranked> ranked;  // its reweighting's best plans (reweight), `plan` first
  };
  // A construction's starting point: the input surface, unrefined, at `root`.
  auto new_trial = [&](int root) {
    CutResult trial;
    trial.root = root;
    trial.genus = genus;
    trial.surface.mesh = mesh;
    trial.surface.num_input_vertices = nv0;
    trial.surface.input_positions = positions;
    return trial;
  };
  // One construction at candidate (c, hops), into out if it succeeds within `bound` (and within
  // *rival: canonical_rounds, canonical_crosses).
  auto attempt = [&](int c, bool hops, bool crosses, long bound, Outcome& out,
                     const std::atomic<long>* rival = nullptr) {
    CutResult trial = new_trial(c);
    DetachPlan plan;
    const bool ok = crosses ? canonical_crosses(trial, unit, hops, bound, plan, rival)
                            : canonical_rounds(trial, unit, hops, bound, plan, nullptr, rival);
    if (ok) out.ok = true, out.crosses = crosses, out.hops = hops, out.stats = trial.stats, out.plan = std::move(plan);
    return ok;
  };
  // One candidate: the rounds, bounded by max_rounds_growth; where they pass it (their own bound
  // binding, not only the best so far; Best) the crosses, whose outcome (or error) then counts.
  // race (a lone candidate where the rounds tend to pass their bound: kRaceFacesPerHandle): both
  // run, side by side on two threads (CutOptions::parallel), the rounds followed by their
  // congestion reweighting (reweight), and the fewer planned vertices win, the rounds on ties
  // (their plan after the reweighting, which can only lower it: couplingdown at root 100 gets
  // 2,266 vertices from the reweighted rounds, 2,587 from the crosses, whose plan is below the
  // rounds' first). Each run is bounded by the other's best plan so far: the crosses by the
  // rounds' (from their first plan on), the rounds by the crosses' where no reweighting follows.
  // The rounds' count only grows, the crosses' grows from round to round, and a plan has at least
  // the vertices of its surface, so a run that passes the other's plan would lose anyway: the
  // outcome does not depend on the threads (an error of the rounds wins; one of the crosses
  // counts where the rounds failed; an Internal error that only a losing run would reach may go
  // unseen), and the time is about that of the longer of the two, or less where the winner stops
  // the other.
  // How many of the reweighting's best plans are drawn to choose the kept one, and whether they
  // are (see after the candidates below).
  constexpr std::size_t kNormalFormDrawn = 8;
  const bool draw_ranked = mesh.num_faces() <= 200000;
  const int reweight_rounds = mesh.num_faces() > 200000 && options.congestion_rounds < 0
                                   ? 0
                                   : congestion_budget(options, mesh, 1000000L, 0L, 250L);
  if (reweight_rounds > 0) check_congestion_step(options.congestion_step);
  // The congestion reweighting of a rounds plan at (root, hops) (step 3a with the penalties of
  // step 1c, accumulated from each round's plan), all rounds of the budget (their outcomes are
  // erratic); the plan with the fewest planned vertices is kept, with its stats. Not for the
  // crosses (a candidate costs seconds where they are needed). Each round is bounded by the
  // rounds' own limit only: a round past the kept plan still gives the next penalties. Each new
  // best's count goes to *publish (if given). Budget clamp(1e6 / F, 0, 250) rounds, none past
  // 2e5 faces: there a round costs as much as the construction (the 1M-face g20: 7.5 s). Against
  // clamp(2e5 / F, 0, 40): on generated genus 2-12 of 2k-40k faces (36 meshes) 20,340 vertices
  // added instead of 23,873 in 3.5x the time (43.6 s against 12.6 s; 2e6 / F and 500 rounds:
  // 19,457 in 81 s); the new bests keep coming late (couplingdown's at rounds 71, 121, 235, 284).
  // Besides the kept plan, the kNormalFormDrawn plans with the fewest planned vertices (the
  // first plan included; the earlier on ties) are collected in *ranked, `plan` first, for
  // the drawn choice after the candidates below.
  auto reweight = [&](int root, bool hops, DetachPlan& plan, CutStats& stats, std::atomic<long>* publish,
                      std::vector<Ranked>* ranked) {
    CutStats latest;  // the stats of the last round's construction
    long latest_count = 0;
    int round = 0;
    if (ranked) ranked->assign(1, Ranked{plan, stats, 0});
    const int kept_round = reweight_for_congestion(
        plan, nv0, options.congestion_step * metric_unit(mesh, unit, hops), reweight_rounds, reweight_rounds,
        [&](const std::vector<double>& penalty, DetachPlan& next) {
          CutResult trial = new_trial(root);
          const bool ok = canonical_rounds(trial, unit, hops, rounds_limit, next, &penalty);
          ++round;  // one replan per round
          latest = trial.stats;
          latest_count = ok ? planned_vertices(next) : 0;
          if (ok && ranked) {  // a stable insertion by planned count, at most kNormalFormDrawn kept
            std::size_t at = ranked->size();
            while (at > 0 && latest_count < planned_vertices((*ranked)[at - 1].plan)) --at;
            if (at < kNormalFormDrawn) {
              ranked->insert(ranked->begin() + static_cast<std::ptrdiff_t>(at), Ranked{next, latest, round});
              if (ranked->size() > kNormalFormDrawn) ranked->pop_back();
            }
          }
          return ok;
        },
        [&](int) {
          stats = latest;
          if (publish) *publish = latest_count;
        });
    stats.congestion_best_round = kept_round;
    stats.congestion_rounds = reweight_rounds;
  };
  bool raced = false;
  auto run_candidate = [&](int c, bool hops, bool crosses_only, long best, Outcome& out, bool race) {
    if (crosses_only) {
      attempt(c, hops, true, best, out);
      return;
    }
    const bool crosses_may_count = options.construction == C::Best && rounds_limit <= best;
    if (!race || !crosses_may_count) {
      if (attempt(c, hops, false, std::min(best, rounds_limit), out) || !crosses_may_count) return;
      attempt(c, hops, true, best, out);
      out.rounds_passed = true;
      return;
    }
    raced = true;
    Outcome crossed;
    std::atomic<long> rounds_planned{std::numeric_limits<long>::max()};
    std::atomic<long> crosses_planned{std::numeric_limits<long>::max()};
    std::exception_ptr crosses_error;
    auto rounds = [&] {
      try {
        if (attempt(c, hops, false, std::min(best, rounds_limit), out, reweight_rounds == 0 ? &crosses_planned : nullptr)) {
          rounds_planned = planned_vertices(out.plan);
          if (reweight_rounds > 0) {
            reweight(c, hops, out.plan, out.stats, &rounds_planned, draw_ranked ? &out.ranked : nullptr);
            out.reweighted = true;
          }
        }
      } catch (...) {
        rounds_planned = -1;  // the error wins: the crosses stop at their next round
        throw;
      }
    };
    auto crosses = [&] {
      try {
        if (attempt(c, hops, true, best, crossed, &rounds_planned)) crosses_planned = planned_vertices(crossed.plan);
      } catch (...) {
        crosses_error = std::current_exception();
      }
    };
    run_pair(options.parallel, rounds, crosses);
    if (out.ok && (!crossed.ok || planned_vertices(out.plan) <= planned_vertices(crossed.plan))) return;
    if (!out.ok && crosses_error) std::rethrow_exception(crosses_error);
    if (!crossed.ok) return;  // neither
    out = std::move(crossed);
    out.rounds_passed = true;
  };
  // The rounds pass max_rounds_growth on coarse meshes of high genus (cheese: 134 faces per
  // handle, a generated genus 200 on 30k faces: 150) and stay well within it on fine ones
  // (couplingdown: 413, the 1M-face genus 20: 49.5k): a lone candidate races the two below
  // kRaceFacesPerHandle. Not on fine meshes below kCrossesGenus: there the rounds plan about as
  // many vertices in half the time (the 1M-face genus 20: 546.8k in 4.3 s against 536.0k in
  // 8.1 s; genus 10 on 200k faces: 109.4k in 0.6 s against 111.1k in 1.0 s).
  // From kCrossesGenus on every candidate runs the crosses alone (Best): on every mesh of that
  // genus measured the crosses planned at most the rounds' vertices, where the rounds
  // succeeded at all (cheese; 50 generated meshes of genus 50-200 on 2k-1M faces, e.g. genus 50
  // on 500k faces 424k vertices for the rounds alone against 345k, genus 60 on 600k 843k
  // against 403k; 13 of genus 30-45, e.g. one root: genus 30 on 400k faces 303k against 230k,
  // genus 40 on 1M 735k against 576k; 4-6 roots: genus 35 on 40k faces 45.0k for Best against
  // 35.5k for the crosses alone, genus 30 on 36k 34.0k against 28.3k), and the rounds often
  // failed only after the crosses had finished (genus 200 on 400k faces: 31.7 s against
  // 12.3 s). With several candidates the first two no longer try the rounds before the crosses
  // (genus 50-133, 16 meshes with 1-24 candidates: the same cuts, 10-45 % faster).
  constexpr long kRaceFacesPerHandle = 2000;
  constexpr int kCrossesGenus = 30;
  const bool race = mesh.num_faces() < kRaceFacesPerHandle * static_cast<long>(genus);
  const bool crosses_by_genus = options.construction == C::Best && genus >= kCrossesGenus;
  bool found = false, kept_hops = false, kept_reweighted = false;
  int tried = 0, rounds_passed = 0;
  DetachPlan kept;
  std::vector<Ranked> kept_ranked;  // the kept plan's reweighting's best plans
  for (std::size_t i = 0; i < candidates.size(); i += 2) {  // chunks of two
    const std::size_t n = std::min<std::size_t>(2, candidates.size() - i);
    const long best = found ? planned_vertices(kept) - 1 : limit;
    const bool crosses_only = options.construction == C::Crosses || crosses_by_genus ||
                              (options.construction == C::Best && rounds_passed >= 2);
    Outcome out[2];
    auto run = [&](std::size_t j) {
      return [&, j] {
        run_candidate(candidates[i + j].first, candidates[i + j].second, crosses_only, best, out[j], false);
      };
    };
    if (n == 2) run_pair(options.parallel, run(0), run(1));
    else run_candidate(candidates[i].first, candidates[i].second, crosses_only, best, out[0], race);
    for (std::size_t j = 0; j < n; ++j) {
      ++tried;
      rounds_passed += out[j].rounds_passed;
      if (out[j].ok && (!found || planned_vertices(out[j].plan) < planned_vertices(kept))) {
        res.root = candidates[i + j].first;
        res.stats = out[j].stats;
        res.stats.crosses = out[j].crosses;
        kept = std::move(out[j].plan);
        kept_hops = out[j].hops;
        kept_reweighted = out[j].reweighted;
        kept_ranked = std::move(out[j].ranked);
        found = true;
      }
    }
  }
  // The kept rounds plan's congestion reweighting (in a race it came before the comparison).
  if (found && !res.stats.crosses && !kept_reweighted && reweight_rounds > 0)
    reweight(res.root, kept_hops, kept, res.stats, nullptr, draw_ranked ? &kept_ranked : nullptr);
  // On meshes of at most 2e5 faces the reweighting's best plans are drawn and tightened on
  // copies, and the fewest vertices win (the fewer planned on ties, then the earlier): the plan
  // does not see what the tightening will remove (couplingdown: the fewest planned, 2,257, end
  // with 2,137 vertices; the fifth fewest, 2,294, with 2,093). Tightened here even with
  // CutOptions::tighten off, so that the option does not change the loops chosen. The winner is
  // drawn again below. O(kNormalFormDrawn (n + crossings)).
  if (found && kept_ranked.size() > 1) {
    std::vector<const DetachPlan*> plans;
    for (const Ranked& r : kept_ranked) plans.push_back(&r.plan);
    const std::size_t win = fewest_drawn(plans, positions, options.parallel, nullptr);
    if (win > 0) {
      kept = std::move(kept_ranked[win].plan);
      res.stats = kept_ranked[win].stats;
      res.stats.congestion_rounds = reweight_rounds;
      res.stats.congestion_best_round = kept_ranked[win].round;
    }
  }
  kept_ranked.clear();
  res.stats.raced = raced;
  if (found) {
    res.stats.planned_vertices = planned_vertices(kept);
    res.loops = realize_strands(kept, res.stats, options.parallel);
    rs = std::move(kept.rs);
    found = rs.mesh.num_vertices() <= limit;  // chord splits and face vertices come on top of the plan
  }
  if (!found && options.construction == C::Rounds)
    throw Error(ErrorKind::Unsupported,
                "normal form: the rounds would grow the mesh past " + std::to_string(rounds_limit) +
                    " vertices (CutOptions::max_rounds_growth x " + std::to_string(nv0) +
                    " input vertices); use the crosses construction, or run without the normal form");
  if (!found)
    throw Error(ErrorKind::Unsupported,
                "normal form: the canonical loops would grow the mesh past " + std::to_string(limit) +
                    " vertices (CutOptions::max_normal_form_growth x " + std::to_string(nv0) +
                    " input vertices); run without the normal form");
  res.stats.genus = genus;
  res.stats.vertices_before = nv0;
  res.stats.faces_before = mesh.num_faces();
  res.stats.roots_tried = tried;
  res.stats.seconds_detach = seconds_since(t_start);
}

// Steps 1, 1c and 2 (without the normal form, or as step 3c's start with options.normal_form, which
// changes only the drawn comparison below): the root and metric (the given root, or among
// deterministic candidates ranked by their planned crossings), the congestion reweighting of the
// best ranked and the detaching of the kept plan: fills res.root, res.loops, res.surface and
// res.stats. Returns true if the loops are already tightened (the drawn comparison kept them).
bool greedy_system(const TriMesh& mesh, const std::vector<Vec3d>& positions, const std::vector<Vec3d>& unit,
                   const CutOptions& options, int genus, Clock::time_point t_start, CutResult& res) {
  const int nv0 = mesh.num_vertices();
  RefinedSurface& rs = res.surface;
  bool tightened = false;
  // Root and metric: the given root with 3D edge lengths, or among K deterministic root
  // candidates (root_candidates_by_ring_deficit, K = clamp(1e6 / F, 1, 24): the extra cost is
  // bounded by one basis computation on a 1M-face mesh), each with 3D lengths and with hop
  // counts as the basis metric, ranked by the crossings their detaching will make (predicted by plan_detach, without
  // building anything; the earlier wins ties). The best CutOptions::congestion_candidates of them
  // are reweighted (step 1c, two at a time on two threads) and the plan with the fewest planned
  // vertices is kept (the better ranked on ties), so the result does not depend on the threads.
  std::vector<DetachPlan> top;  // the best ranked plans, best first
  const int rounds = congestion_budget(options, mesh, 2000000L, 1L, 500L);
  const std::size_t keep = rounds > 0 ? static_cast<std::size_t>(options.congestion_candidates) : 1;
  if (options.root >= 0) {
    top.push_back(plan_detach(mesh, unit, options.root, genus, false));
  } else {
    const long k = std::clamp(1000000L / std::max(1, mesh.num_faces()), 1L, 24L);
    for (int c : root_candidates_by_ring_deficit(mesh, k, genus)) {
      DetachPlan q[2];  // 3D lengths, hop counts: planned side by side, ranked in that order
      run_pair(options.parallel, [&] { q[0] = plan_detach(mesh, unit, c, genus, false); },
               [&] { q[1] = plan_detach(mesh, unit, c, genus, true); });
      for (DetachPlan& p : q) {
        ++res.stats.roots_tried;
        // Insert after every kept plan with at most as many crossings (stable), drop the last.
        std::size_t at = top.size();
        while (at > 0 && p.crossings < top[at - 1].crossings) --at;
        if (at < keep) {
          top.insert(top.begin() + static_cast<std::ptrdiff_t>(at), std::move(p));
          if (top.size() > keep) top.pop_back();
        }
      }
    }
  }
  // Congestion reweighting at each kept root and metric (reweight_for_congestion).
  DetachPlan P;
  std::optional<TightenedLoops> drawn_win;  // the drawn comparison's winner, drawn and tightened
  CutStats drawn_stats;                     // its drawing's counts
  if (rounds > 0) {
    check_congestion_step(options.congestion_step);
    std::vector<int> best_round(top.size(), 0);
    for (std::size_t i = 0; i < top.size(); i += 2) {
      auto one = [&](std::size_t j) {
        return [&, j] {
          if (j >= top.size()) return;
          const bool hops = top[j].hops;
          const int root = top[j].root;
          best_round[j] = reweight_for_congestion(
              top[j], nv0, options.congestion_step * metric_unit(mesh, unit, hops), rounds, kCongestionPatience,
              [&](const std::vector<double>& penalty, DetachPlan& plan) {
                plan = plan_detach(mesh, unit, root, genus, hops, &penalty);
                return true;
              },
              [](int) {});
        };
      };
      run_pair(options.parallel && i + 1 < top.size(), one(i), one(i + 1));
    }
    std::size_t win = 0;
    for (std::size_t j = 1; j < top.size(); ++j)
      if (planned_vertices(top[j]) < planned_vertices(top[win])) win = j;
    // On meshes of at most 2e5 faces the reweighted candidates are drawn and tightened on copies,
    // and the fewest vertices win instead (the better ranked on ties): the plan does not see
    // what the tightening will remove. For the normal form's step 3c (and step 3 at its root) only
    // the candidates of least ring deficit are drawn: the slides' arcs and step 3's loops crowd the
    // root more than the greedy loops do (couplingdown: roots of deficit 41-42 end with 99-172
    // added over 8 id orders, mean 118, roots of deficit 48-49 with 108-195, mean 148; over 32
    // orders 92-155, mean 119, instead of 99-198, mean 132; the 36 generated genus 2-12 meshes
    // 4,876 instead of 4,977). Tightened here even with CutOptions::tighten off, so that
    // the option does not change the loops chosen; with it on, the winner's copy is the result
    // (not drawn a second time). O(C (n + crossings)).
    if (top.size() > 1 && mesh.num_faces() <= 200000) {
      std::vector<const DetachPlan*> plans;
      std::vector<std::size_t> idx;  // the plans compared
      std::vector<long> deficit(top.size(), 0);
      if (options.normal_form) {
        HopRings rings(mesh);
        for (std::size_t j = 0; j < top.size(); ++j) deficit[j] = ring_deficit(rings, top[j].root, genus);
      }
      const long least = *std::min_element(deficit.begin(), deficit.end());
      for (std::size_t j = 0; j < top.size(); ++j)
        if (deficit[j] == least) idx.push_back(j);
      for (std::size_t j : idx) plans.push_back(&top[j]);
      DrawnPlan drawn;
      win = idx[fewest_drawn(plans, positions, options.parallel, options.tighten ? &drawn : nullptr)];
      if (options.tighten) drawn_win = std::move(drawn.tightened), drawn_stats = drawn.drawing;
    }
    P = std::move(top[win]);
    res.stats.congestion_rounds = rounds;
    res.stats.congestion_best_round = best_round[win];
    res.stats.congestion_candidates = static_cast<int>(top.size());
  } else {
    P = std::move(top[0]);
  }
  res.root = P.root;
  res.stats.band_splits = P.band_splits;
  res.stats.predicted_crossings = P.crossings;
  res.stats.planned_vertices = planned_vertices(P);
  res.stats.seconds_basis = seconds_since(t_start);
  const auto t_detach = Clock::now();
  if (drawn_win) {
    res.stats.crossings = drawn_stats.crossings;
    res.stats.steiner_vertices = drawn_stats.steiner_vertices;
    res.stats.chord_splits = drawn_stats.chord_splits;
    res.stats.collapsed = drawn_win->stats.collapsed;
    rs = std::move(drawn_win->surface);
    res.loops = std::move(drawn_win->loops);
    tightened = true;
  } else {
    P.rs.input_positions = positions;
    res.loops = realize_strands(P, res.stats, options.parallel);
    rs = std::move(P.rs);
  }
  res.stats.seconds_detach = seconds_since(t_detach);
  return tightened;
}

// Whether and how step 3c runs (CutOptions::slides): with the normal form, Best and the tightening
// on; for -1 beside step 3 where F g^2 <= B and F g^3 <= 16 B (B = CutOptions::slides_budget), and
// after it, if its growth calls for it (grew_past_target), where both are at most 4x that.
// About 5 g^2 slides are drawn (4 per linked pair per step), each on a copy of the surface: O(F)
// each, about 1 microsecond x F g^2 in all on the bench machine (generated genus 10 on 100k faces,
// seed 1: 8.2 s instead of 1.6 s, for 0.35 % growth instead of 8.6 %); with many loops a drawing's
// word checks and tightening grow with g as well (genus 20 on 5k faces: 1,758 slides in 6.9 s).
// Past the budget, at its 4x bounds, up to about 50 s (genus 20 on 80k faces, F g^3 = 6.4e8).
enum class SlidesRun { No, Beside, IfGrown };
SlidesRun slides_run(const TriMesh& mesh, const CutOptions& options, int genus) {
  if (!options.normal_form || options.construction != CutOptions::Construction::Best || !options.tighten ||
      options.slides == 0)
    return SlidesRun::No;
  if (options.slides == 1) return SlidesRun::Beside;
  const double f = mesh.num_faces(), g = genus, b = options.slides_budget;
  if (f * g * g <= b && f * g * g * g <= 16 * b) return SlidesRun::Beside;
  if (f * g * g <= 4 * b && f * g * g * g <= 64 * b) return SlidesRun::IfGrown;
  return SlidesRun::No;
}

// Whether a cut added more than 2 % of the input's vertices: the growth the normal form should
// stay under on g <= 10. Past its budget step 3c runs after step 3 only then (the rounds pass it
// on finer meshes than the budget covers: generated genus 10: 8.6 %, 7.4 %, 6.3 % on 100k, 200k,
// 400k faces; genus 8: 2.0 % and 2.4 % on 200k and 400k; bench/README.md, step 3c), and so do
// the restarts (CutOptions::restarts).
bool grew_past_target(int vertices_before, int vertices_now) {
  return 100LL * (vertices_now - vertices_before) > 2LL * vertices_before;
}

// Step 3c: the greedy system of steps 1-2b (same options), tightened (greedy_start), brought into
// blocks by canonical_slides (to_blocks). O(steps 1-2b + g (4g)^2 (n + tightening)).
struct Slid {
  SlideState state;
  int root = -1;
  CutStats stats;  // steps 1-2b's
  int slides = 0;
  long long trials = 0;
  bool ok = false;
};
Slid greedy_start(const TriMesh& mesh, const std::vector<Vec3d>& positions, const std::vector<Vec3d>& unit,
                   const CutOptions& options, int genus) {
  const auto t_slides = Clock::now();
  CutResult g;
  g.genus = genus;
  if (!greedy_system(mesh, positions, unit, options, genus, t_slides, g)) {
    TightenedLoops t = tighten_loops(std::move(g.surface), std::move(g.loops), g.root);
    g.surface = std::move(t.surface);
    g.loops = std::move(t.loops);
    g.stats.collapsed = t.stats.collapsed;
  }
  Slid out;
  out.state = SlideState{std::move(g.surface), std::move(g.loops), {}};
  out.state.word = root_word(out.state.rs.mesh, g.root, out.state.loops);
  out.root = g.root;
  out.stats = g.stats;
  return out;
}
// Pre: `out` from greedy_start.
void to_blocks(Slid& out, bool parallel) {
  out.ok = canonical_slides(out.state, out.root, parallel, &out.slides, &out.trials);
}
Slid slides_system(const TriMesh& mesh, const std::vector<Vec3d>& positions, const std::vector<Vec3d>& unit,
                   const CutOptions& options, int genus) {
  Slid out = greedy_start(mesh, positions, unit, options, genus);
  to_blocks(out, options.parallel);
  return out;
}

// Step 3d on the rounds' or crosses' system (tightened): its loops redrawn between their own
// corners or inside their handles (redraw_loops, kRedrawPasses). Returns the redraws kept.
int redraw_system(CutResult& res, bool parallel) {
  SlideState st{std::move(res.surface), std::move(res.loops), {}};
  st.word = root_word(st.rs.mesh, res.root, st.loops);
  const int kept = redraw_loops(st, res.root, kRedrawPasses, parallel);
  res.surface = std::move(st.rs);
  res.loops = std::move(st.loops);
  res.stats.slide_splits += st.splits;
  res.stats.collapsed += st.collapsed;
  return kept;
}

// Keeps step 3c's system instead of res's (tightened) if it has fewer vertices; res's stats get
// what step 3c did either way.
void keep_fewer(Slid& slid, CutResult& res) {
  if (slid.ok && slid.state.rs.mesh.num_vertices() < res.surface.mesh.num_vertices()) {
    const CutStats rounds = res.stats;
    res.surface = std::move(slid.state.rs);
    res.loops = std::move(slid.state.loops);
    res.root = slid.root;
    res.stats = slid.stats;  // the counts of steps 1-2b; the sizes and times stay the whole run's
    res.stats.genus = rounds.genus;
    res.stats.vertices_before = rounds.vertices_before;
    res.stats.faces_before = rounds.faces_before;
    res.stats.seconds_basis = rounds.seconds_basis;
    res.stats.seconds_detach = rounds.seconds_detach;
    res.stats.slides = slid.slides;
    res.stats.slide_splits = slid.state.splits;
    res.stats.redrawn = slid.state.redrawn;
    res.stats.collapsed += slid.state.collapsed;
  }
  res.stats.slide_trials = slid.trials;
  res.stats.slides_failed = !slid.ok;
}

// Steps 1-5 on the mesh as numbered (cut_to_canonical_disk below may renumber it first). Pre: the
// input and the options checked there, `genus` >= 1 the mesh's.
CutResult cut_in_given_order(const TriMesh& mesh, const std::vector<Vec3d>& positions, const CutOptions& options,
                             int genus) {
  const auto t_start = Clock::now();
  const int nv0 = mesh.num_vertices();
  CutResult res;
  const std::vector<Vec3d> unit = unit_scaled(positions);  // edge lengths finite at any magnitude
  res.genus = genus;
  res.stats.genus = genus;
  res.stats.vertices_before = nv0;
  res.stats.faces_before = mesh.num_faces();
  RefinedSurface& rs = res.surface;
  bool tightened = false;  // the loops were drawn and tightened while the root was chosen
  auto tighten = [&] {
    if (!options.tighten || tightened) return;
    const auto t_tighten = Clock::now();
    TightenedLoops t = tighten_loops(std::move(rs), std::move(res.loops), res.root);
    rs = std::move(t.surface);
    res.loops = std::move(t.loops);
    res.stats.collapsed = t.stats.collapsed;
    res.stats.seconds_detach += seconds_since(t_tighten);
  };
  if (options.normal_form) {
    // Step 3 and, where it runs, step 3c side by side (two threads with CutOptions::parallel; each
    // may use two more), then the fewer vertices: the same result either way. An error of step 3
    // is rethrown first (run_pair). Beside and with root = -1, steps 1-2b come first, and step 3
    // runs at their root with both metrics (normal_form_system's slides_root) beside the slides:
    // on generated genus 2-12 (2k-40k faces, 2 seeds, 36 meshes) 4,977 vertices added instead of
    // 5,664 with step 3's own root candidates, 86.7 s against 85.4 s; couplingdown as given 90
    // instead of 129, over 16 orders of its ids 99-195 (mean 133) instead of 101-216 (mean 151);
    // with the greedy root of least ring deficit (greedy_system) 4,876, and couplingdown 86-155
    // (mean 119) over 32 orders. Both roots' systems, the better kept: 4,902 without that
    // (4,994 with 3D lengths only, in 136 s).
    const SlidesRun run = slides_run(mesh, options, genus);
    const bool beside = run == SlidesRun::Beside;
    Slid slid;
    auto redraw = [&] { res.stats.redrawn = redraw_system(res, options.parallel); };  // step 3d
    auto slide = [&] { slid = slides_system(mesh, positions, unit, options, genus); };  // step 3c
    auto construct = [&](int slides_root) {  // step 3 (at step 3c's root if >= 0), tightened, 3d
      normal_form_system(mesh, positions, unit, options, genus, t_start, res, slides_root);
      tighten();
      if (beside) redraw();
    };
    if (beside && options.root < 0) {
      slid = greedy_start(mesh, positions, unit, options, genus);
      run_pair(options.parallel, [&] { construct(slid.root); }, [&] { to_blocks(slid, options.parallel); });
    } else {
      run_pair(options.parallel && beside, [&] { construct(-1); }, [&] { if (beside) slide(); });
    }
    // Past the budget: steps 3d and 3c as beside, after step 3 and only for its growth.
    const bool after = run == SlidesRun::IfGrown && grew_past_target(nv0, rs.mesh.num_vertices());
    if (after) run_pair(options.parallel, redraw, slide);
    if (beside || after) {
      keep_fewer(slid, res);
      res.stats.slides_after = after;
      res.stats.seconds_detach = seconds_since(t_start);  // both steps
    }
  } else {
    tightened = greedy_system(mesh, positions, unit, options, genus, t_start, res);
    tighten();
  }
  const auto t_cut = Clock::now();

  // ---- 4. the cut (with the normal form: loops renumbered so that the word is L0 L1 L0^-1 ...) ----
  build_cut(res, -1);
  if (options.normal_form) relabel_blocks(res, word_of(res));
  res.stats.precondition_splits += precondition_pass(res);
  build_cut(res, find_he(rs.mesh, res.root, res.loops[0][1]));
  if (options.normal_form && !is_canonical_word(word_of(res)))
    internal("cut word is not canonical: " + to_string(word_of(res)));
  res.stats.seconds_cut = seconds_since(t_cut);
  res.stats.vertices_after = rs.mesh.num_vertices();
  res.stats.faces_after = rs.mesh.num_faces();
  res.stats.seconds_total = seconds_since(t_start);
  return res;
}

// Step 0: the locality order. Vertices renumbered breadth-first from vertex 0 (a vertex's
// unnumbered neighbours in its rotation order from its vertex half-edge; a vertex no search reached
// starts a new one), faces in the order in which the vertices, in the new order, first meet them
// (around each in rotation order), every face's corners in their given rotation. O(V + F).
struct VertexOrder {            // a renumbering: step 0's, or a restart's shuffle
  std::vector<int> old_of_new;  // vertex
  TriMesh mesh;                 // the renumbered mesh
};
VertexOrder locality_order(const TriMesh& mesh) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  VertexOrder out;
  std::vector<int> new_of_old(nv, -1), new_face(nf, -1);
  out.old_of_new.reserve(nv);
  int placed = 0;
  for (int s = 0; s < nv; ++s) {
    if (new_of_old[s] >= 0) continue;
    new_of_old[s] = static_cast<int>(out.old_of_new.size());
    out.old_of_new.push_back(s);
    // The queue is old_of_new itself: vertices are taken in their new order, so the faces are met
    // in the order stated above, in the same walk around each.
    for (std::size_t i = static_cast<std::size_t>(new_of_old[s]); i < out.old_of_new.size(); ++i) {  // each vertex once
      const int v = out.old_of_new[i];
      const int h0 = mesh.vertex_halfedge(v);
      int h = h0;
      do {  // valence(v) steps
        const int w = mesh.target(h);
        if (new_of_old[w] < 0) new_of_old[w] = static_cast<int>(out.old_of_new.size()), out.old_of_new.push_back(w);
        if (new_face[TriMesh::face(h)] < 0) new_face[TriMesh::face(h)] = placed++;
        h = mesh.next_around_origin(h);
      } while (h != h0);
    }
  }
  std::vector<int> origin(3 * static_cast<std::size_t>(nf)), twin(3 * static_cast<std::size_t>(nf));
  for (int h = 0; h < 3 * nf; ++h) {
    const int g = 3 * new_face[TriMesh::face(h)] + h % 3, t = mesh.twin(h);
    origin[g] = new_of_old[mesh.origin(h)];
    twin[g] = 3 * new_face[TriMesh::face(t)] + t % 3;
  }
  out.mesh = TriMesh::from_halfedges(nv, std::move(origin), std::move(twin));
  return out;
}

// A result on the renumbered mesh in the caller's numbering: input vertices get their ids back
// (constructed ones keep theirs, and their points' slots are sorted again), faces and disk
// vertices stay as they are. O(V + F).
void restore_order(CutResult& res, const std::vector<int>& old_of_new, const std::vector<Vec3d>& positions) {
  RefinedSurface& rs = res.surface;
  const int nin = rs.num_input_vertices;
  auto old_id = [&](int v) { return v < nin ? old_of_new[v] : v; };
  std::vector<int> origin = rs.mesh.origins();
  for (int& v : origin) v = old_id(v);
  std::vector<int> twin = rs.mesh.twins();
  rs.mesh = TriMesh::from_halfedges(rs.mesh.num_vertices(), std::move(origin), std::move(twin));
  for (SurfacePoint& p : rs.constructed) {
    for (int i = 0; i < 3 && p.v[i] >= 0; ++i) p.v[i] = old_of_new[p.v[i]];
    for (int i = 1; i < 3 && p.v[i] >= 0; ++i)  // insertion sort of the used slots
      for (int j = i; j > 0 && p.v[j - 1] > p.v[j]; --j) {
        std::swap(p.v[j - 1], p.v[j]);
        mpq_swap(p.w[j - 1].get_mpq_t(), p.w[j].get_mpq_t());
      }
  }
  rs.input_positions = positions;
  res.root = old_id(res.root);
  for (auto& loop : res.loops)
    for (int& v : loop) v = old_id(v);
  for (int& v : res.disk_to_surface) v = old_id(v);
}

// Steps 1-5 on `mesh` renumbered by `order` (order.mesh), in the caller's ids; `locality` marks
// the result as step 0's. O(V + F) besides the cut.
CutResult cut_in_order(const VertexOrder& order, const TriMesh& mesh, const std::vector<Vec3d>& positions,
                       const CutOptions& options, int genus, bool locality) {
  const int nv = mesh.num_vertices();
  std::vector<Vec3d> renumbered(nv);
  for (int v = 0; v < nv; ++v) renumbered[v] = positions[order.old_of_new[v]];
  CutOptions o = options;
  if (o.root >= 0) o.root = static_cast<int>(std::find(order.old_of_new.begin(), order.old_of_new.end(), o.root) - order.old_of_new.begin());
  CutResult res = cut_in_given_order(order.mesh, renumbered, o, genus);
  restore_order(res, order.old_of_new, positions);
  res.stats.locality_ordered = locality;
  return res;
}

// How many restarts the cut takes (CutOptions::restarts; -1: clamp(5e6 / (F g^2), 0, 15), each
// about as costly as the first run, whose step 3c costs about F g^2).
int restart_count(const TriMesh& mesh, const CutOptions& options, int genus) {
  if (options.restarts >= 0) return options.restarts;
  const double fg2 = static_cast<double>(mesh.num_faces()) * genus * genus;
  return static_cast<int>(std::clamp(std::floor(5e6 / fg2), 0.0, 15.0));
}

// Vertex ids shuffled by seed `seed` (Fisher-Yates driven by splitmix64, so the same on every
// platform): old_of_new and the mesh renumbered by it (faces and half-edges keep their ids). O(V + F).
VertexOrder shuffled_order(const TriMesh& mesh, std::uint64_t seed) {
  const int nv = mesh.num_vertices();
  VertexOrder out;
  out.old_of_new.resize(nv);
  std::iota(out.old_of_new.begin(), out.old_of_new.end(), 0);
  std::uint64_t state = seed;
  auto next = [&state] {  // splitmix64
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  for (int i = nv - 1; i > 0; --i) {  // nv - 1 swaps; the modulo's bias is irrelevant here
    const int j = static_cast<int>(next() % static_cast<std::uint64_t>(i + 1));
    std::swap(out.old_of_new[i], out.old_of_new[j]);
  }
  std::vector<int> new_of_old(nv);
  for (int v = 0; v < nv; ++v) new_of_old[out.old_of_new[v]] = v;
  std::vector<int> origin = mesh.origins();
  for (int& v : origin) v = new_of_old[v];
  out.mesh = TriMesh::from_halfedges(nv, std::move(origin), mesh.twins());
  return out;
}

// Steps 0-5 on the mesh as given (step 0 renumbers it for locality from
// CutOptions::locality_order_min_vertices vertices on), in the caller's ids.
CutResult cut_once(const TriMesh& mesh, const std::vector<Vec3d>& positions, const CutOptions& options, int genus) {
  const int nv = mesh.num_vertices();
  if (options.locality_order_min_vertices < 0 || nv < options.locality_order_min_vertices)
    return cut_in_given_order(mesh, positions, options, genus);
  const VertexOrder order = locality_order(mesh);
  return cut_in_order(order, mesh, positions, options, genus, true);
}

}  // namespace

CutResult cut_to_canonical_disk(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                const CutOptions& options) {
  const auto t_start = Clock::now();
  const int nv = mesh.num_vertices();
  // The input and the options, checked once, before step 0: errors name the caller's ids.
  if (static_cast<int>(positions.size()) != nv)
    throw Error(ErrorKind::InvalidArgument, "positions (" + std::to_string(positions.size()) +
                                                ") do not match the mesh vertices (" + std::to_string(nv) + ")");
  if (nv == 0) throw Error(ErrorKind::Empty, "mesh has no vertices");
  for (int v = 0; v < nv; ++v)
    if (mesh.vertex_halfedge(v) < 0)
      throw Error(ErrorKind::InvalidArgument, "vertex " + std::to_string(v) + " is used by no face", {v});
  const int chi = mesh.num_vertices() - mesh.num_edges() + mesh.num_faces();
  if (chi > 2 || chi % 2 != 0) throw Error(ErrorKind::InvalidArgument, "Euler characteristic " + std::to_string(chi));
  const int genus = (2 - chi) / 2;
  if (genus == 0) throw Error(ErrorKind::Unsupported, "genus 0 surface: the topology stage needs genus >= 1");
  if (options.root < -1 || options.root >= nv)
    throw Error(ErrorKind::InvalidArgument, "root vertex " + std::to_string(options.root) + " out of range [0, " +
                                                std::to_string(nv) + ")", {options.root});
  if (options.congestion_candidates < 1)
    throw Error(ErrorKind::InvalidArgument, "CutOptions::congestion_candidates must be >= 1, got " +
                                                std::to_string(options.congestion_candidates));
  if (options.normal_form_roots == 0 || options.normal_form_roots < -1)
    throw Error(ErrorKind::InvalidArgument, "CutOptions::normal_form_roots must be >= 1 or -1 (automatic), got " +
                                                std::to_string(options.normal_form_roots));
  if (options.congestion_rounds < -1)
    throw Error(ErrorKind::InvalidArgument,
                "CutOptions::congestion_rounds must be >= -1 (-1: automatic), got " + std::to_string(options.congestion_rounds));
  if (options.slides < -1 || options.slides > 1)
    throw Error(ErrorKind::InvalidArgument,
                "CutOptions::slides must be -1 (automatic), 0 or 1, got " + std::to_string(options.slides));
  if (!(std::isfinite(options.slides_budget) && options.slides_budget >= 0)) {
    std::ostringstream got;
    got << options.slides_budget;
    throw Error(ErrorKind::InvalidArgument, "CutOptions::slides_budget must be finite and >= 0, got " + got.str());
  }
  if (options.locality_order_min_vertices < -1)
    throw Error(ErrorKind::InvalidArgument, "CutOptions::locality_order_min_vertices must be >= -1 (-1: never), got " +
                                                std::to_string(options.locality_order_min_vertices));
  if (options.restarts < -1)
    throw Error(ErrorKind::InvalidArgument,
                "CutOptions::restarts must be >= -1 (-1: automatic), got " + std::to_string(options.restarts));
  CutResult res = cut_once(mesh, positions, options, genus);
  // Restarts (CutOptions::restarts): the whole cut again on shuffled ids, the fewest vertices kept
  // (the earliest on ties). At most restart_count(...) more runs.
  const int restarts = options.normal_form ? restart_count(mesh, options, genus) : 0;
  if (restarts > 0 && grew_past_target(nv, res.surface.mesh.num_vertices())) {
    int kept = 0, failed = 0;
    for (int i = 1; i <= restarts; ++i) {
      try {
        CutResult r = cut_in_order(shuffled_order(mesh, static_cast<std::uint64_t>(i)), mesh, positions, options, genus,
                                   false);
        if (r.surface.mesh.num_vertices() < res.surface.mesh.num_vertices()) res = std::move(r), kept = i;
      } catch (const Error& e) {
        if (e.kind() != ErrorKind::Unsupported) throw;
        ++failed;  // this shuffle's construction passed the growth bounds: not a candidate
      }
    }
    res.stats.restarts = restarts;
    res.stats.restart_kept = kept;
    res.stats.restarts_failed = failed;
  }
  res.stats.seconds_total = seconds_since(t_start);
  return res;
}

}  // namespace igm
