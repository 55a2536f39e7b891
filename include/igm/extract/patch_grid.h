#pragma once
// The quad mesh of a sized layout's IGM (igm/patch_maps.h): the a x b unit grid of every layout
// quad's rectangle, each grid point located exactly in the patch's UV triangulation; vertices
// shared along layout edges (by their integer position along the surface edge), at layout vertices
// and across glued polygon sides.
#include <array>
#include <vector>

#include "igm/igm/patch_mesh.h"
#include "igm/layout/sizing.h"

namespace igm {

/// A quad-mesh vertex: a point of patch-mesh triangle `triangle` with exact barycentric
/// coordinates w.r.t. its corners (the same in UV and on the surface: the map is affine on the
/// triangle), and the layout vertex it is (-1 if none).
struct GridVertex {
  int triangle = -1;
  std::array<Rational, 3> barycentric;
  int layout_vertex = -1;
};

struct PatchGrid {
  std::vector<std::array<int, 4>> quads;  // counter-clockwise
  std::vector<int> quad_patch;            // per quad: its layout quad
  std::vector<GridVertex> vertices;
};

/// Extracts the grid: grid point (i, j) of layout quad q, 0 <= i <= a, 0 <= j <= b, is found by an
/// exact straight walk in the UV triangulation of q's patch (extract/ uses arrange/planar_walk.h).
/// Result: sum of a b quads over the layout quads. Pre: `corner_uv` maps every patch onto its
/// rectangle (map_patches). Throws igm::Error(Internal) if a grid point cannot be located.
/// Cost O(F log F + sum over grid points of walk length) exact predicates.
PatchGrid extract_patch_grids(const QuadLayout& layout, const PatchMesh& mesh, const Sizing& sizing,
                              const std::vector<std::array<Point2q, 3>>& corner_uv);

}  // namespace igm
