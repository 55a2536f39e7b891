#pragma once
// Topology stage: a system of 2g loops through one root vertex, pairwise disjoint except at the
// root, and the disk obtained by cutting the surface along them (paper §3–4.1).
//
//  0. locality order (CutOptions::locality_order_min_vertices; meshes of >= 32,768 vertices): the
//     steps run on a copy of the mesh whose vertices are numbered breadth-first and whose faces
//     follow them, and the result is given back in the caller's vertex ids (constructed points,
//     loops, root, disk-to-surface map; the refined faces keep the copy's order). Every step walks
//     vertex stars, and in an input whose ids are scattered (the generator shuffles them, as a
//     mesh written by some tools does) nearly every step of a walk past the cache is a miss. The
//     ids also break ties, so the cut is another one, as valid: measured on generated genus-20
//     meshes of 1M faces (4 seeds), without the normal form 3.4-5.1 s -> 1.5-1.9 s and 506.4k ->
//     509.8k vertices on average, with it 8.2-15.8 s -> 3.9-8.6 s and 545.8k -> 536.4k; of 60k
//     faces (16 seeds, normal form) 1.87 -> 1.53 s, 39.2k -> 39.8k (sd 1.7k). O(V + F).
//  1. greedy homotopy basis (Erickson & Whittlesey 2005) by tree–cotree: Dijkstra shortest-path
//     tree T from the root (metric: 3D edge lengths or hop counts), maximum spanning tree of the
//     dual graph on the edges not in T weighted by dist(u)+|uv|+dist(v); the 2g leftover edges
//     ("bands") close the loops root~u, uv, v~root. O(n log n). With CutOptions::root = -1 the
//     root and the metric are chosen among a few deterministic candidates by the crossings step 2
//     would make (planned, not built): on the shared meshes this lowers the growth 2-10x. Without
//     the normal form the candidates are those of a spread sample with the least ring deficit (the
//     4g strands leaving the root share vertices on every hop ring around it with fewer than 4g):
//     on 16 meshes of genus 2-12, 1,204 vertices added in all instead of 1,595.
//  1c. congestion reweighting (CutOptions::congestion_rounds; with the normal form for the rounds
//     of step 3a, at the kept root and metric, their Dijkstra forests penalized alike): strands
//     that share a tree path are drawn side by side in step 2, and past the free vertices beside
//     the path every further strand costs a vertex per edge it passes. So the basis is recomputed
//     at the chosen root and metric with each tree vertex's length raised by congestion_step x
//     (strands through it - 1) per round, accumulated (negotiated congestion, as in the PathFinder
//     router, McMurchie & Ebeling 1995), until the budget ends (the basis: or 10 rounds pass
//     without a new best); the plan with the fewest planned vertices is kept, so
//     this never plans more vertices than step 1. Without the normal form the best
//     CutOptions::congestion_candidates root candidates are reweighted. Measured, vertices added
//     (before -> after, spread root candidates): couplingdown 229 -> 134 (12.4 % -> 7.3 %; 106
//     with the ranked candidates of step 1), elephant 38 -> 10, helmet 6 -> 3, anchor 10 -> 0,
//     cheese 19.6k -> 18.2k; with the normal form couplingdown 322 -> 300,
//     elephant 87 -> 21, helmet 31 -> 9, anchor 39 -> 3. Measured and not kept (stop 20): more
//     root candidates (couplingdown 105-151 as the candidate set changes: noise, at up to 2x the
//     time); PathFinder's present-congestion term on top (worse on every weight tried); penalties
//     from the vertices left after tightening; reweighting the normal form's runners-up or
//     warm-starting its rounds from the basis's penalties; choosing the normal form's plan by
//     drawn count; reweighting the crosses (cheese: 804k, 668k, 615k against 649k, erratic).
//  2. detaching: a band end that is a leaf of the tree spanned by all band ends ends its strand
//     itself; the others get a vertex on the band edge hanging below them in T (u-a-b-v at 1/3 and
//     2/3, or u-b-v at 1/2). The 4g paths root~a, root~b ("strands") are drawn pairwise disjoint
//     as normal curves in a thin neighbourhood of T, ordered by the counter-clockwise depth-first
//     tour of T: every tree vertex x but the root lies on one strand, its owner (the owner of one
//     of its children); the other strands go around x, those before the owner in tour order
//     counter-clockwise and those after it clockwise, crossing the edges at x at exact rational
//     points (ordered along each edge by tour distance to the owner); a strand that reaches x on
//     the wrong side first crosses the parent edge. The owners minimise the crossings (dynamic
//     programming over T, O(sum of strand lengths)). Each face is then re-triangulated along the
//     curves. Growth: one vertex per crossing (plus a split where a curve would run along an edge,
//     and a face vertex where a fan would be flat). Cost O(n + total crossings).
//  2b. tightening (CutOptions::tighten, tighten_loops.h), after step 2 or 3: crossing vertices
//     collapse into free neighbours (the outer strand of a bundle then runs through the existing
//     vertices beside it), loops shortcut across faces, pushed aside to make room; each move
//     checked exactly and refused where it would join a loop to itself. The same loops, order and
//     word. Measured: couplingdown 2187 -> 2070 vertices (normal form 2369 -> 2163), anchor with
//     the normal form 622 -> 558, a 1M-face genus 20 +0.2 s.
//  3. normal form (CutOptions::normal_form), instead of steps 1-2, by one of two constructions
//     (CutOptions::construction; Best: the rounds, and for a root whose rounds pass
//     CutOptions::max_rounds_growth the crosses; after two such roots only the crosses). Both end
//     with a tree G from the root and 2g bands, detached once by step 2; the word traced from G's
//     tour is checked to be one cycle in commutator blocks.
//     a. rounds, handle by handle on one growing tree G from the root (no handle slides): Gamma =
//     G and the bands taken so far, not yet detached. Detached along G (step 2, once at the end),
//     the loops leave the root in the order of G's counter-clockwise tour; a gap (the stretch of
//     the tour between two consecutive taken ends, a corner of the final polygon) between blocks
//     can take new blocks. A round: the gaps between blocks of the word so far (the whole rotation
//     in round 0); a Dijkstra forest T from their free half-edges over the vertices off Gamma (a
//     vertex x of G starts at its distance along G), each vertex of T labelled by its gap; the dual
//     maximum spanning tree with every edge at Gamma or between two gaps' parts forced in first;
//     the leftover edges' ends in the tour of G + T; per gap, linked pairs (ends X Y X' Y') taken
//     greedily as long as their word read from the gap stays in blocks; the taken bands and their
//     paths in T join G. The search starts from the best k gaps (by the region they reach; k =
//     min(twice the number the last round's search used, a quarter of the loops still to find),
//     at least 1); if no gap finds a pair it is repeated from the best half of those, a quarter,
//     ..., one; then, since chords (edges off Gamma joining two Gamma vertices) wall T off where
//     branches of G run side by side, the same on a copy of the surface with every chord split at
//     its midpoint (a midpoint costs 1000 unit lengths), after which only the chords the taken
//     paths cross are split on the surface (with the other chords of a face where two meet, in the
//     copy's order, so that the paths exist). With no chord a linked pair exists (the
//     intersection form is nondegenerate). At most g rounds, at most 2 (log2 g + 2) searches per
//     round. On a coarse mesh of high genus the late rounds' paths must run along earlier loops
//     through chords and the splits compound (cheese g133 passes 4x its vertices; straightening the
//     new paths as in (b) does not stop it: root 7844 still passes 100x, stop 21).
//     b. crosses: g disjoint crosses, each round's hung at once from one tree P from the root. A
//     cross is a linked pair of loops of a tree-cotree basis of the surface cut along the crosses
//     and P so far (Dijkstra forest from seeds off them, spread farthest-first; dual maximum
//     spanning tree with the edges at a cross, at P or between two seeds' parts forced in; pairs by
//     length), without its stem to the seed: the union of the two loops' tree paths (they share a
//     path, where the loops cross once) and the two bands. After each round a Dijkstra from P's
//     vertices (at their depths along P) over the free vertices hangs each new cross from the first
//     of its vertices it reaches, and the paths join P, a wall for the later rounds. Disjoint
//     crosses are independent and, cut along all of them, the surface is a sphere with g holes,
//     connected; every cross's four ends lie next to each other in G's tour (G = P + the crosses'
//     trees; P holds no band end, so a cross may hang anywhere on it), where any rotation of
//     X Y X' Y' reads a commutator block. Chords (edges off the crosses and P joining two of their
//     vertices) are handled as in (a): fewer seeds, then a copy with every chord split. At most g
//     rounds (each takes at least one cross, as many disjoint ones as it finds). Its loops are
//     longer than the rounds' on small meshes (eight 409 vertices instead of 323), and its late
//     rounds compound too (P is a wall), but far less than the rounds. A round on a copy crosses
//     the chords at their midpoints; where a cross's tree path passes a split diagonal inside an
//     input face (neither a branch point nor a band end), that vertex is collapsed again into a
//     path neighbour when the tightening's exact checks allow (straighten_paths, tighten_loops.h),
//     so the path runs straight across the face and later rounds do not meet the fan the midpoint
//     made: cheese g133 gets 148k vertices, 17x (373k, 43x, without; measured against 2.5M for the
//     prototype), generated genus 200 on 30k faces 151k instead of 191k, each the best of 11 and 6
//     roots. Since stop 23 they get one root by default (CutOptions::normal_form_roots, hop counts):
//     160.8k in 2-3.5 s instead of 31 s, and 195k in 3 s instead of 14 s; since stop 24, with the
//     same outputs, cheese in 1.6-1.9 s (exact points built in place, a copy's seeds without its
//     full Dijkstra, the hanging's Dijkstra stopped once all hang, chords split per vertex); since
//     stops 25-26, again with the same outputs, its crosses take 7.80G instructions instead of
//     8.94G (searches that read only what they reach, compaction through the kept half-edge
//     pairing, the drawing's crossings on two threads) and its raced rounds 3.71G instead of 4.23G
//     (their gap half-edges scanned in order, not sorted).
//     Measured and rejected before: handle slides on the detached greedy loops (plan_handle_slides,
//     handle_slides.h): the slides' paths double in length per handle on cheese; rounds that
//     detached their loops before the next round (stop 13): every later round had to squeeze
//     between parallel strands (couplingdown 3.45k vertices instead of 2.37k now); in (b), P built
//     once after the last round (stop 15): its paths then wind through the maze the crosses leave
//     (cheese: path lengths summing to ~100k vertices against ~6k when hung at once; 608k vertices
//     instead of 373k, generated g200 697k instead of 148k), and hanging at once only until a round
//     needs a copy (the late crosses' paths wind as well). Prototyped on cheese (stop 19, outside
//     the library) and rejected: meridians first, then the longitudes as disjoint arcs between the
//     two sides of each: 133 disjoint independent cycles of total length 529 exist, and the arcs
//     alone would sum to 7.5k vertices, but routed one at a time with the earlier ones as walls
//     they need 70k chord splits (shortest first; longest first: 5.2M), and P then costs ~1.4M
//     detaching crossings hung last, 0.95M chord splits in the arcs hung first, 2M interleaved.
//     The crosses' size is chaotic in their greedy choices: capping a round's pairs at 1.5, 2, 3,
//     5 or 10 times its cheapest gives 543k, 664k, 484k, 841k, 664k vertices on cheese's root 0
//     (649k uncapped); the choice among root candidates picks the best of such draws.
//     Where the size comes from (stop 21, cheese root 7844, 506k vertices before the
//     straightening, 31 rounds): rounds 0-11 take 67 of the 133 crosses with no chord split;
//     rounds 12-24 take 57 with 36k; rounds 25-30 take the last 9 with 222k, the last three (4
//     crosses) 51k, 47k and 97k, the last cross alone 96,768 edges long. Of the last round's 96.8k
//     split chords, 92.9k join two vertices made by earlier splits: a path through a corridor
//     between two walls splits each of its rungs, and the fans at the new midpoints leave about
//     1.5 rungs per old one on each side, which the next path through that corridor must split in
//     turn (geometric in the paths sharing a corridor); 79.1k of them are diagonals inside input
//     faces (17.6k lie on input edges). Per round at most 7 such diagonal midpoints are branch
//     points or band ends, which must stay. With the straightening, root 7844 gets 211k vertices
//     (its last round 32k new, 14.7k collapsed again), root 0 211k instead of 649k. What is left
//     is the late crosses' own length: the last four rounds' single crosses are then 9.9k, 15.8k,
//     26.4k and 32k edges long and cross input edges 5.6k, 8.7k, 13.9k and 17.2k times (cheese
//     has 26.7k edges), winding through what the earlier walls leave; shorter ones need earlier
//     rounds that leave room for them (a choice of crosses, not a cheaper drawing). Steering the
//     paths instead does not help: a halo cost beside the walls (1 or 3 mean edges: root 7844
//     506k -> failed / 623k, root 0 649k -> 698k / 486k) or midpoints costing 3x or 5x when one
//     or both ends of their chord are split vertices (437k, 843k): the same noise.
//     Where cheese's size comes from (stop 22, root 4706): the detaching's 85k crossings are at
//     least 16.3k on P (four strands per cross hung below) plus 25.3k inside the crosses (a cross
//     hung on an arm carries three strands to where its loops meet; 8.2k if each were hung at its
//     best vertex), a pass costing about two; the crosses hold 60.8k of the 63.6k surface
//     vertices, nearly all in the last rounds' crosses, whatever their seed. Not kept (stop 22;
//     roots 4706 / 7844 / 2: 148k / 211k / 257k): each cross hung where 4 x its depth along P plus
//     its own passes is least (229k / 246k / 223k); midpoints at 1-10 mean edges (190k-209k); P
//     passable at a cost, cut there and the crosses below hung again (a round's crosses get 2-10x
//     shorter, but the re-hung paths wind: > 0.7M); crosses also hung from earlier crosses' wedges
//     between blocks (195k / 304k / 212k; after rounds without P, 0.56M); the rounds (a) for the
//     last 3-20 handles (326k to > 870k); pairs by the size of their union (182k / 240k / 218k).
//     Couplingdown (2141 vertices): every edge in a gap as a candidate band (2152-2195), the gaps'
//     depths scaled by 0.3-10 (2200-2294), the ring-deficit roots of step 1 (2234); every 10th
//     vertex as the root gives at best 2123. One shortest-path tree spanning every vertex seldom
//     holds g crossing pairs of single-edge bands with disjoint spans (couplingdown 4-6 of 9).
//     The root and metric are chosen among candidates by the planned vertex count (the refined
//     surface's vertices plus the planned detaching's crossings): each candidate is planned, not
//     drawn, and only the one kept is realized; candidates go in fixed pairs, side by side on two
//     threads (CutOptions::parallel), each pair bounded by the best of the pairs before it and
//     merged in order, so the result does not depend on the threads; a lone candidate (a given
//     root, or one root: CutOptions::normal_form_roots) of a mesh of fewer than 2000 faces per
//     handle runs (Best) its rounds and its crosses side by side instead (CutStats::raced): there
//     the rounds tend to pass their bound, and elsewhere (below genus 30) the crosses would only
//     take time and memory bandwidth from the rounds for about as many vertices (the 1M-face genus
//     20: rounds 546.8k in 4.3 s, crosses 536.0k in 8.1 s). Raced, the fewer planned vertices win,
//     the rounds on ties and with their plan after their congestion reweighting where one follows
//     (step 1c, which only lowers it: couplingdown at root 100 gets 2,266 vertices from the
//     reweighted rounds, 2,587 from the crosses, whose plan is below the rounds' first one), each
//     run stopped once it passes the other's best plan so far (it would lose anyway, so the threads
//     change nothing). From genus 30 on (Best) every candidate runs the crosses alone: on every
//     such mesh measured they gave at most the vertices Best gave with the rounds (cheese and 63
//     generated meshes of genus 30-200), and on large ones the rounds passed their bound only after
//     seconds (generated genus 200 on 400k faces: 31.7 s, the crosses took 12.3 s). Measured
//     against stop 27 (generated; one root, seed 1, unless noted): genus 30 on 1M faces 596.4k
//     vertices in 6.3 s -> 580.5k, genus 40 on 1M 735.0k in 7.7 s -> 576.1k (seed 3: 683.3k in 8.6
//     s -> 608.0k), genus 30 on 400k 303.4k in 2.5 s -> 230.3k, genus 35 on 40k (4 roots) 45.0k ->
//     35.5k, genus 50 on 1M 704.6k in 24.4 s -> 12.5 s, genus 100 on 1M ~47 s -> 16.3 s, genus 200
//     on 400k 658.5k in 43.0 s -> 10.8 s; genus 20 on 8k faces at a given root 10.0k -> 8.9k
//     (raced); the shared meshes (at the default root and at 6 given roots each), cheese and the
//     1M-face genus 20 unchanged.
//     Loops are renumbered and reoriented so that the word is exactly L0 L1 L0^-1 L1^-1 L2 L3 ...
//     Off, the word is whatever step 2 gives.
//  4. embedding pre-conditions (embed/tutte.h): every interior disk edge joining two vertices of
//     one polygon side (a root copy lies on its two sides) is split at its midpoint; then no
//     triangle has three vertices on one side. O(n).
//  5. cut: the disk whose face f is face f of the refined surface; its boundary is one ccw cycle of
//     4g sides, each from a root copy to the next, labelled (loop, direction) and paired.
// Every constructed vertex is an exact point of one input face (SurfacePoint).
#include <array>
#include <string>
#include <vector>

