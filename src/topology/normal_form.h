#pragma once
// Internal to the topology stage (igm/topology/cut_to_canonical_disk.h): step 3, the normal form,
// by its two constructions (normal_form_rounds.cpp, normal_form_crosses.cpp) and what they share
// (normal_form_tree.cpp): the tree G, its tour and word, the chords and the split copies. Not
// installed, not part of the API.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <utility>
#include <vector>

#include "detach.h"
#include "igm/topology/handle_slides.h"

namespace igm::topology_internal {

// The boundary word of loops at the root whose ends, in ccw order, are `ends` (per end: loop id,
// and whether it is the loop's last edge; each loop twice): the boundary walk leaves along an
// end, comes back at its mate and leaves along the next end clockwise (build_cut's rule),
// starting with the end at position `start`. departures[k] is the position letter k leaves from.
// Returns an empty word if the walk closes before it has used every end (more than one boundary
// cycle). For ends in one wedge, start = m - 1 reads the word from the corner outside the wedge.
// O(m log m).
Word trace_word(const std::vector<Letter>& ends, int start, std::vector<int>* departures);

// True if w is non-empty and p q p^-1 q^-1 blocks from letter 0 on (any ids and orientations).
bool blocks_from_start(const Word& w);

// Depth-first tour of a tree on M from the root, counter-clockwise after the parent edge (the
// root: all of its half-edges from root_h0 on): child(h) says whether target(h) is a child of
// origin(h); visit(h) is called, in tour order, for every other half-edge out of a tree vertex
// (the parent edges excepted). Each tree vertex once: O(E).
template <class Child, class Visit>
void tour_tree(const TriMesh& M, int root_h0, Child&& child, Visit&& visit) {
  struct It { int h, stop; };
  std::vector<It> st;
  auto step = [&](int h) {
    if (child(h)) st.push_back({M.next_around_origin(M.twin(h)), M.twin(h)});
    else visit(h);
  };
  int h = root_h0;
  do {  // valence(root) steps, each followed by one subtree
    step(h);
    while (!st.empty()) {
      It& t = st.back();
      if (t.h == t.stop) {
        st.pop_back();
        continue;
      }
      const int g = t.h;
      t.h = M.next_around_origin(g);
      step(g);  // may push (t is not used after)
    }
    h = M.next_around_origin(h);
  } while (h != root_h0);
}

// The tree G of the canonical construction: parent, distance from the root along G, membership.
struct GammaTree {
  std::vector<int> pg;
  std::vector<double> dg;
  std::vector<char> on_g;
  void grow(int nv) {
    pg.resize(nv, -1);
    dg.resize(nv, INFINITY);
    on_g.resize(nv, 0);
  }
};

// The tour of G (with the bands `taken`) on M: rot = the taken ends in tour order (Letter{band,
// end at v}), gap_of[h] = the number of ends before the half-edge h out of G that is neither a tree
// edge nor a band (-1 for the others), band_of[h] = the taken band on h's edge (-1: none);
// gap_halfedges (if given) = the half-edges with gap_of[h] >= 0, ascending. O(E).
void gamma_tour(const TriMesh& M, const GammaTree& K, const std::vector<std::pair<int, int>>& taken, int root,
                int root_h0, std::vector<int>& band_of, std::vector<int>& gap_of, std::vector<Letter>& rot,
                std::vector<int>* gap_halfedges = nullptr);

// The searches' edge length on the surface or on a chord-split copy (P: unit-scaled positions): one
// hop or the 3D length, plus kMidpointCost for each end that is a copy's chord midpoint (ids >=
// first_mid), so that crossing a chord is a last resort. Both constructions use it. O(1).
inline constexpr double kMidpointCost = 1000.0;
inline double search_length(const std::vector<Vec3d>& P, int first_mid, bool hops, int a, int b) {
  return (hops ? 1.0 : length(P[a], P[b])) + (a >= first_mid ? kMidpointCost : 0.0) +
         (b >= first_mid ? kMidpointCost : 0.0);
}

// Appends to p the (unit-scaled, double) positions of S's vertices from p.size() on, to guide the
// searches only (path lengths): each weight rounded to a double, then summed in doubles (not the
// exact point rounded, as evaluate() gives: a fifth of a crosses candidate's time on cheese).
// O(new vertices).
void extend_positions(const RefinedSurface& S, const std::vector<Vec3d>& unit, std::vector<Vec3d>& p);

// The first child of the root in G, counter-clockwise from the root's stored half-edge (G's tour
// starts at its edge). O(valence).
int first_child_of_root(const TriMesh& M, const GammaTree& G, int root);

// The end of both normal-form constructions: checks that the word traced from the tour of G
// (from the root's edge to root_start) with the bands `taken` is one cycle in commutator blocks
// (Internal otherwise), then plans step 2 once (all loops detached along G) without drawing it:
// the caller realizes only the candidate it keeps (realize_strands). True: res.surface has moved
// into `plan` and planned_vertices(plan) <= vertex_limit; false: the plan would pass
// vertex_limit (res.surface kept). O(n + total strand length).
bool plan_along_tree(CutResult& res, const GammaTree& G, int root_start, const std::vector<std::pair<int, int>>& taken,
                     long vertex_limit, DetachPlan& plan);

// The chords of M: its edges between two vertices of is_wall but for those skip(a, b, h) names (h:
// a -> b), as pairs (a, b) with a < b, sorted: made in order, each wall vertex's higher neighbours
// sorted in turn. Both constructions' copies split these. O(n + sum of valence log valence).
template <class IsWall, class Skip>
std::vector<std::pair<int, int>> sorted_chords(const TriMesh& M, IsWall&& is_wall, Skip&& skip) {
  std::vector<std::pair<int, int>> chords;
  std::vector<int> higher;
  for (int a = 0; a < M.num_vertices(); ++a) {
    if (!is_wall(a)) continue;
    higher.clear();
    const int h0 = M.vertex_halfedge(a);
    int h = h0;
    do {
      const int b = M.target(h);
      if (b > a && is_wall(b) && !skip(a, b, h)) higher.push_back(b);
      h = M.next_around_origin(h);
    } while (h != h0);
    std::sort(higher.begin(), higher.end());
    for (int b : higher) chords.push_back({a, b});
  }
  return chords;
}

// A copy of M with every chord (sorted vertex pairs of M) split at its midpoint: combinatorics
// and double positions only, to guide a search. mid[k] is chord k's midpoint (ids from
// M.num_vertices() on, in chord order). O(n + chords).
TriMesh split_copy(const TriMesh& M, const std::vector<Vec3d>& pos, const std::vector<std::pair<int, int>>& chords,
                   std::vector<int>& mid, std::vector<Vec3d>& pos_copy);

// After a search on split_copy(rs.mesh, ..., chords, mid, ...) (copy_nv vertices): splits on rs,
// in the copy's order, the chords that the copy's edges `used` cross, and every chord of a face
// where a used edge meets two, so that those faces are triangulated as in the copy and the used
// edges exist on rs. Returns the map from the copy's vertices to rs's (-1: a midpoint not split);
// `splits` counts the splits. O(chords + used).
std::vector<int> split_like_copy(RefinedSurface& rs, const std::vector<std::pair<int, int>>& chords,
                                 const std::vector<int>& mid, int copy_nv,
                                 const std::vector<std::pair<int, int>>& used, int& splits);

// Step 3a (rounds): the canonical system built handle by handle on one growing tree, with no
// slides. Gamma = a tree G from the root (parent pg, distance dg along G) and the bands taken so
// far; once detached along G (step 2, at the end) the loops root~u, uv, v~root leave the root in
// the order of G's counter-clockwise tour, and that order traces a word in commutator blocks
// (checked every round). A gap is the stretch of the tour between two consecutive taken ends (it
// becomes a corner of the polygon); a gap between blocks can take new blocks. One round:
//  a. the tour of G: each half-edge out of a vertex of G that is neither a tree edge nor a taken
//     band gets the gap it lies in; the word of the taken ends and its gaps between blocks (round 0:
//     the whole rotation of the root);
//  b. the gap t between blocks whose free half-edges reach the largest connected set of vertices
//     off Gamma;
//  c. greedy basis of the surface cut along Gamma: Dijkstra forest T from the free half-edges of
//     gap t (a vertex x of G starts at dg[x]; metric `hops` or 3D lengths, plus the congestion
//     penalties of the input vertices if `penalty` is given: raise_penalties) over the vertices off
//     Gamma; dual maximum spanning tree on the edges off T and off Gamma, every edge at a Gamma
//     vertex (but the sources) or at a vertex T misses forced in first;
//  d. the leftover edges' ends in the tour of G + T (they lie inside gap t); linked pairs (ends
//     X Y X' Y') taken greedily by right end as long as their word read from the gap stays in
//     blocks from its first letter; the taken bands and their paths in T join G.
// Chords (edges off Gamma joining two Gamma vertices) wall T off where branches of G run side by
// side. A round with no usable pair is searched again (c, d) on a copy of the surface with every
// chord split at its midpoint; then only the chords the taken paths cross are split on the
// surface, with every chord of the faces at them, in the copy's order (so that those faces are
// triangulated as in the copy and the paths exist). If that finds nothing either, gap t is given
// up for this round. Every round adds a block: at most g rounds, at most g + 1 gaps per round.
// Then step 2 detaches all 2g loops once, along G. Returns false as soon as the mesh would have
// more than vertex_limit vertices, or more than *rival (if given: the planned vertices of the
// crosses raced against it; the rounds only add vertices, so such a run would lose). Post (true):
// res.loops holds the 2g loops, their word in commutator blocks (relabelled by the caller);
// res.stats has the counts. Cost O(g^2 n log n + crossings) in the worst case, O(g n log n +
// crossings) when no gap is given up.
bool canonical_rounds(CutResult& res, const std::vector<Vec3d>& unit, bool hops, long vertex_limit, DetachPlan& plan,
                      const std::vector<double>* penalty = nullptr, const std::atomic<long>* rival = nullptr);

// Step 3b (crosses): g disjoint crosses, each round's hung at once from a tree P from the root. A
// cross is two loops a, b that share one tree path and cross once there (a linked pair of a
// tree–cotree basis of the surface cut along the earlier crosses and P, its stem to the seed
// dropped): the union of their two tree paths, with the two bands. Disjoint crosses are
// independent (each pair meets once, the pairs not at all), and cut along all of them the surface
// is a sphere with g holes, connected; P, a tree from the root over the vertices off the crosses
// meeting each cross at one vertex c, leaves the four ends of every cross next to each other in
// G's tour (G = P + the crosses' trees), where any cyclic rotation of X Y X' Y' reads a
// commutator block. Detached along G (step 2 once), the word is in blocks wherever P meets a
// cross, so nothing constrains where it does.
// One round: seeds spread over the vertices off the crosses and P (farthest first, from those and
// the root); a Dijkstra forest from them over those vertices; the dual maximum spanning tree with
// every edge at a cross, at P, or between two seeds' parts forced in first; the leftover edges'
// ends in each seed's tour; linked pairs by length, taken while their paths are disjoint from the
// pairs taken before; then the round's crosses are hung from P (hang_round), whose new paths are
// walls for the rounds after. Chords (edges off the crosses and P joining two of their vertices)
// can wall the forest off; a round that finds nothing from k seeds is searched from k/2, ..., 1,
// then on a copy with every chord split (a midpoint costs 1000 unit lengths), after which only
// the chords the found crosses use are split on the surface; P reaches a walled-off cross the same
// way. A round starts from k = min(twice the seeds the last round used, a quarter of the crosses
// still to find) seeds, at least 1. At most g rounds (each takes a cross), at most log2 k + 1
// searches on the surface and as many on a copy per round, and one or two hanging searches.
// Returns false as soon as the mesh has more than vertex_limit vertices, or at the start of a
// round once it has at least *rival (if given: the planned vertices of the rounds raced against
// it, which win ties; the count at a round's start only grows, and the plan has at least as many,
// so such a run would lose). Post (true): as canonical_rounds. Cost O(g log g (E log E +
// L^2 log L) + crossings), L <= 2g + k the leftover edges of a search.
bool canonical_crosses(CutResult& res, const std::vector<Vec3d>& unit, bool hops, long vertex_limit, DetachPlan& plan,
                       const std::atomic<long>* rival);

// Step 3c (slides): the normal form reached from detached loops by handle slides (Fulton,
// Algebraic Topology, ch. 17b; handle_slides.h), each slide drawn on the surface. A slide {i, j, x}
// replaces loop x by a new loop c from polygon corner i to corner j: with x removed, the surface
// cut along the other loops is an annulus whose two boundaries hold corners i and j, and any
// simple arc across it from corner i to corner j cuts it into a disk with the word apply_slide
// gives (the word depends only on the corners), so c is the cheapest such arc: a path from the
// root's wedge of corner i to its wedge of corner j over the vertices on no other loop (x's are
// free again), none of them beside the root but its two ends, each vertex costing kSlideHopCost
// plus the number of loop vertices beside it (the chords the arc makes for later slides), crossing
// chords (edges off the loops joining two loop vertices) at their midpoints on a copy where needed
// (a midpoint costs kMidpointCost), after which only the chords it crosses are split on the surface
// (split_like_copy). The loops are then tightened (tighten_loops), which also removes x's old
// constructed vertices.

// A slide's arc: a path vertex costs this plus one per loop vertex beside it. Hop counts alone (1
// and no loop vertices) add 6,231 vertices on 36 generated genus 2-12 meshes against 5,664 (0.25:
// 5,677, 0.75: 5,651; bench/README.md, stop 33).
inline constexpr double kSlideHopCost = 0.5;

// The loops, their surface and the word read from the root (one cycle, trace_word's convention).
struct SlideState {
  RefinedSurface rs;
  std::vector<std::vector<int>> loops;  // each from the root, pairwise disjoint but at the root
  Word word;
  int splits = 0;     // chords split by the slides drawn (split_like_copy)
  int collapsed = 0;  // constructed vertices their tightening removed
  int redrawn = 0;    // redraws redraw_loops kept
  long loop_vertices() const {
    long n = 0;
    for (const auto& l : loops) n += static_cast<long>(l.size());
    return n;
  }
};

// The word of `loops` read at the root of M from the end at position 0 of the root's ccw rotation
// (from its stored half-edge); Internal if the loops' ends do not make one boundary cycle.
// O(valence + g log g).
Word root_word(const TriMesh& M, int root, const std::vector<std::vector<int>>& loops);

// Draws slide s on st (st.word: the current word, as root_word reads it up to rotation): the new
// loop takes s.loop's id, st.word becomes apply_slide(st.word, s), the loops are tightened, and
// st.splits and st.collapsed count what that added and removed. False (st unchanged) if no path
// joins the two wedges (a wedge whose free vertices are all walled in, even on the copy).
// Internal if the drawn loops do not read st.word up to rotation before or after the slide.
// `beside_cost` is the cost of each loop vertex beside a path vertex (1; 0 for hop counts, which a
// test compares). O(n + chords + tightening).
bool draw_slide(SlideState& st, int root, const Slide& s, double beside_cost = 1.0);

// Redraws loops one at a time where that saves vertices (step 3d). Loop x, with letters p (x)
// and q (x^-1) in st.word, is drawn again on copies (draw_slide) by these moves:
// - the slide {p, p + 1, x}: the cheapest arc between x's own two wedges once x is removed, which
//   reads the same word up to rotation (every simple arc there does, handle_slides.h);
// - if st.word is in commutator blocks, every slide of x whose word is in blocks too (x becomes
//   x y^+-1 or the like inside its handle), one per resulting word up to rotation.
// The best copy (fewest vertices, then loop vertices, then the first move) replaces st if it has
// fewer vertices, or as many and fewer loop vertices. A loop drawn before later slides moved the
// others often finds a path that crosses fewer chords (couplingdown's normal form by slides:
// 2,086 vertices without, 1,969 with, by hop counts; bench/README.md, step 3d). Passes over the
// loops, longest first (ties by id), until one keeps nothing, at most max_passes; each loop's
// moves are drawn in two halves on two threads if `parallel` (the same choice either way).
// Returns the redraws kept (also added to st.redrawn). Pre: as draw_slide. O(max_passes 2g (m (n
// + chords + tightening) + g^3)) for m moves per loop (1, or about 5 in blocks).
int redraw_loops(SlideState& st, int root, int max_passes, bool parallel);

// redraw_loops' passes where step 3d runs: after step 3c's last step and on the rounds' or
// crosses' system. More find nothing on couplingdown (2 passes already end at 1,969 vertices, by
// hop counts).
inline constexpr int kRedrawPasses = 3;

// The handles formed greedily, one per step: while some loops are not in commutator blocks, each
// linked pair X .. Y .. X^-1 .. Y^-1 of them is a candidate from each of its letters (the two-slide
// formation of plan_handle_slides: first {X, the corner after X^-1, Y}, then from the corner before
// the new Y^-1 to the one before the new Y, replacing X). Every candidate's first slide is drawn on
// a copy of st; the 6 best (ranked by vertices + loop vertices / 4, then vertices, loop vertices,
// candidate order: long loops are walls that make later slides long) get their second, and the best
// of those so ranked is kept. After the last step the loops are redrawn (redraw_loops,
// kRedrawPasses). Candidates are drawn in two halves on two threads if `parallel`, merged in
// candidate order (the same choice either way). At most g steps (each adds a block and
// keeps the others: Internal otherwise), each of at most (4g)^2 + 6 drawn slides. True: st's word
// is in commutator blocks, *slides = the slides kept, *trials = the slides drawn. False (st
// unchanged): at some step no candidate could be drawn (generated genus 10 on 2k faces, seed 2).
// Pre: st as stated, tightened.
bool canonical_slides(SlideState& st, int root, bool parallel, int* slides, long long* trials);

}  // namespace igm::topology_internal
