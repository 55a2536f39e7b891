#pragma once
// Exact overlay of non-crossing segments on a planar triangulation of a convex polygon
// (paper §4.2: "an arrangement between the polygonal schema and the quad template [CLSA20],
// splitting mesh edges to resolve intersections"), with rational coordinates throughout.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "igm/arrange/planar_walk.h"

namespace igm {

struct Segment2 {
  Point2q a, b;
};

/// Where an output vertex lies in the input: the input vertex it is (input_vertex >= 0,
/// input_triangle = -1), or exact barycentric coordinates w.r.t. the corners
/// (triangles[input_triangle][0..2]) of an input triangle (input_vertex = -1). Points on an
/// input edge have one zero coordinate (either adjacent triangle may be named).
struct VertexOrigin {
  int input_vertex = -1;
  int input_triangle = -1;
  std::array<Rational, 3> barycentric;
};

struct OverlayOptions {
  bool validate_input = true;  // check positivity, manifoldness and a convex simple boundary: O(F log F)
  /// A cap on the output's triangles (0: none). Every new point adds at least one triangle, so
  /// the walk stops with igm::Error(Unsupported) as soon as input triangles + new points pass it,
  /// before the retriangulation, and the output is checked against it at the end: the result has
  /// at most max_triangles triangles or there is none. (The pipeline's memory limit.)
  std::size_t max_triangles = 0;
};

struct OverlayStats {
  std::size_t crossings = 0;          // transversal segment / input-edge crossings
  std::size_t endpoint_vertices = 0;  // distinct segment endpoints that are new vertices
  std::size_t split_triangles = 0;    // input triangles that were refined
  std::size_t local_flips = 0;        // edge flips inside refined input triangles
  std::size_t max_local_points = 0;   // max over input triangles of points on/in it (k_T)
  std::size_t max_local_pieces = 0;   // max over input triangles of segment pieces inside it
  std::size_t max_coordinate_bits = 0;  // max bit_size over output vertex coordinates
};

struct OverlayResult {
  PlanarTriangulation mesh;               // vertices 0..n_in-1 are the input vertices, same ids
  std::vector<int> input_triangle;        // per output triangle: the input triangle containing it
  std::vector<VertexOrigin> origin;       // per output vertex
  std::vector<std::vector<int>> chains;   // per segment: output vertices along it, from a to b
  OverlayStats stats;
};

/// Refines `mesh` so that every segment is a chain of edges.
///
/// Pre: `mesh` triangulates a convex polygon: every triangle strictly counter-clockwise (exact),
/// every edge in at most two triangles, one boundary loop (checked when validate_input, else
/// assumed). Segments have distinct endpoints inside the closed polygon and pairwise meet at
/// most in a shared endpoint. Violations throw igm::Error(InvalidArgument) naming the segment(s)
/// (crossing segments, a segment through another's endpoint, overlapping segments, a segment
/// leaving the polygon, a zero-length segment); bad triangles throw as PlanarAdjacency::build
/// or InvalidArgument (non-positive triangle, naming it).
///
/// Method: the input is never modified while walking. Each segment is walked through the input
/// triangulation (walk_segment); its crossings with input edges become vertices whose exact
/// coordinates are the intersection of the segment with the INPUT edge (so coordinates have
/// bounded size: they never depend on other crossings, and every output vertex is an input
/// vertex, a segment end point, or one segment/input-edge intersection). Then every input
/// triangle T with points on its edges or inside is retriangulated on its own, so every output
/// triangle lies inside one input triangle:
///  - no end point inside T: the pieces are chords and cut T into convex cells; the boundary
///    polygon is split along each chord and each cell triangulated by clipping strictly convex
///    corners (no flips; O(k_T^2) integer work, O(k_T) orientations);
///  - otherwise: end points by face/edge splits, edge points by edge splits (most-used piece
///    ends first), pieces by exact edge flips (Sloan 1993); O(k_T^2) flips worst case.
///
/// Past OverlayOptions::max_triangles: igm::Error(Unsupported) with the count reached.
/// Post: every output triangle strictly positive; a manifold triangulation of the same polygon
/// (same area, Euler characteristic 1, same boundary vertices plus segment end points lying on
/// the boundary); each segment's chain consists of output edges, in order.
/// Cost: O(F log F) validation + O(sum over segments of walk length) + point location walks for
/// the distinct end points + sum over refined input triangles of the local work above (k_T =
/// points on/in T; small unless many segments cross one input triangle).
OverlayResult overlay_segments(const PlanarTriangulation& mesh, const std::vector<Segment2>& segments,
                               const OverlayOptions& options = {});

/// A point of output triangle `t` with barycentric coordinates `b` (w.r.t. t's corners),
/// expressed in the input: the input triangle containing t and exact barycentric coordinates
/// w.r.t. its corners (for composing with the input's 3D positions). Cost O(1) rational ops.
struct InputPoint {
  int input_triangle = -1;
  std::array<Rational, 3> barycentric;
};
InputPoint to_input(const PlanarTriangulation& input, const OverlayResult& result, int t, const std::array<Rational, 3>& b);

/// Independent check of every post-condition of overlay_segments (for tests and debugging):
/// positivity, manifoldness, Euler characteristic 1, area equal to the input's, each triangle
/// inside its input triangle, every origin reproducing the vertex position exactly, every chain
/// made of edges lying on its segment in order. Returns "" or a description. Cost O(F log F).
std::string check_overlay(const PlanarTriangulation& input, const std::vector<Segment2>& segments,
                          const OverlayResult& result);

}  // namespace igm