#include "igm/exact/predicates.h"
#include "igm/mesh/surface_point.h"
#include "igm/mesh/trimesh.h"

namespace igm {

struct CutOptions {
  /// Root vertex (the basis then uses 3D edge lengths); -1 picks, among a few deterministic
  /// candidates (the vertex of maximum valence, then evenly spaced ids; without the normal form
  /// the least ring deficit of a spread sample, step 1; with it normal_form_roots of them) and two
  /// metrics (3D lengths, hop counts), the pair whose detaching crosses the fewest edges, then the
  /// best of those after the congestion reweighting (with normal_form: whose planned construction
  /// ends with the fewest vertices).
  int root = -1;
  /// Bring the word into a1 b1 a1^-1 b1^-1 ... (step 3, <= g rounds). Off: the word is whatever the
  /// detached greedy loops give (still 4g sides, paired). The pipeline runs with it off by default
  /// (PipelineOptions::normal_form, step 3's growth); here it is on by default.
  bool normal_form = true;
  /// Which construction of step 3 builds the normal form: Best (rounds, and crosses for a root
  /// where the rounds pass max_rounds_growth; a lone root candidate of a coarse mesh runs both,
  /// and from genus 30 on only the crosses run; the fewest vertices win), or one of the two alone.
  enum class Construction { Best, Rounds, Crosses };
  Construction construction = Construction::Best;
  /// Bound on the vertices the normal form may add, as a multiple of the input's vertex count;
  /// exceeding it with every root is igm::Error(Unsupported). Cheese (g133 on 8.6k vertices) needs
  /// 17x: its late crosses' loops are long for a mesh that coarse.
  double max_normal_form_growth = 100.0;
  /// The rounds construction is abandoned for a root once it passes this multiple (its later loops
  /// compound on coarse meshes of high genus); with Best, after two roots that did so it is not
  /// tried again (from genus 30 on not at all), and the crosses construction runs instead. 2 since
  /// stop 25 (was 4): on generated meshes of genus 5-60 (500-40k faces, two seeds each) the rounds
  /// alone added between 2x and 4x on 7 of 32, and the crosses gave fewer vertices on all 7; with
  /// Best, 10 of 32 got fewer vertices (5,505 fewer in all, e.g. genus 25 on 5k faces 8,646 ->
  /// 7,365), 3 more (227 in all), the rest the same; and cheese's rounds (which the crosses beat)
  /// stop after about 1 s instead of 1.6 s.
  double max_rounds_growth = 2.0;
  /// Evaluate root candidates two at a time on two threads (root = -1; a lone candidate on a mesh
  /// of fewer than 2000 faces per handle and genus < 30: its two constructions side by side,
  /// step 3), and make the exact points of the kept plan's crossings in two halves on two threads
  /// (at least 1024 of them; each from older points only). The result is the same either way:
  /// candidates go in fixed pairs, merged in order, and every point is the same canonical rational.
  bool parallel = true;
  /// With the normal form and root = -1: how many roots are tried (each with 3D lengths and hop
  /// counts; one root: hop counts only). -1 picks clamp(min(2e5 / F, 4e6 / (F g)), 1, 12): a
  /// candidate costs about its output, which grows with g (cheese, g133: one root, 1.6-1.9 s and
  /// 160.8k vertices; 11 roots: 31 s and 148.4k). >= 1: that many (at most V); 0 or < -1 is
  /// InvalidArgument.
  int normal_form_roots = -1;
  /// After the root and metric are chosen, the basis (with the normal form: the rounds of step
  /// 3a; not the crosses) is recomputed up to this many times with the metric raised at the
  /// vertices that several strands pass, the basis stopping 10 rounds after its last new best
  /// (step 1c; the plan with the fewest planned vertices wins, so it never plans more than the
  /// first). -1 picks clamp(1e6 / F, 1, 40) (with the normal form
  /// clamp(2e5 / F, 0, 40): none past 2e5 faces), 0 turns it off, < -1 is InvalidArgument.
  int congestion_rounds = -1;
  /// Without the normal form and with root = -1: how many of the best ranked root candidates
  /// (by their first plan) are reweighted; the fewest vertices once drawn and tightened win (even
  /// with tighten off, so that it does not change the choice; on meshes of more than 2e5 faces
  /// the fewest planned). >= 1.
  int congestion_candidates = 4;
  /// The raise per round and per extra strand through a vertex, in the metric's unit (the mean
  /// edge length, or one hop). Must be finite and > 0 when congestion_rounds != 0.
  double congestion_step = 0.05;
  /// After the detaching, pull the loops onto free existing vertices where a crossing vertex has
  /// one beside it (tighten_loops.h): the same loops and word, fewer vertices.
  bool tighten = true;
  /// From this many vertices on, the steps run on a copy of the mesh renumbered for memory
  /// locality (step 0) and the result is given back in the caller's vertex ids; 0: always, -1:
  /// never, < -1 is InvalidArgument. The cut is as valid either way but not the same one (ties
  /// fall by id). Below the default (2^15; every shared mesh, armadillo's 26k vertices included)
  /// the gain is small and the cut stays the one of the input's order.
  int locality_order_min_vertices = 1 << 15;
};

struct CutStats {
  int genus = 0;
  int vertices_before = 0, faces_before = 0;
  int vertices_after = 0, faces_after = 0;
  int crossings = 0;            // vertices created where strands cross edges (step 2)
  int steiner_vertices = 0;     // face-interior vertices added to avoid flat triangles (step 2)
  int band_splits = 0;          // band edge vertices (step 2; at most two per band)
  int chord_splits = 0;         // edges split so that no strand runs along an edge (step 2)
  int collapsed = 0;            // constructed loop vertices removed by the tightening (step 2b)
  int precondition_splits = 0;  // edge splits of step 4
  long long predicted_crossings = 0;  // the detaching plan's count for the chosen root (step 2)
  long long planned_vertices = 0;     // the kept plan's vertices: refined surface + planned crossings
  int roots_tried = 0;          // (root, metric) candidates whose detaching was planned (root = -1)
  int congestion_rounds = 0;    // the congestion reweighting's round budget (step 1c; 0: off)
  int congestion_best_round = 0;  // the one kept (0: the first basis)
  int congestion_candidates = 0;  // root candidates reweighted (without the normal form)
  int normal_form_rounds = 0;   // rounds of the normal form's construction (<= g)
  int round_chord_splits = 0;   // chords split so that a round's (or the crosses' tree's) paths exist
  int straightened = 0;         // of those, split diagonals inside input faces removed again (step 3b)
  bool crosses = false;         // the normal form came from the crosses construction
  bool raced = false;           // a lone candidate ran both constructions (step 3, Best)
  bool locality_ordered = false;  // the steps ran on the mesh renumbered by step 0
  // Exact points of crossings made on two threads (CutOptions::parallel, at least 1024 in one
  // drawing); 0 on one thread.
  long long points_on_two_threads = 0;
  double seconds_basis = 0, seconds_detach = 0, seconds_cut = 0, seconds_total = 0;
};

/// One side of the disk boundary: the copy of loop `loop`, run forward (ℓ) or backward (ℓ⁻¹).
struct BoundarySide {
  int loop = -1;
  bool inverse = false;
  int mate = -1;                    // index of the side it glues to (reversed)
  std::vector<int> disk_vertices;   // from the root copy where it starts to the one where it ends
};

struct CutResult {
  RefinedSurface surface;  // the refined closed surface (same genus as the input)
  int root = -1;
  int genus = 0;
  /// 2g loops, each a vertex cycle of `surface.mesh` starting at the root (not repeated at the end).
  std::vector<std::vector<int>> loops;
  /// The disk: triangle f corresponds to surface face f, over disk vertices.
  std::vector<std::array<int, 3>> disk_triangles;
  std::vector<int> disk_to_surface;  // disk vertex -> surface vertex
  /// The boundary cycle (disk vertices, counter-clockwise, interior on the left), starting at a
  /// root copy; sides[i] covers it from one root copy to the next.
  std::vector<int> boundary;
  std::vector<BoundarySide> sides;  // 4g sides in ccw order
  CutStats stats;

