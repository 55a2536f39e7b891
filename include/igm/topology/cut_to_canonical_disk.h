#pragma once
// Topology stage: a system of 2g loops through one root vertex, pairwise disjoint except at the
// root, and the disk obtained by cutting the surface along them (paper §3–4.1).
//
//  1. greedy homotopy basis (Erickson & Whittlesey 2005) by tree–cotree: Dijkstra shortest-path
//     tree T from the root on 3D edge lengths, maximum spanning tree of the dual graph on the
//     edges not in T weighted by dist(u)+|uv|+dist(v); the 2g leftover edges ("bands") close the
//     loops root~u, uv, v~root. O(n log n).
//  2. detaching: each band uv is split at 1/3 and 2/3 into u-a-b-v, a hangs below u and b below v
//     in T. The 4g paths root~a, root~b ("strands") are drawn pairwise disjoint as normal curves
//     in a thin neighbourhood of T: strands are ordered by the counter-clockwise depth-first tour of
//     T; at each tree vertex x only the last strand of x's subtree passes through x, the others
//     go around x on one side, crossing the edges at x at exact rational points (ordered by tour
//     index along each edge). Each face is then re-triangulated along the curves. Growth: one new
//     vertex per crossing (plus a few to keep triangles non-degenerate). Cost O(n + total crossings).
//  3. embedding pre-conditions: every edge that is not on a loop but joins two loop vertices (the
//     root included) is split at its midpoint, so that no interior disk edge joins two boundary
//     vertices, no triangle has three boundary vertices and every root wedge has an interior vertex.
//  4. normal form: the slides planned by plan_handle_slides (handle_slides.h, <= 2g of them) are
//     realized one by one: the new loop is a shortest path between the two root wedges through
//     vertices on no loop (it exists because of step 3), the replaced loop is dropped, and the edges
//     joining the new loop to other loop vertices are split (step 3 again, locally). Loops are then
//     renumbered and reoriented so that the word is exactly L0 L1 L0^-1 L1^-1 L2 L3 ...
//     Known limitation: near the root the new loops run in thin strips between earlier loops, and
//     each slide refines those strips again, so growth compounds with the number of slides
//     (couplingdown g9: 1841 -> ~20k vertices; genus >= 20 is impractical). normal_form = false
//     avoids it (growth of steps 2-3 only).
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
  /// candidates (the vertex of maximum valence, then evenly spaced ids) and two metrics (3D
  /// lengths, hop counts), the pair whose detaching crosses the fewest edges.
  int root = -1;
  /// Bring the word into a1 b1 a1^-1 b1^-1 ... by handle slides (<= 2g). Off: the word is whatever
  /// the detached greedy loops give (still 4g sides, paired), for tests and measurements.
  bool normal_form = true;
  /// Bound on the slides' edge splits, as a multiple of the vertex count before the slides;
  /// exceeding it is igm::Error(Unsupported) (the slides' paths run between earlier loops, and on
  /// high genus their length compounds: cheese g133 would grow past 10M vertices).
  double max_slide_growth = 4.0;
  /// Debug: rebuild the cut after every slide and compare its word with the planned one (O(n) each).
  bool check_each_slide = false;
};

struct CutStats {
  int genus = 0;
  int vertices_before = 0, faces_before = 0;
  int vertices_after = 0, faces_after = 0;
  int crossings = 0;            // vertices created where strands cross edges (step 2)
  int steiner_vertices = 0;     // face-interior vertices added to avoid flat triangles (step 2)
  int band_splits = 0;          // two per band (step 2)
  int chord_splits = 0;         // edges split so that no strand runs along an edge (step 2)
  int precondition_splits = 0;  // edge splits of step 3
  long long predicted_crossings = 0;  // the detaching plan's count for the chosen root (step 2)
  int roots_tried = 0;          // (root, metric) candidates whose detaching was planned (root = -1)
  int num_slides = 0;           // handle slides performed (normal form)
  int slide_splits = 0;         // edges split where the slides' paths cross them (normal form)
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
/// igm::Error(InvalidArgument) for an out-of-range root or bad sizes, igm::Error(Internal) if an
/// invariant breaks. Cost O(n log n + crossings).
CutResult cut_to_canonical_disk(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                const CutOptions& options = {});

}  // namespace igm
