#pragma once
// The k-quad pattern for a layout patch whose boundary turns at k != 4 corners (docs/field.md,
// section 4): one interior node of valence k joined to a node near the middle of every side, so the
// patch becomes k four-sided patches, as the kite layout fills the 4g-gon (Pietroni et al. 2021,
// QuadWild, fill 3- to 6-sided patches with such patterns).
#include <string>
#include <vector>

#include "igm/layout/surface_layout.h"

namespace igm {

/// A patch of a SurfaceLayout with k corners: its triangles are those with triangle_patch ==
/// patch; `sides` is its boundary, counter-clockwise (the patch on the left), as k sides from
/// corner to corner, each a non-empty list of arc uses. `turns`: per side, the patch's angle at
/// the corner it starts from, in quarter turns: 1 (convex) or 3 (reflex); empty = all 1.
struct PolygonPatch {
  int patch = -1;
  std::vector<std::vector<ArcUse>> sides;
  std::vector<int> turns;
};

struct PolygonPatternOptions {
  /// Rounds of refining a patch's triangles where its interior has no room for k disjoint paths
  /// (centroid splits where it has no interior vertex, else midpoint splits of its interior edges).
  int max_refine_rounds = 4;
};

struct PolygonPatternStats {
  int patterns = 0;       // patches filled
  int split_edges = 0;    // side edges split at their midpoint (a side of one edge)
  int split_arcs = 0;     // arcs cut in two at a side's middle node
  int reflex_cuts = 0;    // polygons with a reflex corner cut in two
  int refine_rounds = 0;  // summed over the patches
  int added_vertices = 0;
};

/// Fills every polygon patch with the k-quad pattern:
/// - a node m_s near the middle of every side s (the side's vertex nearest half its length in 3D,
///   met once on the patch's boundary; a side without one gets its middle edge split at the exact
///   midpoint); an arc through m_s is cut in two there, in every patch that uses it;
/// - a centre c, the interior vertex whose largest hop distance to the m_s is smallest (ties: the
///   smaller sum, then the smaller id);
/// - k vertex-disjoint paths along surface edges from c to the m_s through the patch's interior (a
///   unit-capacity max flow: k augmenting breadth-first searches); in a disk they leave c in the
///   order of the sides;
/// - patch j of the pattern: corner j, m_j, c, m_{j-1}, a four-sided LayoutPatch. The first keeps
///   the polygon's patch id, the others are appended. c is a node of valence k (a cone for k != 4),
///   each m_s a T-junction for the neighbouring patch.
/// A polygon with one reflex corner r (three quarter turns; then 5 convex corners for a disk
/// without a cone inside) is first cut by one path from r through its interior to the middle node
/// of a side that leaves four corners on each part (r keeps one quarter turn on one part, two on
/// the other; of the two such sides the one whose middle is nearer r in 3D); a part with 3, 5 or 6
/// corners then gets the pattern. Two or more reflex corners are refused.
/// Where a patch's interior has no room (fewer than k disjoint paths), its triangles are refined
/// (centroid splits where it has no interior vertex, else midpoint splits of its interior edges,
/// red-green), at most options.max_refine_rounds rounds. New vertices are exact midpoints and
/// centroids of refined edges and faces (mesh/surface_point.h); every decision is combinatorial
/// except which side vertex is nearest the middle (doubles; any choice gives a valid layout).
/// Pre: `layout` is valid (check_surface_layout) apart from the polygon patches' LayoutPatch
/// entries, which are ignored and replaced; 3 <= k <= 6. Returns "" (the layout then passes
/// check_surface_layout, checked) or why a patch could not be filled, naming it (the layout is then
/// unspecified). Cost per patch: O(T + V) per refinement round and O(k (T + V)) for the paths, T
/// and V the layout's triangles and vertices.
std::string fill_polygon_patches(SurfaceLayout& layout, const std::vector<PolygonPatch>& polygons,
                                 const PolygonPatternOptions& options = {}, PolygonPatternStats* stats = nullptr);

}  // namespace igm
