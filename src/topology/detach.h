#pragma once
// Internal to the topology stage (igm/topology/cut_to_canonical_disk.h): steps 1 (greedy homotopy
// basis by tree-cotree, planned), 1c (congestion reweighting) and 2 (detaching the loops as
// disjoint strands along the tree). Not installed, not part of the API.
#include <algorithm>
#include <vector>

#include "igm/mesh/surface_point.h"
#include "igm/topology/tighten_loops.h"
#include "topology_internal.h"

namespace igm::topology_internal {

// A planned detaching (steps 1-2 up to the owners; drawn by realize_strands): the surface with the
// band splits, the tree (parent, pruned to the band ends' paths), its tour's leaves and the owners.
// `crossings` is the number of edge crossings the strands will make (the dynamic programme's
// optimum, chord splits not counted).
struct DetachPlan {
  RefinedSurface rs;
  int root = -1;
  int root_start = -1;  // the tour starts at the root's edge to this vertex (-1: its stored half-edge)
  std::vector<int> parent, leaf_a, leaf_b, leaves, leaf_index, min_leaf, max_leaf, owner;
  std::vector<char> pruned, is_leaf;
  long long crossings = 0;
  int band_splits = 0;
  bool hops = false;  // the metric of the basis
};

// The vertex count a plan's realization will have: one new vertex per crossing (chord splits and
// face vertices, usually none, come on top).
inline long planned_vertices(const DetachPlan& P) { return P.rs.mesh.num_vertices() + P.crossings; }

// Step 1 and the plan of step 2: the greedy homotopy basis at `root` by tree-cotree (Erickson &
// Whittlesey 2005; metric: 3D edge lengths, or hop counts if `hops`, plus (penalty[a] +
// penalty[b]) / 2 per edge ab if `penalty` is given, one value per input vertex), planned for
// detaching by plan_strands. Pre: mesh valid, connected, of genus `genus` >= 1; positions finite
// (unit-scaled). Internal if the cotree does not leave 2g bands. Cost O(n log n).
DetachPlan plan_detach(const TriMesh& mesh, const std::vector<Vec3d>& positions, int root, int genus, bool hops,
                       const std::vector<double>* penalty = nullptr);

// Step 2 planned for the loops root~u, uv, v~root of `bands` on the tree P.parent (rooted at P.root;
// every band end reaches the root through it): the band splits (done on P.rs), the pruned tree, the
// tour (counter-clockwise from the root's edge to P.root_start), the owners and the word. Pre:
// P.rs, P.root, P.parent (size V) set; the tree edges at the root lie in one wedge that the tour
// start does not cut. Cost O(n + total strand length).
void plan_strands(DetachPlan& P, const std::vector<std::pair<int, int>>& bands);

// Congestion penalties (negotiated congestion, after the PathFinder router of McMurchie & Ebeling
// 1995). Strands that share a tree path are drawn side by side (step 2), and past the free vertices
// beside the path each further strand costs a crossing vertex per edge it passes. So after a plan
// every tree vertex x of the input (x < nv0, not the root) that k > 1 strands pass has its penalty
// raised by raise * (k - 1); a basis recomputed with the metric plus the penalties (per edge ab,
// (penalty[a] + penalty[b]) / 2) routes its paths around the crowded vertices, and its cotree,
// weighted by the same loop lengths, picks other bands. O(nv0).
void raise_penalties(const DetachPlan& p, int nv0, double raise, std::vector<double>& penalty);

// The unit of a metric on `unit` positions: the mean edge length (0 only if every edge has length
// 0; the penalties then do nothing), or one hop. O(E).
double metric_unit(const TriMesh& mesh, const std::vector<Vec3d>& unit, bool hops);

// Throws InvalidArgument unless CutOptions::congestion_step is finite and > 0.
void check_congestion_step(double step);

// The congestion reweighting of the basis (not of the normal form's rounds, whose outcomes jump
// from round to round: there it would lose, e.g. couplingdown 2141 -> 2167 vertices) stops once
// max(this, the best round's index) rounds have passed without a new best plan. Its descent is
// slow and steady (couplingdown's best plans come at rounds 38, 49, 95, ..., 255, 444), so a fixed
// patience would stop it early; a mesh where it stalls (cheese: round 2) stops after 12 rounds.
inline constexpr int kCongestionPatience = 10;

// The round budget of the congestion reweighting: CutOptions::congestion_rounds, or for -1
// clamp(per_faces / F, least, most) (a round costs about one basis, O(F log F)).
int congestion_budget(const CutOptions& options, const TriMesh& mesh, long per_faces, long least, long most);

// Step 1c: up to `rounds` rounds (stopping once max(patience, r_best) rounds have passed since
// the round r_best of the last new best) of congestion
// reweighting from the plan `best`, the penalties (raise_penalties, `raise` per extra strand)
// accumulating over the rounds, each from the last plan made. replan(penalty, plan) makes a plan
// with the penalties, or returns false (that round gives none). `best` becomes the plan with the
// fewest planned vertices (the earliest on ties), so never more than it had; kept(r) is called
// when round r's plan becomes the best, before it moves into `best`. Returns the index of the
// round kept (0: none). Deterministic. Cost: `rounds` replans and O(rounds nv0).
template <class Replan, class Kept>
int reweight_for_congestion(DetachPlan& best, int nv0, double raise, int rounds, int patience, Replan&& replan,
                            Kept&& kept) {
  std::vector<double> penalty(nv0, 0.0);
  DetachPlan current;
  const DetachPlan* last = &best;
  long best_count = planned_vertices(best);
  int best_round = 0;
  for (int r = 1; r <= rounds && r - best_round <= std::max(patience, best_round); ++r) {
    raise_penalties(*last, nv0, raise, penalty);
    DetachPlan next;
    if (!replan(penalty, next)) continue;
    const long count = planned_vertices(next);
    if (count < best_count) {
      best_count = count;
      best_round = r;
      kept(r);
      best = std::move(next);
      last = &best;
    } else {
      current = std::move(next);
      last = &current;
    }
  }
  return best_round;
}

// Step 2 realized: draws the strands planned in P as pairwise disjoint normal curves around the
// pruned tree and re-triangulates the faces they cross (on P.rs; vertex ids are kept, new ones are
// appended). Returns the loops, one per band in band order, each from the root. Adds to
// stats.crossings, steiner_vertices and chord_splits. Cost O(n + total crossings).
std::vector<std::vector<int>> realize_strands(DetachPlan& P, CutStats& stats, bool parallel);

// A plan drawn and tightened on a copy (fewest_drawn): the loops and the drawing's counts.
struct DrawnPlan {
  TightenedLoops tightened;
  CutStats drawing;  // crossings, steiner_vertices, chord_splits of realize_strands
};

// Draws each of `plans` on a copy whose input positions are `positions` (realize_strands, then
// tighten_loops; the plans are not changed) and returns the index of the one with the fewest
// vertices once drawn and tightened, the earliest on ties. The plans do not see what the
// tightening will remove, so this can beat the fewest planned. With `winner`, the winner's
// drawing is left there. Pre: plans non-empty, all of one input mesh. O(sum over the plans of
// n + crossings).
std::size_t fewest_drawn(const std::vector<const DetachPlan*>& plans, const std::vector<Vec3d>& positions,
                         bool parallel, DrawnPlan* winner);

}  // namespace igm::topology_internal
