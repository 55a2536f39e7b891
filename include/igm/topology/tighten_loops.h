#pragma once
// Loop tightening: the detaching (cut_to_canonical_disk.h, step 2) draws parallel strands as
// normal curves that cross the edges around the tree they follow, one new vertex per crossing.
// Where a crossing vertex has a neighbour that no loop uses, the loop can run through that
// neighbour instead, and the crossing vertex goes. Four moves, repeated until none applies:
//  M1 a constructed loop vertex c (not the root) collapses into a free neighbour w (the edge cw is
//     contracted into w): the loop runs through w. This pulls the outer strand of a bundle onto
//     the existing vertices beside it (a "lane");
//  M2 a loop vertex whose two loop neighbours (neither the root) span a face leaves the loop, which
//     takes the face's third edge (an isotopy across the face); done at once after an M1 that made
//     w adjacent to the loop vertex two steps on;
//  M3 a constructed vertex on no loop (left by M2, or by an earlier stage) collapses into a
//     neighbour;
//  M4 where a constructed loop vertex c is next to a vertex w of another loop B, B is pushed off w
//     onto w's free neighbours on the far side from c (an isotopy across w's faces there), and c
//     collapses into w; undone unless both succeed.
// A collapse of v into u is made only if it keeps everything the later stages need, each checked
// exactly:
//  - the mesh stays a closed 2-manifold: v and u have exactly the two common neighbours of the
//    faces at the edge vu (link condition), and every vertex keeps valence >= 3;
//  - the mesh stays a refinement of the input: each face (v, a, b) that becomes (u, a, b) lies in
//    one input face F (the joint support of v, a, b), u's support lies in F too, and the exact
//    orientation of (u, a, b) in F's barycentric chart is that of (v, a, b) (not zero);
//  - the loops stay simple and pairwise disjoint but at the root; no loop uses the edge vu, so the
//    contraction (a homeomorphism up to isotopy, by the link condition) carries the old system
//    onto the new one: the same loops, the same order at the root, the same word.
// No move may make a loop vertex adjacent to a vertex of its own loop other than its two loop
// neighbours, or to the root unless it is an end of its loop: such an edge could join two vertices
// of one polygon side, which the cut would split again (cut_to_canonical_disk.h, step 4).
// Input vertices are never removed or moved; the constructed vertices that stay keep their exact
// points. Variants measured and not built: bench/README.md.
#include <utility>
#include <vector>

#include "igm/mesh/surface_point.h"

namespace igm {

struct TightenStats {
  int collapsed = 0;  // constructed vertices removed
  int shortcuts = 0;  // loop vertices left by a shortcut across a face
  int pushes = 0;     // collapses made possible by pushing another loop off the target vertex
  long long passes = 0;  // sweeps over the loops (the last one changes nothing)
};

struct TightenedLoops {
  RefinedSurface surface;                // input vertices keep their ids; constructed ones renumbered
  std::vector<std::vector<int>> loops;   // the same loops (same order, same start at the root)
  TightenStats stats;
};

struct StraightenedPaths {
  RefinedSurface surface;  // vertices below `first` keep their ids; the others are renumbered in order
  std::vector<int> to;     // old vertex -> its new id, or (removed) that of the vertex it went into
  int removed = 0;
};

/// Straightens paths between the points where they cross input edges: every vertex v >= first
/// that lies strictly inside an input face, has exactly two neighbours along `edges` (vertex pairs
/// of surface.mesh: the union of some vertex-disjoint paths and trees) and is not in `keep`, is
/// collapsed into one of its two path neighbours (the first listed, else the other), where the
/// collapse passes the tightening's exact checks (link condition, valences >= 3, every moved face
/// keeping its orientation in its input face). The path then runs straight from that neighbour
/// to the next. For the normal form's crosses (cut_to_canonical_disk.h, step 3b): a path found on
/// a copy crosses the diagonals between walls inside an input face at their midpoints, and without
/// this every later path through the corridor would cross the fans at those midpoints in turn.
/// Pre: a valid refinement, `edges` edges of its mesh (else igm::Error(Internal)). Post: a valid
/// refinement of the same surface with `removed` fewer vertices; an edge (x, y) of `edges` becomes
/// (to[x], to[y]) (dropped where they are equal). Cost O(F + candidates x valence^2) and
/// O(valence) exact orientations per tried collapse.
StraightenedPaths straighten_paths(RefinedSurface surface, const std::vector<std::pair<int, int>>& edges,
                                   const std::vector<int>& keep, int first);

/// Tightens `loops` (vertex cycles of surface.mesh, each starting at `root`, pairwise disjoint but
/// at the root) as described above. Pre: surface is a valid refinement (closed manifold mesh,
/// constructed points in step with it), the loops as stated (else igm::Error(Internal) naming the
/// vertex). Post: a valid refinement with at most as many vertices, the same loops up to isotopy,
/// in the same order at the root. Cost: O(F) to set up and rebuild, plus for the first pass
/// O(sum over loop and free constructed vertices of valence^2) with O(valence) exact orientations
/// per tried collapse; later passes check only the vertices near the last pass's moves (the same
/// moves as checking all: see the .cpp); at most V (V + 2) + 1 passes, in practice 3 to 9.
/// every_vertex_every_pass checks every vertex in every pass instead: the reference the
/// dirty-vertex passes must equal exactly (tests compare the two). `barred` (one flag per vertex,
/// or empty): vertices no loop may move onto (M1 and M4 never make a loop run through one); the
/// open surfaces' cut (open_cut.h) bars the boundary and the filled holes.
TightenedLoops tighten_loops(RefinedSurface surface, std::vector<std::vector<int>> loops, int root,
                             bool every_vertex_every_pass = false, const std::vector<char>& barred = {});

}  // namespace igm
