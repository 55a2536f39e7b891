// Tests of step 3c, the normal form by handle slides drawn on the surface
// (src/topology/normal_form_slides.cpp, internal): each drawn slide against the word apply_slide
// predicts, read again from the drawn loops by an independent walk around the root; the surface
// re-checked as an exact refinement of the input; the loops from their raw vertex lists.
#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "../../src/topology/normal_form.h"
#include "generated_mesh.h"
#include "loop_check.h"
#include "igm/mesh/validate.h"
#include "igm/topology/cut_to_canonical_disk.h"
#include "igm/topology/handle_slides.h"
#include "refinement_check.h"

using namespace igm;
using namespace igm::topology_internal;

namespace {

// The boundary word of loops at the root, read independently of the library's tracing: the loop
// ends around the root counter-clockwise; the walk leaves along an end (forward if it is the
// loop's first edge), comes back at the loop's other end and leaves along the next end
// clockwise. Every rotation of it is returned as a string, for comparisons up to rotation.
std::vector<std::string> words_at_root(const TriMesh& M, const std::vector<std::vector<int>>& loops, int root) {
  std::vector<std::pair<int, bool>> ends;  // (loop, last edge?) ccw
  const int h0 = M.vertex_halfedge(root);
  int h = h0;
  do {
    const int t = M.target(h);
    for (int i = 0; i < static_cast<int>(loops.size()); ++i) {
      if (loops[i][1] == t) ends.push_back({i, false});
      if (loops[i].back() == t) ends.push_back({i, true});
    }
    h = M.next_around_origin(h);
  } while (h != h0);
  const int m = static_cast<int>(ends.size());
  auto mate = [&](int k) {
    for (int j = 0; j < m; ++j)
      if (j != k && ends[j].first == ends[k].first) return j;
    return -1;
  };
  std::vector<std::string> letters;
  int leave = 0;
  for (int k = 0; k < m; ++k) {
    std::string letter = "L";
    letter += std::to_string(ends[leave].first);
    if (ends[leave].second) letter += '\'';
    letters.push_back(letter);
    leave = (mate(leave) + m - 1) % m;
  }
  std::vector<std::string> all;
  for (int r = 0; r < m; ++r) {
    std::string w;
    for (int k = 0; k < m; ++k) {
      if (k) w += ' ';
      w += letters[(r + k) % m];
    }
    all.push_back(w);
  }
  return all;
}

bool reads(const SlideState& st, int root, const Word& w) {
  const auto all = words_at_root(st.rs.mesh, st.loops, root);
  return std::find(all.begin(), all.end(), to_string(w)) != all.end();
}

// The detached greedy loops of a generated mesh (the cut without the normal form), as a start.
struct Start {
  ValidMesh in;
  SlideState st;
  int root = -1;
};
Start greedy_start(int genus, long faces, std::uint64_t seed) {
  Start s{igm_test::generated_mesh(genus, faces, seed), {}, -1};
  CutOptions o;
  o.normal_form = false;
  CutResult c = cut_to_canonical_disk(s.in.mesh, s.in.positions, o);
  s.root = c.root;
  s.st.rs = std::move(c.surface);
  s.st.loops = std::move(c.loops);
  s.st.word = root_word(s.st.rs.mesh, s.root, s.st.loops);
  return s;
}

}  // namespace

TEST_CASE("each drawn slide reads the word apply_slide predicts, on an exact refinement, with its vertices counted") {
  // The slides plan_handle_slides gives for the greedy loops of a generated genus-4 mesh, drawn one
  // after the other: after each, the loops read (up to rotation) the predicted word, stay simple
  // and disjoint, the surface is an exact refinement of the input, and the vertex count moved by
  // exactly the splits made minus the tightening's collapses.
  Start s = greedy_start(4, 3000, 11);
  REQUIRE(reads(s.st, s.root, s.st.word));
  Word planned_final;
  const std::vector<Slide> plan = plan_handle_slides(s.st.word, &planned_final);
  REQUIRE(plan.size() >= 2);
  int drawn = 0;
  for (const Slide& sl : plan) {
    CAPTURE(drawn);
    const Word predicted = apply_slide(s.st.word, sl);
    const int before = s.st.rs.mesh.num_vertices(), splits = s.st.splits, collapsed = s.st.collapsed;
    const std::vector<std::vector<int>> old_loops = s.st.loops;
    REQUIRE(draw_slide(s.st, s.root, sl));
    ++drawn;
    CHECK(s.st.word == predicted);
    CHECK(reads(s.st, s.root, predicted));
    CHECK(igm_test::loop_violation(s.st.rs.mesh, s.st.loops, s.root, s.in.genus) == "");
    CHECK(igm_test::refinement_violation(s.in, s.st.rs, true) == "");
    CHECK(s.st.rs.mesh.num_vertices() == before + (s.st.splits - splits) - (s.st.collapsed - collapsed));
    // Only the slid loop is new; the others are the same up to the tightening (same ends' order).
    CHECK(s.st.loops.size() == old_loops.size());
  }
  CHECK(s.st.word == planned_final);
  CHECK(commutator_rotation(s.st.word) >= 0);
}

