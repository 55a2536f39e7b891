#pragma once
// Loop tightening: the detaching (cut_to_canonical_disk.h, step 2) draws parallel strands as
// normal curves that cross the edges around the tree they follow, one new vertex per crossing.
// Where a crossing vertex has a neighbour that no loop uses, the loop can run through that
// neighbour instead: the edge between them is collapsed into the neighbour, and the crossing
// vertex is gone. Repeated until no collapse applies, this pulls the outermost strand of every
// bundle onto the existing vertices beside it (a "lane"), where they are free.
//
// A collapse of a constructed loop vertex c (not the root) into a neighbour w on no loop is made
// only if it keeps everything the later stages need, each checked exactly:
//  - the mesh stays a closed 2-manifold: c and w have exactly the two common neighbours of the
//    faces at the edge cw (link condition), and every vertex keeps valence >= 3;
//  - the mesh stays a refinement of the input: each face (c, a, b) that becomes (w, a, b) lies in
//    one input face F (the joint support of c, a, b), w's support lies in F too, and the exact
//    orientation of (w, a, b) in F's barycentric chart is that of (c, a, b) (not zero);
//  - the loops stay simple and pairwise disjoint but at the root (w is on none); no loop uses the
//    edge cw, so the contraction (a homeomorphism up to isotopy, by the link condition) carries
//    the old system onto the new one: the same loops, the same order at the root, the same word.
// Input vertices are never removed or moved; the constructed vertices that stay keep their exact
// points. The embedding's pre-conditions are not kept here: the cut's own pass restores them
// (cut_to_canonical_disk.h, step 4).
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

/// Tightens `loops` (vertex cycles of surface.mesh, each starting at `root`, pairwise disjoint but
/// at the root) as described above. Pre: surface is a valid refinement (closed manifold mesh,
/// constructed points in step with it), the loops as stated. Post: a valid refinement with at most
/// as many vertices, the loops as stated, each isotopic to its input. Cost: O(P * sum over loop
/// vertices of their valence^2) exact orientation tests for P passes; P <= 1 + collapsed, and in
/// practice 2-3 (a pass visits every loop vertex once).
TightenedLoops tighten_loops(RefinedSurface surface, std::vector<std::vector<int>> loops, int root);

}  // namespace igm
