#pragma once
// The IGM of a quantized surface layout (layout/surface_layout.h): every patch, cut along its arcs
// into a disk, mapped exactly and one-to-one onto its integer rectangle by a certified Tutte map,
// the same parameters on both sides of every arc, so that every seam's transition is a rotation by
// a multiple of 90 degrees plus an integer translation. The one back end of every layout.
#include <array>
#include <vector>

#include "igm/embed/tutte.h"
#include "igm/embed/weights.h"
#include "igm/igm/patch_maps.h"
#include "igm/layout/surface_layout.h"
#include "igm/output/igm_mesh.h"

namespace igm {

struct LayoutMapOptions {
  WeightKind weights = WeightKind::MeanValue;
  /// Arc-length parameters along arcs are multiples of 2^-parameter_bits (1..52): with 32 bits and
  /// lengths below 2^20 every boundary coordinate is exactly a double.
  int parameter_bits = 32;
  /// 3D lengths and weights are computed on the positions times this (mesh/scale.h).
  double length_scale = 1;
  TutteOptions tutte;
};

struct LayoutMap {
  /// The layout's refined surface, further refined by the splits (their vertices and triangles
  /// appended, patch by patch), with the map's exact corner UVs; input vertices first.
  IgmMesh igm;
  /// Per output triangle: its patch.
  std::vector<int> triangle_patch;
  /// Per patch: its rectangle (a, b) = (length of sides 0 and 2, of sides 1 and 3).
  std::vector<std::array<int, 2>> patch_size;
  PatchMapStats stats;
};

/// Maps every patch of `layout` (check_surface_layout must accept it: InvalidArgument with the
/// violation otherwise) with arc lengths `arc_length` (one integer >= 1 per arc, opposite sides of
/// every patch of equal sums: InvalidArgument naming the patch otherwise) onto [0,a] x [0,b]:
/// corner k of the patch to corner k of the rectangle ((0,0), (a,0), (a,b), (0,b)), the arcs of
/// side k one after the other on their integer segments of the rectangle's side k, every arc
/// vertex at its arc-length parameter (arc_length_parameters of the 3D lengths along the arc,
/// computed once per arc, mirrored as 1 - t for a backward use), the interior by a Tutte map with
/// positive weights from the patch's 3D triangles (edge_weights, tutte_embed). Before the map, every
/// interior edge of a patch disk joining two vertices on one side of it (a corner lies on two) is
/// split at its exact midpoint (both triangles, one patch), so that tutte_embed's pre-conditions
/// hold; the new vertices get exact locations (lerp of the ends' locations) and are numbered after
/// the layout's, patch by patch (each patch's in the order of its local vertex pairs).
/// Post (checked exactly by tutte_embed): every UV triangle strictly positive; arc ends at integer
/// points; both sides of every arc at the same parameters (the certifier checks the transitions).
/// Taken by value: pass std::move(layout) to let the output take its vertices and triangles.
/// Each patch is mapped on its own (no shared mutable state; results in per-patch slots).
/// Throws igm::Error(InvalidArgument) as above or for a bad option, Internal if a map fails.
/// Cost: check_surface_layout, then one certified Tutte solve per patch (embed/tutte.h).
LayoutMap map_layout(SurfaceLayout layout, const std::vector<int>& arc_length, const LayoutMapOptions& options = {});

}  // namespace igm
