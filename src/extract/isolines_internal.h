#pragma once
// Internal to extract_isolines (include/igm/extract/isolines.h): the IGM's charts and seams
// (isolines.cpp builds them) and the exact walks along isolines (isolines_trace.cpp).
#include <array>
#include <cstdint>
#include <vector>

#include "igm/exact/predicates.h"
#include "igm/extract/isolines.h"
#include "igm/mesh/trimesh.h"

namespace igm::isolines {

/// Axis direction m (0..3) = R^m (1, 0), R the rotation by +90 degrees: (1,0) (0,1) (-1,0) (0,-1).
inline constexpr int kDx[4] = {1, 0, -1, 0};
inline constexpr int kDy[4] = {0, 1, 0, -1};

/// An integer point of a chart.
struct Grid2 {
  std::int64_t x = 0, y = 0;
};

/// R^k p + t.
inline Grid2 apply(int k, const Grid2& p, const Grid2& t) {
  switch (k & 3) {
    case 0: return {p.x + t.x, p.y + t.y};
    case 1: return {t.x - p.y, t.y + p.x};
    case 2: return {t.x - p.x, t.y - p.y};
    default: return {t.x + p.y, t.y - p.x};
  }
}

/// A corner's UV as floor and integrality per axis: exact comparisons with integers, no GMP.
struct CornerFloor {
  std::int64_t floor[2];
  bool integer[2];
};

/// The certified IGM as the walks need it: half-edges (face f owns 3f..3f+2, half-edge 3f+i from
/// corner i to corner i+1; a boundary half-edge has twin -1) and per half-edge the seam
/// x -> R^k x + t from its face's chart to its twin's face's chart (the identity on the boundary).
struct Charts {
  const std::vector<std::array<int, 3>>* triangles = nullptr;
  const std::vector<std::array<Point2q, 3>>* uv = nullptr;
  TriMesh mesh;
  std::vector<signed char> k;       // per half-edge
  std::vector<Grid2> t;             // per half-edge
  std::vector<int> degree;          // per vertex: its triangles
  std::vector<CornerFloor> floors;  // per corner (= half-edge leaving it)

  const Point2q& corner(int h) const { return (*uv)[h / 3][h % 3]; }
  int vertex(int h) const { return (*triangles)[h / 3][h % 3]; }
};

/// A triangle's corners as integers over a common denominator: X_i = (x_i, y_i) / d, d the least
/// common multiple of the six denominators; total = det(x_1 - x_0, x_2 - x_0) > 0.
struct FaceFrame {
  int face = -1;
  mpz_class d, x[3], y[3], total;
  void set(int f, const std::array<Point2q, 3>& X);
  /// Exact barycentric coordinates of the integer point p: w_i = det(x_{i+1} - d p, x_{i+2} - d p)
  /// / total (integer arithmetic, one gcd per weight; canonical).
  void barycentric(const Grid2& p, std::array<Rational, 3>& w);

