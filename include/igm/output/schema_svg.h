#pragma once
// SVG picture of the polygonal schema: the 4g-gon with its sides coloured by loop pair, the
// quad template drawn on top, and the embedded mesh edges faintly underneath. For people only:
// nothing is decided from it.
#include <array>
#include <iosfwd>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

struct SchemaDrawing {
  std::vector<Vec2d> polygon;                          // corners, counter-clockwise
  std::vector<int> side_pair;                          // side s (corner s -> s+1) glues to side_pair[s] (-1: free, dashed grey)
  /// Optional: side s drawn as this polyline (from corner s to corner s+1) instead of a segment
  /// (genus 0: the sides of the orbifold disk are mesh paths, not straight).
  std::vector<std::vector<Vec2d>> side_paths;
  std::vector<std::array<Vec2d, 2>> template_edges;    // layout edges
  std::vector<std::array<Vec2d, 2>> diagonals;         // quad diagonals of the piecewise-affine map (dashed)
  std::vector<std::array<Vec2d, 2>> mesh_edges;        // embedded mesh edges (drawn faintly)
  std::vector<Vec2d> cones;                            // layout vertices (drawn as dots)
};

/// Writes a self-contained SVG (800x800, y up). Mesh edges beyond `max_mesh_edges` are thinned
/// (every k-th drawn) to keep the file small. Cost O(edges).
void write_schema_svg(std::ostream& out, const SchemaDrawing& drawing, std::size_t max_mesh_edges = 200000);

}  // namespace igm
