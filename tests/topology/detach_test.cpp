// Tests of steps 1, 1c and 2 of the topology stage (src/topology/detach.cpp, internal): the
// planned detaching against its drawing, and the congestion reweighting's choice of plan.
#include <doctest/doctest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "../../src/topology/detach.h"
#include "generated_mesh.h"

using namespace igm;
using namespace igm::topology_internal;

namespace {

// A plan that only carries a vertex count (an empty surface plus `crossings`).
DetachPlan plan_of(long long crossings) {
  DetachPlan p;
  p.crossings = crossings;
  return p;
}

}  // namespace

TEST_CASE("the congestion reweighting keeps the first plan with the fewest vertices and stops when its patience runs out") {
  // Planned counts of the first plan (round 0) and of the replans of rounds 1, 2, ...
  const std::vector<long long> counts = {50, 60, 40, 45, 40, 39, 70, 80, 90, 91, 92, 20, 25};
  auto run = [&](int rounds, int patience, std::vector<int>& kept_rounds, int& replans) {
    DetachPlan best = plan_of(counts[0]);
    replans = 0;
    const int r = reweight_for_congestion(
        best, 0, 1.0, rounds, patience,
        [&](const std::vector<double>&, DetachPlan& next) {
          ++replans;
          if (counts[replans] == 45) return false;  // a round that gives no plan
          next = plan_of(counts[replans]);
          return true;
        },
        [&](int round) { kept_rounds.push_back(round); });
    CHECK(planned_vertices(best) == counts[r]);
    return r;
  };
  std::vector<int> kept;
  int replans = 0;
  // Round 2 (40) beats 50, round 4 only ties it, round 5 (39) wins. The patience is then
  // max(3, 5) = 5 rounds, not 3: rounds 6 to 10 run (a fixed patience of 3 would stop after
  // round 8), and round 11's 20 is not reached (a run without patience would keep it).
  CHECK(run(12, 3, kept, replans) == 5);
  CHECK(kept == std::vector<int>{2, 5});
  CHECK(replans == 10);
  // With patience 7, round 11 is reached and kept; round 12 runs (its patience is now 11) but
  // does not beat it.
  kept.clear();
  CHECK(run(12, 7, kept, replans) == 11);
  CHECK(kept == std::vector<int>{2, 5, 11});
  CHECK(replans == 12);
  // Before any new best the patience is the given one: patience 1 stops after round 1.
  kept.clear();
  CHECK(run(12, 1, kept, replans) == 0);
  CHECK(kept.empty());
  CHECK(replans == 1);
  // No rounds: the first plan stays.
  kept.clear();
  CHECK(run(0, 9, kept, replans) == 0);
  CHECK(kept.empty());
  CHECK(replans == 0);
}

TEST_CASE("a planned detaching predicts the crossings its drawing makes, and the loops meet only at the root") {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const ValidMesh in = igm_test::generated_mesh(3, 3000, seed);
    const int genus = 3, root = static_cast<int>(seed) * 97 % in.mesh.num_vertices();
    for (bool hops : {false, true}) {
      DetachPlan plan = plan_detach(in.mesh, in.positions, root, genus, hops);
      const long long predicted = plan.crossings;
      const long planned = planned_vertices(plan);
      plan.rs.input_positions = in.positions;
      CutStats stats;
      const std::vector<std::vector<int>> loops = realize_strands(plan, stats, false);
      const TriMesh& M = plan.rs.mesh;
      CHECK(M.check_invariants().empty());
      CHECK(long(M.num_vertices()) - M.num_edges() + M.num_faces() == 2 - 2 * genus);
      CHECK(stats.crossings == predicted);
      CHECK(M.num_vertices() == planned + stats.steiner_vertices + stats.chord_splits);
      REQUIRE(loops.size() == 2u * genus);
      std::set<int> seen;
      for (const auto& loop : loops) {
        REQUIRE(loop.size() >= 3u);
        CHECK(loop[0] == root);
        for (std::size_t i = 0; i < loop.size(); ++i) {
          CHECK(M.find_halfedge(loop[i], loop[(i + 1) % loop.size()]) >= 0);  // a cycle of edges
          if (i > 0) CHECK(seen.insert(loop[i]).second);                       // simple, and disjoint
        }
      }
      // Planning twice gives the same plan (deterministic).
      CHECK(plan_detach(in.mesh, in.positions, root, genus, hops).crossings == predicted);
    }
  }
}

TEST_CASE("the drawn choice keeps the plan with the fewest vertices once drawn and tightened, the earliest on ties") {
  const ValidMesh in = igm_test::generated_mesh(4, 2000, 5);
  const int genus = 4;
  // Plans at a few roots, both metrics: their counts once drawn and tightened, found here directly.
  std::vector<DetachPlan> plans;
  for (int root : {0, 311, 622, 933})
    for (bool hops : {false, true}) plans.push_back(plan_detach(in.mesh, in.positions, root, genus, hops));
  std::vector<long> drawn;
  for (const DetachPlan& p : plans) {
    DetachPlan copy = p;
    copy.rs.input_positions = in.positions;
    CutStats stats;
    std::vector<std::vector<int>> loops = realize_strands(copy, stats, false);
    drawn.push_back(tighten_loops(std::move(copy.rs), std::move(loops), copy.root).surface.mesh.num_vertices());
  }
  const long fewest = *std::min_element(drawn.begin(), drawn.end());
  const auto first_fewest = static_cast<std::size_t>(std::min_element(drawn.begin(), drawn.end()) - drawn.begin());
  // The counts differ between plans and the fewest is not the first plan's, or the test would
  // not tell a choice from taking the first.
  CHECK(*std::max_element(drawn.begin(), drawn.end()) > fewest);
  CHECK(drawn[0] > fewest);
  std::vector<const DetachPlan*> ptrs;
  for (const DetachPlan& p : plans) ptrs.push_back(&p);
  std::vector<long long> crossings_before;
  for (const DetachPlan& p : plans) crossings_before.push_back(p.crossings);
  DrawnPlan winner;
  const std::size_t win = fewest_drawn(ptrs, in.positions, false, &winner);
  CHECK(win == first_fewest);
  CHECK(winner.tightened.surface.mesh.num_vertices() == fewest);
  CHECK(winner.drawing.crossings == plans[win].crossings);
  CHECK(winner.tightened.loops.size() == 2u * genus);
  CHECK(winner.tightened.loops[0][0] == plans[win].root);
  // The plans are drawn on copies: unchanged, and drawing them again gives the same choice.
  for (std::size_t i = 0; i < plans.size(); ++i) CHECK(plans[i].crossings == crossings_before[i]);
  CHECK(fewest_drawn(ptrs, in.positions, true, nullptr) == win);
  // Ties go to the earlier: the winner placed after a copy of itself loses to the copy.
  std::vector<const DetachPlan*> tied = {ptrs[(win + 1) % ptrs.size()], ptrs[win], ptrs[win]};
  CHECK(fewest_drawn(tied, in.positions, false, nullptr) == (drawn[(win + 1) % ptrs.size()] == fewest ? 0u : 1u));
}