 private:
  mpz_class px, py, s1, s2, n[3];
};

/// A grid point as found: the triangle that owns it, where it lies there (GridPointKind and
/// IsolineQuadVertex::local), its integer UV in that triangle's chart.
struct GridPoint {
  int face = -1;
  GridPointKind kind = GridPointKind::Face;
  int local = -1;
  Grid2 uv;
};

/// Every grid point once. face_points[face_begin[f] ..) are the points triangle f owns (inside it,
/// inside a side whose half-edge id is below its twin's, or inside a boundary side), sorted by
/// (y, x) for look-ups; a grid point on a mesh vertex is vertex_point[vertex].
struct GridPoints {
  std::vector<GridPoint> points;
  std::vector<int> vertex_point;  // per mesh vertex: its grid point or -1
  std::vector<int> face_begin, face_points;
  std::int64_t chords = 0;  // integer rows and columns meeting the closed UV triangles
  std::int64_t rows = 0;    // rows scanned
};

/// Step 1: per triangle the integer rows of its bounding box, each row's exact ends, the integer
/// points between (closed); each classified on a corner / inside a side / inside. Checks that
/// every point inside a side is found from the twin's triangle too (through the seam) and every
/// corner on the grid from all its vertex's triangles; igm::Error(Internal) otherwise, and
/// igm::Error(TooLarge) past max_work rows and points. Cost O(F + rows + points) exact integer
/// operations on the corners' numerators.
GridPoints find_grid_points(const Charts& c, std::int64_t max_work);

/// The grid point at the integer point t of triangle g: its corner `corner` if >= 0, else inside
/// its side `side` if >= 0, else inside it; -1 if there is none. O(log points of the triangle).
int find_point(const Charts& c, const GridPoints& gp, int g, int corner, int side, const Grid2& t);

/// Sign of the cross product (a - o) x d_m: > 0 when the axis direction m points to the left
/// of o -> a. Exact (rational comparisons).
int cross_axis(const Point2q& o, const Point2q& a, int m);
/// Sign of the dot product (a - o) . d_m. Exact.
int dot_axis(const Point2q& o, const Point2q& a, int m);
/// Axis direction m lies in the half-open wedge [a - o, b - o) at o (turning counter-clockwise
/// from a - o, by an angle in (0, pi]; b - o may equal -(a - o)). Exact.
bool in_wedge(const Point2q& o, const Point2q& a, const Point2q& b, int m);

/// The axis direction m with a - o = lambda d_m, lambda > 0, or -1 if a - o is not along an axis.
/// Exact.
int axis_of(const Point2q& o, const Point2q& a);

/// A direction at a point: triangle, the point's corner in it (-1 if not a corner), axis m in
/// that triangle's chart, and an integer target point carried along (the trace's end).
struct Heading {
  int face = -1;
  int corner = -1;
  int m = 0;
  Grid2 target;
};

/// Boundary fans: the last corner of a boundary vertex's fan (its side from corner i+2 to corner
/// i is the incoming boundary edge) holds, besides its half-open wedge, the direction along that
/// edge away from the vertex (the fan's closing direction), so that the fan's closed wedge is
/// covered once. Likewise a point inside a boundary side has the closed half-plane.
/// The closing direction of corner `corner` of face `face` if its side from corner+2 to corner is
/// a boundary edge, else -1.
int closing_axis(const Charts& c, int face, int corner);

/// Turns clockwise around vertex corner(3 h.face + h.corner), carrying direction and target
/// across the seams, to the first corner of its fan (whose outgoing side is a boundary edge).
/// Returns false and leaves h as it was at an interior vertex (the ring closes). Bound: the
/// vertex's degree.
bool rewind_to_fan_start(const Charts& c, Heading& h);

/// Turns around mesh vertex corner(3 h.face + h.corner) counter-clockwise, carrying direction and
/// target across the seams, until the triangle whose half-open corner wedge holds the direction
/// (at the end of a boundary fan: or its closing direction); with `unique`, walks the whole ring
/// (a boundary vertex's whole fan, from its first corner) and checks that exactly one wedge holds
/// it. Throws igm::Error(Internal) naming the vertex when none does (a vertex of total angle !=
/// 2 pi met away from a grid point, or a direction out of the surface) or the ring does not
/// close. Bound: twice the vertex's degree.
Heading turn_to_wedge(const Charts& c, Heading h, bool unique);

/// Where a trace ends: the triangle (closed) holding the target, the arrival direction in its
/// chart, and where the target lies there: at corner at.corner (>= 0), else inside side `side`
/// (from corner side to side+1, >= 0), else inside the triangle.
struct TraceEnd {
  Heading at;
  int side = -1;
  std::int64_t steps = 0;
  std::int64_t vertex_crossings = 0;
};

/// Follows the integer isoline from a grid point along `start` (start.m lies in the half-open
/// wedge of start.face at the point, or is its closing direction on the boundary; start.target =
/// point + d_m) until the triangle holding the target. Along a boundary side the isoline may run
/// either way (against the side's direction the triangle is on its right). Throws
/// igm::Error(Internal) naming `what` if the walk leaves the isoline's triangles, leaves the
/// surface across a boundary edge or passes `max_steps` triangles. Cost O(steps) exact
/// comparisons and orient2d.
TraceEnd trace(const Charts& c, Heading start, std::int64_t max_steps, std::int64_t what);

}  // namespace igm::isolines
