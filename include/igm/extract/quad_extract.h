#pragma once
// Planar quad extraction (paper §6.2): the N x N grid of every layout quad, each grid point
// located exactly in the refined triangulation through the piecewise-affine UV charts.
#include <array>
#include <vector>

#include "igm/arrange/overlay.h"
#include "igm/arrange/quad_template.h"
#include "igm/igm/quad_charts.h"

namespace igm {

/// How the polygon's sides are glued: side s (corner s -> corner s+1) is glued to partner[s];
/// if reversed[s], the point at parameter u along s is the point at 1-u along partner[s].
struct SidePairing {
  std::vector<int> partner;
  std::vector<char> reversed;
  /// a1 b1 a1^-1 b1^-1 ...: side 4i <-> 4i+2 and 4i+1 <-> 4i+3, both reversed.
  static SidePairing canonical(int genus);
};

/// A quad-mesh vertex: a point of the refined triangulation given as an output triangle of the
/// overlay and exact barycentric coordinates w.r.t. its corners (the same in the plane and in
/// UV: the chart is affine on the triangle), its planar position, and the layout vertex it is
/// (-1 if none). A vertex on glued sides is given by one of its copies.
struct QuadVertexLocation {
  int triangle = -1;
  std::array<Rational, 3> barycentric;
  Point2q position;
  int layout_vertex = -1;
};

struct PlanarQuadMesh {
  std::vector<std::array<int, 4>> quads;  // counter-clockwise (in UV and in the plane)
  /// Per quad: edge k (from quads[f][k] to quads[f][k+1]) as an edge id 0..num_edges-1. At
  /// N = 1 and 2 the root carries loops and multi-edges (e.g. a side at N = 1 joins the root to
  /// itself), so edges are NOT determined by their end vertices; these ids are.
  std::vector<std::array<int, 4>> quad_edges;
  int num_edges = 0;
  std::vector<int> layout_quad;           // per quad: the layout quad it subdivides
  std::vector<QuadVertexLocation> vertices;
};

/// Extracts the quad mesh at resolution N >= 1: grid point (i/N, j/N) of layout quad q is
/// located by a straight walk in the UV triangulation of q (exact). Vertices are shared along
/// layout edges, at layout vertices (all polygon corners are one vertex, the root) and across
/// glued sides (per `pairing`). Result: 5g N^2 quads (N^2 for g = 1); at N = 1, 2+3g vertices.
/// Errors: InvalidArgument for N < 1, N > 4096 or a pairing that is not a fixed-point-free
/// involution on the 4g sides; Internal if a grid point cannot be located. Cost
/// O(F log F + sum over grid points of walk length).
PlanarQuadMesh extract_quads(const QuadTemplate& t, const OverlayResult& overlay, const QuadCharts& charts, int resolution,
                             const SidePairing& pairing);

}  // namespace igm
