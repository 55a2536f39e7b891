#pragma once
// The IGM's triangle mesh before its UVs: the overlay of a quad layout on the embedded disk
// (arrange/overlay.h), glued back into a refinement of the input surface, each triangle labelled
// with its layout quad ("patch"), each layout edge with its chain of vertices. As a surface layout
// (to_surface_layout) it is mapped by map_layout (igm/layout_map.h); the paper's affine maps
// (igm/patch_maps.h) and the rectangles' grids (extract/patch_grid.h) are computed on it directly.
#include <array>
#include <vector>

#include "igm/arrange/overlay.h"
#include "igm/layout/quad_layout.h"
#include "igm/layout/surface_layout.h"
#include "igm/mesh/surface_point.h"

namespace igm {

/// Vertices are numbered twice: "plane ids" are the overlay's vertices (a disk: the glued polygon
/// sides carry two copies of each vertex on them) followed by the vertices split into patches, and
/// "surface ids" (vertex_of[plane id]) number the glued surface: the input vertices first, then
/// the topology stage's constructed points, then the overlay's and the splits' new points.
struct PatchMesh {
  std::vector<SurfacePoint> locations;          // per surface vertex: exact point of the input surface
  std::vector<Vec3d> positions;                 // per surface vertex: evaluate(location)
  std::vector<int> vertex_of;                   // plane id -> surface id
  std::vector<std::array<int, 3>> triangles;    // plane ids, counter-clockwise in the plane
  std::vector<int> triangle_quad;               // per triangle: its layout quad
  /// Per triangle corner: its overlay vertex (a plane id below num_overlay_vertices), or -1 for a
  /// vertex split into a patch (the affine maps need plane positions; split vertices have none).
  int num_overlay_vertices = 0;
  /// Per layout edge (QuadLayout::edges): plane ids along it from edge.a to edge.b.
  std::vector<std::vector<int>> edge_chain;
  /// Per layout point: a plane id of it (a side point has two copies: the one on its own side).
  std::vector<int> point_vertex;
};

struct PatchMeshInput {
  const QuadLayout* layout = nullptr;
  /// overlay_segments(disk, segments) with segments[e] = layout edge e (from points[a] to points[b])
  /// for every layout edge e, optionally followed by further segments inside quads (diagonals).
  const OverlayResult* overlay = nullptr;
  int num_disk_vertices = 0;                          // overlay vertices below are disk vertices
  const std::vector<int>* disk_to_surface = nullptr;  // disk vertex -> surface vertex
  const std::vector<std::array<int, 3>>* disk_triangles = nullptr;  // the overlay's input triangles
  /// The surface's vertex locations (input vertices, then constructed points): moved into the result.
  std::vector<SurfacePoint> surface_locations;
  const std::vector<Vec3d>* input_positions = nullptr;
};

/// Builds the patch mesh: surface ids for the overlay's vertices (a disk vertex is its surface
/// vertex; a new point on a polygon side is one vertex with the point it is glued to on the mate
/// side, checked to be the same exact surface point; every other new point is a vertex of its own),
/// every triangle's layout quad (a flood fill bounded by the layout edges' chains) and every layout
/// edge's chain. Edges that break the Tutte maps' pre-conditions are split by map_layout
/// (igm/layout_map.h), not here. Checks that glued chains carry the same surface vertices in
/// opposite orders. Throws igm::Error(InvalidArgument) if the overlay does not match the layout,
/// Internal if an invariant breaks. Cost O(F log F) plus the exact locations (O(1) GMP operations
/// per new vertex).
PatchMesh build_patch_mesh(PatchMeshInput input);

/// The patch mesh of a canonical layout as a surface layout (the one input of map_layout,
/// igm/layout_map.h): the same triangles in the same order over surface ids, the vertices no
/// triangle uses dropped (an open surface's filling; the others keep their order, the first
/// `num_input_vertices` being the input's), patch q = layout quad q with its sides k = its edges
/// k, arc s = surface edge s (QuadLayout::surface_edge: a glued pair of polygon side pieces is one
/// arc; its vertices in the direction of the surface edge), so that a Sizing's edge_count is the
/// arcs' lengths. Moves mesh.locations and mesh.positions into the result (left empty); the rest
/// of `mesh` stays as it was (extract_patch_grids reads its triangles). Pre: build_patch_mesh's
/// output for `layout`. Cost O(F + V).
SurfaceLayout to_surface_layout(const QuadLayout& layout, PatchMesh& mesh, int num_input_vertices);

/// The 3D length of every surface edge of the layout (QuadLayout::surface_edge): the length of the
/// polyline of its chain's positions, multiplied by `scale` (mesh/scale.h). O(vertices on layout
/// edges).
std::vector<double> layout_edge_lengths(const QuadLayout& layout, const PatchMesh& mesh, double scale = 1);

}  // namespace igm
