#pragma once
// The field-driven quad layout (docs/field.md): the motorcycle graph of a cross field's
// separatrices (field/motorcycle.h) inserted exactly into the input mesh, cut into arcs at its
// nodes, and the patches it bounds, each checked to be a topological disk with four corners (the
// points where its boundary turns a quarter in the field; a disk of 3, 5 or 6 corners gets the
// k-quad pattern, layout/polygon_pattern.h), as a SurfaceLayout for the back end
// (layout/surface_layout.h). A patch that is not a disk gets a seed vertex inside it whose four
// field directions are traced too, and the graph is traced again, a bounded number of rounds.
#include <string>
#include <vector>

#include "igm/field/motorcycle.h"
#include "igm/layout/surface_layout.h"
#include "igm/mesh/trimesh.h"

namespace igm {

struct FieldLayoutOptions {
  TraceOptions trace;
  /// Rounds of seeding patches that are not disks (each round traces the whole graph again).
  int max_seed_rounds = 4;
  /// Rounds of leaving out the rays of curves that could not end well (each round traces the whole
  /// graph again), as long as every vertex keeps its angles at most two quarter turns.
  int max_ban_rounds = 8;
  /// A patch that is a disk with 3, 5 or 6 corners (every angle a quarter or a half turn) is filled
  /// with the k-quad pattern (layout/polygon_pattern.h: a node of valence k inside it), and a disk
  /// with one corner of three quarter turns is cut in two from it, instead of failing the layout.
  bool polygon_patterns = true;
};

struct FieldLayoutStats {
  TraceStats trace;
  int rounds = 0;           // tracing rounds run (1 + seeding rounds)
  int seeds = 0;            // seed vertices added
  int banned_rays = 0;      // rays left out
  int nodes = 0, arcs = 0, patches = 0;
  int t_junctions = 0;      // arc ends inside another patch's side
  int non_disk_patches = 0;       // in the last round
  int bad_corner_patches = 0;     // disks whose corners are not four quarter turns (last round)
  int pattern_patches = 0;        // disks of 3, 5 or 6 corners filled with the k-quad pattern
  int reflex_cuts = 0;            // disks with one corner of three quarter turns cut in two
  int pattern_vertices = 0;       // vertices the patterns added (side midpoints, refinement)
  int contradicting_patches = 0;  // patches whose side lengths cannot all be equal (last failed round)
  int refined_vertices = 0, refined_triangles = 0;
  double seconds = 0;
};

struct FieldLayoutResult {
  bool ok = false;
  std::string failure;   // why there is no layout (ok == false): a sentence naming the element
  SurfaceLayout layout;  // with ok
  TraceGraph graph;      // the last round's curves
  /// Without a layout because side lengths contradict each other (the last round's failure): the
  /// input vertices on the sides of the contradicting patches, ascending; empty otherwise.
  std::vector<int> contradicting_vertices;
  /// Without a layout: the input vertices at the last round's patch corners whose angle is not a
  /// quarter or a half turn (for a corner inside an input face or edge, that element's vertices),
  /// ascending; empty when there was none.
  std::vector<int> bad_angle_vertices;
  FieldLayoutStats stats;
};

/// The layout of the cross field given by one direction per face (motorcycle.h) on a connected
/// orientable surface (`mesh` built with allow_boundary where it has boundary loops), whose
/// vertex positions are `positions`. Every decision on the layout's topology (which segments
/// meet, the cells of each face, patch connectivity, corners) is exact; the result passes the
/// independent check_surface_layout. Never throws for a layout it cannot build: returns ok ==
/// false with the reason (a curve that ends dangling, a patch that stays a non-disk or whose
/// corners are not four quarter turns, a vertex whose rays are undefined; with
/// options.trace.stop_at_stuck_wall, a wall that could not be drawn, right after the walls). Throws
/// igm::Error(InvalidArgument) for sizes that do not match. Cost: rounds x (tracing + O(F)
/// insertion + O(k^3) per face with k points on it).
FieldLayoutResult build_field_layout(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                     const std::vector<Vec3d>& face_direction, const FieldLayoutOptions& options = {});

}  // namespace igm
