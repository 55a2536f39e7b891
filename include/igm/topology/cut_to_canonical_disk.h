#pragma once
// Topology stage: a system of 2g loops through one root vertex, pairwise disjoint except at the
// root, and the disk obtained by cutting the surface along them (paper §3–4.1). The steps (their
// algorithms are documented where they are declared, src/topology/detach.h and normal_form.h;
// measured choices and rejected variants in bench/README.md):
//  0. locality order (meshes of >= CutOptions::locality_order_min_vertices): the steps run on a
//     copy renumbered breadth-first for memory locality; the result comes back in the caller's
//     ids (ties fall by id, so the cut is another one, as valid). O(V + F).
//  1. greedy homotopy basis (Erickson & Whittlesey 2005) by tree-cotree: shortest-path tree T from
//     the root (3D edge lengths or hop counts), maximum spanning tree of the dual on the edges off
//     T weighted by dist(u) + |uv| + dist(v); the 2g leftover edges ("bands") close the loops
//     root~u, uv, v~root. O(n log n) per root. With root = -1 the root and metric are chosen among
//     deterministic candidates by the vertices their detaching will add (planned, not drawn).
//  1c. congestion reweighting (CutOptions::congestion_rounds): the basis is recomputed with the
//     metric raised at vertices that several strands pass (negotiated congestion, McMurchie &
//     Ebeling 1995); the plan with the fewest planned vertices is kept, never more than step 1's.
//  2. detaching: the 4g strands root~a are drawn pairwise disjoint as normal
//     curves along T, crossing edges at exact rational points, the strands' sides at each tree
//     vertex chosen by dynamic programming to minimise the crossings; faces re-triangulated.
//     Growth: one vertex per crossing (plus rare edge and face splits). O(n + crossings).
//  2b. tightening (CutOptions::tighten, tighten_loops.h): crossing vertices collapse into free
//     neighbours where exact checks allow; the same loops, order and word, fewer vertices.
//  3. normal form (CutOptions::normal_form), instead of steps 1-2: the loops are built so that the
//     word read around the root is in commutator blocks, then detached once by step 2 and
//     relabelled to exactly L0 L1 L0^-1 L1^-1 L2 L3 ... Two constructions (CutOptions::
//     construction): 3a rounds, handle by handle on one growing tree from the root; 3b crosses,
//     g disjoint linked pairs hung from one tree from the root. Each round's word is checked
//     (Internal if not in blocks); at most g rounds each. 3c (CutOptions::slides) slides: the
//     detached greedy loops of steps 1-2b brought into blocks by handle slides, each drawn as the
//     cheapest arc between its two corners (normal_form.h); the fewer vertices win. Where it runs
//     beside step 3 (within CutOptions::slides_budget) and the root is not given, steps 1-2b come
//     first (their root of least ring deficit among the reweighted candidates) and step 3 runs at
//     their root, with both metrics, beside step 3c's slides (generated genus 2-12, 36 meshes:
//     4,876 vertices added instead of 5,664 with step 3's own root search, in about the same
//     time; couplingdown 90 instead of 129). Past its budget it runs after step 3, where step 3
//     added more than 2 %. Off, the word is whatever step 2 gives.
//  4. embedding pre-conditions (embed/tutte.h): every interior disk edge joining two vertices of
//     one polygon side (a root copy lies on its two sides) is split at its midpoint; then no
//     triangle has three vertices on one side. O(n).
//  5. cut: the disk whose face f is face f of the refined surface; its boundary is one ccw cycle of
//     4g sides, each from a root copy to the next, labelled (loop, direction) and paired.
//  6. restarts (CutOptions::restarts, off by default): with the normal form, where steps 0-5 added
//     more than 2 %, they run again on copies with shuffled vertex ids; the fewest vertices win.
// Every constructed vertex is an exact point of one input face (SurfacePoint). A failing
// invariant is igm::Error(Internal), never a silent skip; every loop has a stated bound.
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
  /// ends with the fewest vertices). With the normal form where step 3c runs beside step 3, both
  /// systems use the root of steps 1-1c (step 3 with both metrics at it), chosen there among the
  /// reweighted candidates of least ring deficit (congestion_candidates).
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
  /// The rounds construction is abandoned for a root once it passes this multiple of the input's
  /// vertices (its later loops compound on coarse meshes of high genus); with Best, after two roots
  /// that did so it is not tried again (from genus 30 on not at all), and the crosses run instead.
  double max_rounds_growth = 2.0;
  /// Evaluate root candidates two at a time on two threads (root = -1; a lone candidate on a mesh
  /// of fewer than 2000 faces per handle and genus < 30: its two constructions side by side,
  /// step 3), and make the exact points of the kept plan's crossings in two halves on two threads
  /// (at least 1024 of them; each from older points only). The result is the same either way:
  /// candidates go in fixed pairs, merged in order, and every point is the same canonical rational.
  bool parallel = true;
  /// With the normal form and root = -1, where step 3c does not run beside step 3 (there step 3
  /// runs at step 3c's root instead, with both metrics): how many roots are tried (each with 3D
  /// lengths and hop counts; one root: hop counts only). -1 picks clamp(min(2e5 / F, 4e6 / (F g)),
  /// 1, 12): a candidate costs about its output, which grows with g. >= 1: that many (at most V);
  /// 0 or < -1 is InvalidArgument.
  int normal_form_roots = -1;
  /// After the root and metric are chosen, the basis (with the normal form: the rounds of step
  /// 3a; not the crosses) is recomputed up to this many times with the metric raised at the
  /// vertices that several strands pass, the basis stopping once max(10, r) rounds have passed
  /// since its last new best, found at round r (step 1c; the plan with the fewest planned
  /// vertices wins, so it never plans more than the first; with the normal form, on at most 2e5
  /// faces, the 8 plans with the fewest are drawn and the fewest vertices once drawn and
  /// tightened win). -1 picks clamp(2e6 / F, 1, 500) (with the normal form clamp(1e6 / F, 0,
  /// 250), all of them run, none past 2e5 faces), 0 turns it off, < -1 is InvalidArgument.
  int congestion_rounds = -1;
  /// Without the normal form (and for step 3c's greedy loops) and with root = -1: how many of the
  /// best ranked root candidates (by their first plan) are reweighted; the fewest vertices once
  /// drawn and tightened win (even with tighten off, so that it does not change the choice; on
  /// meshes of more than 2e5 faces the fewest planned); on at most 2e5, for step 3c, only among
  /// those of least ring deficit (the hop rings' shortfall of 4g vertices near the root). >= 1.
  int congestion_candidates = 4;
  /// The raise per round and per extra strand through a vertex, in the metric's unit (the mean
  /// edge length, or one hop). Must be finite and > 0 when congestion_rounds != 0.
  double congestion_step = 0.05;
  /// After the detaching, pull the loops onto free existing vertices where a crossing vertex has
  /// one beside it (tighten_loops.h): the same loops and word, fewer vertices.
  bool tighten = true;
  /// With the normal form (construction Best, tighten on): also bring the detached greedy loops of
  /// steps 1-2b into the normal form by handle slides drawn on the surface (step 3c), and keep
  /// whichever of the two systems has fewer vertices once tightened (the rounds' or crosses' on
  /// ties). It costs about 1 microsecond x F g^2 more (about 6 g^2 slides drawn on copies) and
  /// often adds far fewer vertices (generated genus 10 on 100k faces: 0.35 % instead of 8.6 %, in
  /// 8.2 s instead of 1.6 s). Where it runs, the loops of both systems are then also redrawn one
  /// at a time where that saves vertices (step 3d: between the loop's own corners, or by a slide
  /// that keeps the blocks; about 30 % more time, couplingdown 1,970 vertices instead of 2,086).
  /// -1: by slides_budget, 0: never, 1: always; other values are InvalidArgument.
  int slides = -1;
  /// Where step 3c runs with slides = -1, in units of F g^2 (about 1 microsecond each on the bench
  /// machine): beside step 3 where F g^2 <= slides_budget and F g^3 <= 16 slides_budget; where both
  /// are at most 4x that, after step 3, and only if step 3's system (tightened) added more than 2 %
  /// of the input's vertices (then the fewer vertices win as beside). Generated genus 10 on 200k
  /// faces: 7.4 % growth without, 0.24 % with, in 13 s instead of 0.4 s; at the 4x bounds up to
  /// about 50 s (genus 20 on 80k faces). 0: only with slides = 1. Finite and >= 0, else
  /// InvalidArgument.
  double slides_budget = 1e7;
  /// With the normal form: where the cut added more than 2 % of the input's vertices, it runs
  /// again on this many copies of the mesh with shuffled vertex ids (copy i by the fixed seed i,
  /// so the result is the same every time), and the fewest vertices win (the earliest on ties).
  /// The ids break the ties of every search, and on coarse meshes the growth varies with them
  /// (couplingdown, genus 9 on 1,841 vertices: 90 as given, 86 to 155 vertices added over 32
  /// other orders of its ids; 15 restarts do not beat its 90, in 14x the time). A copy whose
  /// construction passes the growth bounds (Unsupported) is counted and skipped; the copies are
  /// not renumbered by step 0. Each
  /// run costs about as much as the first, so it is off by default (with -1 the topology tests
  /// would take 3-10x as long); -1 picks clamp(5e6 / (F g^2), 0, 15); < -1 is InvalidArgument.
  int restarts = 0;
  /// From this many vertices on, the steps run on a copy of the mesh renumbered for memory
  /// locality (step 0) and the result is given back in the caller's vertex ids; 0: always, -1:
  /// never, < -1 is InvalidArgument. The cut is as valid either way but not the same one (ties
  /// fall by id). Below the default (2^15; every shared mesh, armadillo's 26k vertices included)
  /// the cut stays the one of the input's order.
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
  int collapsed = 0;            // constructed vertices removed by the tightening (step 2b; 3c: per slide)
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
  int slides = 0;               // handle slides of the kept normal form (step 3c; 0: not slides)
  int slide_splits = 0;         // chords split by those slides and by step 3d's redraws (their
                                // collapses: `collapsed`)
  long long slide_trials = 0;   // slides drawn on copies to choose them (step 3c; 0: not run)
  bool slides_failed = false;   // step 3c ran and some step could draw none of its candidates
  int redrawn = 0;              // loops of the kept system redrawn with fewer vertices (step 3d)
  bool slides_after = false;    // step 3c ran after step 3, past slides_budget, for step 3's growth
  bool raced = false;           // a lone candidate ran both constructions (step 3, Best)
  bool locality_ordered = false;  // the steps ran on the mesh renumbered by step 0
  int restarts = 0;               // runs on shuffled copies (CutOptions::restarts; 0: none ran)
  int restart_kept = 0;           // the one kept (0: the first run)
  int restarts_failed = 0;        // of those, runs that passed the growth bounds
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
/// CutOptions::parallel the candidates take about half that time on two cores. With
/// CutOptions::restarts = k, up to k + 1 times that.
CutResult cut_to_canonical_disk(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                const CutOptions& options = {});

}  // namespace igm
