#pragma once
// SVG picture of a quad mesh: a shaded orthographic view with the quad edges drawn and the
// vertices whose valence is not 4 marked by a dot coloured by valence, with a colour legend.
// For people only: nothing is decided from it.
#include <cstddef>
#include <iosfwd>
#include <map>

#include "igm/exact/predicates.h"
#include "igm/output/igm_mesh.h"

namespace igm {

struct QuadSvgOptions {
  int size = 800;  // width and height of the picture in pixels (64..16384)
  /// Direction from the mesh towards the viewer; (0, 0, 0): the default, from the principal
  /// axes of the vertex positions (e1 of largest spread, e3 of least, signs fixed so that the
  /// largest component of each is positive): v = e3 + 0.5 e2 + 0.35 e1 normalized, so the mesh
  /// is seen across its flattest axis, turned enough to show depth, e1 running left to right.
  Vec3d view{0, 0, 0};
  /// At most this many quads are drawn. Above it the quads facing away from the viewer are left
  /// out (the orientation is taken from the sign of the enclosed volume), and if still too many,
  /// every k-th of the rest in depth order (k = ceil(count / max_quads)); the legend says so.
  std::size_t max_quads = 200000;
};

struct QuadSvgStats {
  std::size_t quads = 0, quads_drawn = 0;
  std::map<int, std::size_t> irregular;  // valence (not 0 or 4) -> its vertices (marked if drawn)
};

/// Writes a self-contained SVG: the quads as polygons in painter's order (far to near by the
/// mean depth of their corners), each filled with Lambert shading from one light above left of
/// the viewer (ambient 0.3 + 0.7 max(0, n.l), n the normal of the quad's diagonals, flipped
/// towards the viewer), edges stroked; a dot on every vertex whose valence (quads around it) is
/// not 4, drawn right after the nearest quad around it so that nearer quads hide it; a legend
/// (top left) with one entry per valence present and its count. Degenerate or non-finite quads
/// are skipped. Cost O(Q log Q + V) for Q quads, output O(min(Q, max_quads) + V).
QuadSvgStats write_quad_svg(std::ostream& out, const QuadMesh& mesh, const QuadSvgOptions& options = {});

}  // namespace igm
