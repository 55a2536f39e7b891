#pragma once
// Distances from points to a triangle surface, for the two-sided distance of quality.h
// (docs/quality.md, "Two-sided distance"): the nearest point of one triangle, and a bounding-volume
// hierarchy over a triangle set for nearest-point queries. A measurement in double: no decision of
// the pipeline depends on it.
#include <array>
#include <cstddef>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

/// The point of the closed triangle (a, b, c) nearest to p: the orthogonal projection of p onto
/// the triangle's plane when its barycentric coordinates are all >= 0, else the nearest point of
/// the edges beyond which the projection lies (a triangle whose Gram determinant |ab|^2 |ac|^2 -
/// (ab.ac)^2 is not positive in double is taken as the union of its three edges). Evaluated in
/// double: the exact nearest point up to rounding (a few ulps of the coordinates' magnitude, more
/// for slivers). Pre: finite coordinates below 1e150 in magnitude (squares stay finite). O(1).
Vec3d closest_point_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c);

/// A nearest-point query's answer.
struct SurfaceNearest {
  double distance = 0;  // |p - point|; +inf for an empty triangle set
  int triangle = -1;    // the triangle `point` lies on (the constructor's ids), -1 for an empty set
  Vec3d point;
};

/// Bounding-volume hierarchy over a triangle set: the triangles in the Morton order of their
/// centroids (21 bits an axis), each node's range split where the highest bit in which its first
/// and last codes differ turns to 1 (at the middle if they are equal), at most 4 triangles a leaf,
/// axis-aligned boxes (double, containing their triangles' vertices exactly); depth <= 63 +
/// ceil(log2(F)). Keeps a copy of the triangles' corners (72 bytes a triangle).
class TriangleBvh {
 public:
  /// Pre (checked): triangle ids in range (igm::Error(IndexOutOfRange) naming the triangle),
  /// finite coordinates of the vertices used (igm::Error(NonFinite) naming the vertex); for
  /// finite distances, coordinates below 1e150 in magnitude. Cost O(F log F) (1M triangles: about
  /// 0.3 s on the 2-core test machine).
  TriangleBvh(const std::vector<Vec3d>& positions,
              const std::vector<std::array<int, 3>>& triangles);

  std::size_t size() const { return ids_.size(); }

  /// The nearest point to p of the union of the triangles (closest_point_on_triangle on every
  /// triangle a box does not rule out; among equally near triangles, any). `hint`: a triangle id
  /// whose distance bounds the search from the start (a nearby query's answer makes it faster), -1
  /// for none; out of range: igm::Error(InvalidArgument). Cost O(log F) for a point near a
  /// well-spread surface, O(F) at worst.
  SurfaceNearest nearest(const Vec3d& p, int hint = -1) const;

  /// The distance of every point to the triangle set, in the order of `points`: the queries run in
  /// the Morton order of the points, each hinted with the previous answer (the same values as
  /// nearest() up to rounding: a box may rule out a triangle at a few ulps nearer). +inf for an
  /// empty set. Cost O(n log n) for the order, then n queries.
  std::vector<double> distances(const std::vector<Vec3d>& points) const;

 private:
  struct Node {
    double lo[3], hi[3];
    int first;  // leaf: its first triangle slot; inner node: the left child
    int count;  // leaf: its triangles (1..4); inner node: 0, and the right child in `second`
    int second;
    int unused = 0;
  };
  // Squared distance from p to the nearest triangle; `slot` in: the hint slot (-1 none), out: the
  // slot of the nearest triangle; `point` out: the nearest point.
  double query(const Vec3d& p, int& slot, Vec3d& point) const;

  std::vector<std::array<Vec3d, 3>> corners_;  // per slot (leaf order)
  std::vector<int> ids_;                       // per slot: the constructor's triangle id
  std::vector<int> slot_of_;                   // per triangle id: its slot
  std::vector<Node> nodes_;                    // nodes_[0] is the root (if any triangle)
};

}  // namespace igm