TEST_CASE("the greedy slides bring the loops into commutator blocks, the same on two threads as on one") {
  for (const auto& [genus, faces, seed] : {std::tuple{3, 2000L, 5u}, std::tuple{6, 4000L, 6u}}) {
    CAPTURE(genus);
    Start s = greedy_start(genus, faces, seed);
    SlideState one = s.st, two = s.st;
    int slides_one = 0, slides_two = 0;
    long long trials_one = 0, trials_two = 0;
    REQUIRE(canonical_slides(one, s.root, false, &slides_one, &trials_one));
    REQUIRE(canonical_slides(two, s.root, true, &slides_two, &trials_two));
    CHECK(commutator_rotation(one.word) >= 0);
    CHECK(reads(one, s.root, one.word));
    CHECK(slides_one % 2 == 0);
    CHECK(slides_one <= 2 * genus);
    CHECK(trials_one >= slides_one);
    CHECK(igm_test::loop_violation(one.rs.mesh, one.loops, s.root, genus) == "");
    CHECK(igm_test::refinement_violation(s.in, one.rs, true) == "");
    CHECK(slides_two == slides_one);
    CHECK(trials_two == trials_one);
    CHECK(two.word == one.word);
    CHECK(two.loops == one.loops);
    CHECK(two.rs.mesh.num_vertices() == one.rs.mesh.num_vertices());
  }
}

TEST_CASE("a loop system already in blocks takes no slide") {
  // Genus 1: any two loops through one point crossing there read a b a^-1 b^-1.
  Start s = greedy_start(1, 1000, 3);
  REQUIRE(commutator_rotation(s.st.word) >= 0);
  const int before = s.st.rs.mesh.num_vertices();
  int slides = -1;
  long long trials = -1;
  REQUIRE(canonical_slides(s.st, s.root, true, &slides, &trials));
  CHECK(slides == 0);
  CHECK(trials == 0);
  CHECK(s.st.rs.mesh.num_vertices() == before);
}

TEST_CASE("a slide's arc that avoids loop vertices adds fewer vertices than the fewest hops") {
  // The slides plan_handle_slides gives for generated genus-6 greedy loops, drawn twice: with the
  // default arc cost (each loop vertex beside a path vertex costs 1: the chord it makes for later
  // arcs) and by hop counts (beside_cost 0). The same words; the default adds fewer vertices
  // (bench/README.md, stop 33: 36 generated meshes 5,664 against 6,231 with steps 3c-3d), and its
  // system is checked like any drawn one.
  Start s = greedy_start(6, 4000, 6);
  SlideState beside = s.st, hops = s.st;
  for (const Slide& sl : plan_handle_slides(s.st.word)) {
    REQUIRE(draw_slide(beside, s.root, sl));
    REQUIRE(draw_slide(hops, s.root, sl, 0.0));
  }
  MESSAGE("genus 6, slides as planned: " << beside.rs.mesh.num_vertices() << " vertices, by hop counts "
                                         << hops.rs.mesh.num_vertices());
  CHECK(beside.word == hops.word);
  CHECK(commutator_rotation(beside.word) >= 0);
  CHECK(beside.rs.mesh.num_vertices() < hops.rs.mesh.num_vertices());
  CHECK(reads(beside, s.root, beside.word));
  CHECK(igm_test::loop_violation(beside.rs.mesh, beside.loops, s.root, 6) == "");
  CHECK(igm_test::refinement_violation(s.in, beside.rs, true) == "");
}

TEST_CASE("redrawing loops keeps their word, or a word in blocks, and never adds vertices (step 3d)") {
  // The slides plan_handle_slides gives for generated genus-6 greedy loops, drawn without step
  // 3c's choices: redrawing that system loop by loop lowers its vertex count, and the result is
  // checked like any drawn system, the same on one thread as on two.
  Start s = greedy_start(6, 4000, 6);
  const Word greedy_word = s.st.word;
  REQUIRE(commutator_rotation(greedy_word) < 0);
  {
    // Not in blocks: only each loop's own corners are tried, so the word stays up to rotation.
    SlideState st = s.st;
    const int before = st.rs.mesh.num_vertices();
    const int kept = redraw_loops(st, s.root, 2, true);
    CHECK(st.redrawn == kept);
    CHECK(reads(st, s.root, greedy_word));
    CHECK(st.rs.mesh.num_vertices() <= before);
    CHECK(igm_test::loop_violation(st.rs.mesh, st.loops, s.root, 6) == "");
    CHECK(igm_test::refinement_violation(s.in, st.rs, true) == "");
  }
  for (const Slide& sl : plan_handle_slides(s.st.word)) REQUIRE(draw_slide(s.st, s.root, sl));
  REQUIRE(commutator_rotation(s.st.word) >= 0);
  SlideState one = s.st, two = s.st;
  const int before = one.rs.mesh.num_vertices(), splits = one.splits, collapsed = one.collapsed;
  const int kept = redraw_loops(one, s.root, 3, false);
  MESSAGE("genus 6, slides as planned: " << before << " vertices, " << one.rs.mesh.num_vertices() << " after "
                                         << kept << " redraws");
  CHECK(kept > 0);
  CHECK(one.redrawn == kept);
  CHECK(one.rs.mesh.num_vertices() < before);
  CHECK(one.rs.mesh.num_vertices() == before + (one.splits - splits) - (one.collapsed - collapsed));
  CHECK(commutator_rotation(one.word) >= 0);
  CHECK(reads(one, s.root, one.word));
  CHECK(igm_test::loop_violation(one.rs.mesh, one.loops, s.root, 6) == "");
  CHECK(igm_test::refinement_violation(s.in, one.rs, true) == "");
  CHECK(redraw_loops(two, s.root, 3, true) == kept);
  CHECK(two.word == one.word);
  CHECK(two.loops == one.loops);
  CHECK(two.rs.mesh.num_vertices() == one.rs.mesh.num_vertices());
  // No pass, no redraw.
  SlideState none = s.st;
  CHECK(redraw_loops(none, s.root, 0, true) == 0);
  CHECK(none.loops == s.st.loops);
}
