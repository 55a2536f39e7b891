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
  /// The refined surface. Vertices 0..n-1 are the input's n vertices (weight-1 locations), the
  /// others exact points of the input surface (mesh/surface_point.h); every triangle lies inside
  /// one input face and the triangles tile the input surface with its orientation.
  std::vector<SurfacePoint> locations;
  std::vector<Vec3d> positions;                // per vertex: evaluate(locations[v])
  std::vector<std::array<int, 3>> triangles;   // counter-clockwise
  std::vector<int> triangle_patch;             // per triangle: its patch
  std::vector<LayoutArc> arcs;
  std::vector<LayoutPatch> patches;
};

}  // namespace igm
