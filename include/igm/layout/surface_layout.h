#pragma once
// A quad layout embedded on a surface: the one structure every layout producer hands to the back
// end (design.md: the topological layouts of the canonical schema, the orbifold and the open cut;
// the field-driven layout of field/). A refinement of the input surface is cut by arcs (paths
// along its edges between nodes) into patches; every patch is a topological disk whose boundary
// has four corners, so that it can be mapped onto an integer rectangle [0,a] x [0,b]. A side of a
// patch (from one corner to the next) is a chain of one or more arcs: an arc end inside a side is
// a T-junction of that patch (a corner of the patches on the other side). Sizing gives every arc
// an integer length >= 1 such that the two opposite sides of every patch have equal sums; the
// per-patch maps then place every arc's vertices by arc length on its integer segment, the same
// parameters from both sides, so every seam's transition is a rotation by a multiple of 90
// degrees plus an integer translation.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "igm/exact/predicates.h"
#include "igm/mesh/surface_point.h"

namespace igm {

/// One use of an arc by a patch side: forward (from arc.vertices.front() to back()) or backward.
struct ArcUse {
  int arc = -1;
  bool forward = true;
};

/// A path along edges of the refined surface between two nodes (layout vertices: cones, corners,
/// T-junctions, boundary corners). `vertices` lists it from one node to the other (at least two
/// vertices, consecutive ones joined by a surface edge; no repeated vertex except that the two
/// ends may be one node). `patch[0]` lies on its left when walked forward (seen from outside the
/// surface, counter-clockwise orientation), `patch[1]` on its right; -1 on the surface's boundary.
/// The two may be the same patch (an arc the patch meets on both sides, as a torus's one quad).
struct LayoutArc {
  std::vector<int> vertices;
  std::array<int, 2> patch{-1, -1};
};

/// A patch: its boundary, counter-clockwise (the patch on the left), as four sides; side k runs
/// from corner k to corner k+1 and is mapped onto the rectangle's side k: 0 bottom (+x), 1 right
/// (+y), 2 top (-x), 3 left (-y). Each side holds at least one arc use, in order along the side.
struct LayoutPatch {
  std::array<std::vector<ArcUse>, 4> sides;
};

struct SurfaceLayout {
  /// The refined surface. Vertices 0..n-1 are the input's n = num_input_vertices vertices
  /// (weight-1 locations, positions the input's), the others exact points of the input surface
  /// (mesh/surface_point.h); every triangle lies inside one input face and the triangles tile the
  /// input surface with its orientation; every vertex is used by a triangle.
  int num_input_vertices = 0;
  std::vector<SurfacePoint> locations;
  std::vector<Vec3d> positions;                // per vertex: evaluate(locations[v])
  std::vector<std::array<int, 3>> triangles;   // counter-clockwise
  std::vector<int> triangle_patch;             // per triangle: its patch
  std::vector<LayoutArc> arcs;
  std::vector<LayoutPatch> patches;
};

/// Independent check of a layout, exact and combinatorial (no geometry decides anything): sizes and
/// indices; input vertices first (vertex v < n located at itself, every other location a convex
/// combination of input vertices with positive weights summing to 1); every vertex used; the
/// triangles edge-manifold and consistently oriented (no directed edge twice); every arc a simple
/// path along surface edges (the ends may be one node), no surface edge on two arcs or twice on
/// one, an arc side with patch -1 on the surface's boundary; every edge on no arc between
/// triangles of one patch (a flood fill across such edges stays in one patch), no boundary edge
/// of the surface off the arcs; every patch, cut along its arcs (patch_disk), a topological disk
/// (connected, Euler characteristic 1) whose one boundary loop is exactly its four sides' arc uses
/// in order, counter-clockwise with the patch on the left, each side non-empty; every arc used
/// exactly once forward by its left patch and once backward by its right patch (a patch on both
/// sides uses it twice; -1 never). Returns "" or the first violation, naming the element. Does not
/// check that the triangles tile the input surface (geometry), nor any sizing. Cost O(F + V + sum
/// of arc lengths), plus O(1) GMP operations per vertex location.
std::string check_surface_layout(const SurfaceLayout& layout);

/// The half-edge structure of a layout's triangles and its arcs, for cutting patches into disks.
/// Half-edge 3t+i runs from corner i to corner i+1 of triangle t. O(V + F) ints.
struct LayoutAdjacency {
  std::vector<int> star_begin, star;   // per vertex: the half-edges leaving it (CSR, ascending)
  std::vector<int> head;               // per half-edge: the vertex it runs to
  std::vector<int> twin;               // per half-edge: the opposite one, -1 on the boundary
  std::vector<char> on_arc;            // per half-edge: it lies along an arc
  std::vector<int> patch_begin, patch_triangles;  // per patch: its triangles, ascending (CSR)
  std::vector<int> slot;               // per triangle: its index in its patch's list
  std::string error;                   // the first violation met while building, "" if none

  /// The half-edge from a to b, or -1. O(valence of a).
  int halfedge(int a, int b) const;
};

/// Builds the adjacency of a layout whose indices are in range (check_surface_layout checks them
/// first; out-of-range indices are undefined behaviour here). Sets `error` for a directed edge in
/// two triangles, an arc that does not run along surface edges, or a surface edge on two arcs.
/// Cost O(F log valence + sum of arc lengths x valence).
LayoutAdjacency layout_adjacency(const SurfaceLayout& layout);

/// A patch cut along its boundary arcs: its triangles around every surface vertex split into wedges
/// (maximal fans joined across edges on no arc), each wedge a local vertex; a disk when the layout
/// is valid.
struct PatchDisk {
  std::vector<int> triangles;                       // the patch's triangles, ascending
  std::vector<std::array<int, 3>> local_triangles;  // the same over local vertices
  std::vector<int> vertex;                          // per local vertex: its surface vertex
  /// The boundary loop as local vertices, counter-clockwise from corner 0: for side 0..3, for each
  /// arc use in order, the arc's vertices in the use's direction but the last (the next use's
  /// first). corner[k]: the index in `boundary` of corner k (the first vertex of side k).
  std::vector<int> boundary;
  std::array<int, 4> corner{-1, -1, -1, -1};
  std::string error;  // "" or why the patch is not a disk bounded by its sides (then the rest is partial)
};

/// Cuts patch `patch` of `layout` into its disk; local vertices are numbered in order of first
/// appearance over its triangles (ascending ids, corners 0, 1, 2). Checks, into `error`: at least
/// one triangle; every edge on no arc an interior edge with the same patch on both sides;
/// connected; Euler characteristic 1; the sides' arc uses, each with this patch on its left
/// (LayoutArc::patch), chain into one closed loop of distinct boundary edges that covers every
/// boundary edge of the cut patch. Pre: `adjacency` of this layout without error.
/// Cost O(patch triangles + its boundary x valence).
PatchDisk patch_disk(const SurfaceLayout& layout, const LayoutAdjacency& adjacency, int patch);

}  // namespace igm
