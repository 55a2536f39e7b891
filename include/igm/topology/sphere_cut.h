#pragma once
// Topology stage for genus 0 (paper §5; Aigerman & Lipman, "Orbifold Tutte Embeddings", SIGGRAPH
// Asia 2015): four cone vertices A, B, C, D and the disk obtained by cutting the sphere along ONE
// simple mesh path A -> B -> C -> D through them (a tree joining the cones).
//
//  1. at least 4 vertices: a 3-vertex sphere (two triangles) gets its face 0 split at the barycentre;
//  2. cones: the option, or farthest-point sampling by BFS hop distance (start: the vertex farthest
//     from vertex 0; ties by lowest id), ordered as the best of the 12 path orders by summed BFS
//     distance (ties: the first in lexicographic order). Geometry never decides topology.
//  3. every edge incident to a cone is split at its midpoint: cones become pairwise non-adjacent
//     (no triangle has two cones);
//  4. legs A->B, B->C, C->D: shortest paths (fewest vertices adjacent to a cone still to be
//     visited, then fewest edges) avoiding the path so far and the other cones; after each leg every
//     chord (an edge joining two path vertices that is not a path edge) is split at its midpoint,
//     so that the surface minus the path stays connected and no triangle has three path vertices.
//     Split passes: one for step 3 and one per leg (4 in all); a missing leg after them is
//     igm::Error(Internal).
//  5. cut: disk triangle f is surface face f; each interior path vertex has two disk copies, copy 1
//     on the faces left of the directed path, copy 2 on the faces right of it; A and D have one.
// Every constructed vertex is an exact point of one input face (SurfacePoint), and every input
// vertex keeps its id.
#include <array>
#include <vector>

#include "igm/exact/predicates.h"
#include "igm/mesh/surface_point.h"
#include "igm/mesh/trimesh.h"

namespace igm {

struct SphereCutOptions {
  /// Four input vertex ids A, B, C, D in path order; empty: the deterministic default (step 2).
  std::vector<int> cones;
};

struct SphereCutStats {
  int vertices_before = 0, faces_before = 0;
  int vertices_after = 0, faces_after = 0;
  int small_mesh_splits = 0;  // face splits of step 1
  int cone_splits = 0;        // edge splits of step 3
  int chord_splits = 0;       // edge splits of step 4
  std::array<int, 3> leg_edges{0, 0, 0};
  int path_edges = 0;
  double seconds_total = 0;
};

struct SphereCut {
  RefinedSurface surface;       // the refined sphere
  std::array<int, 4> cones{};   // surface (= input) vertex ids of A, B, C, D
  std::vector<int> path;        // surface vertices, path[0] = A, path.back() = D
  std::array<int, 4> cone_index{};  // positions of A, B, C, D in `path` (0, iB, iC, k)
  /// The disk: triangle f corresponds to surface face f. Disk vertex v < surface vertex count is
  /// surface vertex v (its only copy, or copy 1 of a path vertex); disk vertex copy2(i) is the
  /// second copy of path[i], 0 < i < k.
  std::vector<std::array<int, 3>> disk_triangles;
  std::vector<int> disk_to_surface;
  /// The boundary cycle, counter-clockwise (interior on the left), from A:
  /// A, path[1..k-1] (copy 1), D, path[k-1..1] (copy 2). Its six sides run between the cone copies
  /// A, B1, C1, D, C2, B2 at positions corners[0..5].
  std::vector<int> boundary;
  std::array<int, 6> corners{};
  int num_surface_vertices = 0;
  SphereCutStats stats;
  int copy2(int i) const { return num_surface_vertices + i - 1; }
};

/// Cuts a closed, connected, oriented genus-0 surface into a disk along a path through four cones
/// (steps above). Pre: mesh valid (closed, manifold, connected, every vertex used), positions per
/// vertex. Throws igm::Error(InvalidArgument) if the mesh is not a sphere, if two edges join the
/// same two vertices, or for a cone list that does not have 4 entries or has an out-of-range or
/// repeated entry (the message names it); igm::Error(Internal) if a leg is not found.
/// Cost O(n log n) (Dijkstra on small integer weights) plus O(n) splits.
SphereCut cut_sphere(const TriMesh& mesh, const std::vector<Vec3d>& positions, const SphereCutOptions& options = {});

}  // namespace igm