  /// The gluing word read along the boundary: side i is loop sides[i].loop, inverse or not.
  std::string word() const;
};

/// Cuts a closed, connected, oriented surface of genus g >= 1 into a disk along 2g loops through one
/// root vertex (see the steps above). Pre: `mesh` is valid (closed, manifold, connected, every
/// vertex used), positions.size() == mesh.num_vertices(). Throws igm::Error(Unsupported) for genus 0,
/// igm::Error(InvalidArgument) for an out-of-range root or bad sizes (named in the caller's ids;
/// an Internal error after step 0 names the renumbered copy's), igm::Error(Unsupported) if the
/// normal form would exceed CutOptions::max_normal_form_growth, igm::Error(Internal) if an
/// invariant breaks (a round whose word is not in blocks included), igm::Error(InvalidArgument) for
/// bad congestion options. Cost without the normal form O((K + C R) n log n + crossings) for K
/// root candidates (2K plans, K = clamp(1e6 / F, 1, 24); one plan if the root is given), C of
/// them reweighted in R rounds (CutOptions::congestion_candidates,
/// congestion_rounds) and, on at most 2e5 faces, drawn to compare; with it
/// O((K' + R') g log g n log n + crossings) for K' = CutOptions::normal_form_roots roots (x2
/// metrics if K' > 1; 1 if the root is given) and R' reweighting rounds, n the refined size; with
/// CutOptions::parallel the candidates take about half that time on two cores.
CutResult cut_to_canonical_disk(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                const CutOptions& options = {});

}  // namespace igm
