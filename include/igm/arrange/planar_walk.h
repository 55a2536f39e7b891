#pragma once
// Planar triangulations with exact rational coordinates, their adjacency, and the exact
// straight-line walk used for point location and segment insertion (arrange/overlay,
// extract/quad_extract). Every decision is an exact orient2d or an exact dot-product sign.
#include <array>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

/// A triangulated planar region: corner triples index `positions`, counter-clockwise.
struct PlanarTriangulation {
  std::vector<Point2q> positions;
  std::vector<std::array<int, 3>> triangles;
};

/// Neighbour and vertex-star tables of a PlanarTriangulation. Edge i of triangle t runs from
/// corner i to corner (i+1)%3; neighbor[t][i] is the triangle across it or -1 on the boundary.
struct PlanarAdjacency {
  std::vector<std::array<int, 3>> neighbor;
  std::vector<std::array<int, 3>> neighbor_edge;  // edge index of edge i of t inside neighbor[t][i]
  std::vector<int> star_begin;                    // CSR: triangles around vertex v are
  std::vector<int> star;                          // star[star_begin[v] .. star_begin[v+1])

  /// Builds the tables. Throws igm::Error(IndexOutOfRange) for a bad corner index,
  /// RepeatedVertex for a triangle using a vertex twice, NonManifoldEdge if an edge has more
  /// than two triangles or two triangles traverse it in the same direction. Cost O(F log F).
  static PlanarAdjacency build(int num_vertices, const std::vector<std::array<int, 3>>& triangles);
};

/// Where a point lies: at corner `index` of `triangle` (Vertex), in the relative interior of
/// edge `index` of `triangle` (Edge), or in the interior of `triangle` (Face).
struct PlanarLocation {
  enum class Kind { Vertex, Edge, Face };
  Kind kind = Kind::Face;
  int triangle = -1;
  int index = 0;
};

/// One step of a walk: the open piece of the walked segment before the next point lies in the
/// interior of a triangle (medium Face, `triangle`) or in the relative interior of an edge
/// (medium Edge, edge `edge` of `triangle`); then the walk reaches `next`: a mesh vertex
/// (`vertex`), a transversal crossing of the interior of edge `edge` of `triangle` (Crossing),
/// or the end point (End).
struct WalkStep {
  enum class Medium { Face, Edge };
  enum class Next { Vertex, Crossing, End };
  Medium medium = Medium::Face;
  int triangle = -1;
  int edge = -1;
  Next next = Next::End;
  int vertex = -1;
  int cross_triangle = -1;
  int cross_edge = -1;
};

/// Walks the straight segment from p to q through the triangulation, starting from `start`,
/// the location of p. Appends the steps to `steps` (if not null) and returns the location of q.
/// Pre: triangles positive, the region convex (a walk that would leave it throws
/// igm::Error(InvalidArgument) "leaves the triangulated region"). Exact: predicates only use
/// p, q and mesh vertex positions (never constructed crossing points). Cost O(deg(v) per vertex
/// passed + 1 per triangle crossed); the loop is bounded by #vertices + #triangles + 2 steps.
PlanarLocation walk_segment(const std::vector<Point2q>& positions, const std::vector<std::array<int, 3>>& triangles,
                            const PlanarAdjacency& adjacency, const PlanarLocation& start, const Point2q& p,
                            const Point2q& q, std::vector<WalkStep>* steps);

/// Point location by a straight walk from vertex `from` (which must be used by a triangle).
/// Same pre-conditions and cost as walk_segment.
PlanarLocation locate_point(const std::vector<Point2q>& positions, const std::vector<std::array<int, 3>>& triangles,
                            const PlanarAdjacency& adjacency, int from, const Point2q& q);


/// Exact helpers.
Rational cross(const Point2q& o, const Point2q& a, const Point2q& b);  // (a-o) x (b-o)
Rational dot(const Point2q& o, const Point2q& a, const Point2q& b);    // (a-o) . (b-o)
bool same_point(const Point2q& a, const Point2q& b);
struct Point2qLess {
  bool operator()(const Point2q& a, const Point2q& b) const {
    const int c = cmp(a.x, b.x);
    return c != 0 ? c < 0 : cmp(a.y, b.y) < 0;
  }
};

}  // namespace igm
