#pragma once
// Certification in plain doubles: a map given by one UV per vertex (seamless.h) is placed on a
// dyadic grid fine enough that every vertex UV x_v and every copy T_c(x_v) = R^k x_v + t of it
// is exactly a double. Integers are on every grid: cones, boundary corners and the isoline
// coordinate of sliding boundary vertices (seamless.h) keep their exact values. Rounding the
// vertex UVs to the grid and rebuilding every corner from its vertex keeps every transition
// exact: the two UVs of an edge end in its two faces are T_c(x_v) and T_c'(x_v) = M(T_c(x_v))
// for the edge's transition M, whatever x_v is (at a regular vertex the fan closes up with the
// identity; a cone keeps its integer point). Cones stay at their integer points; so the rounded
// map is a valid IGM iff every UV triangle is still strictly positive, every boundary edge still
// on its isoline and every vertex keeps its angle (regular vertices stay regular, cones keep
// their index), which is checked exactly (check_map). Used for smoothed maps (smooth.h) and for exact
// maps, so that a doubles file (write_igm_obj) certifies too.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "igm/smooth/seamless.h"

namespace igm {

/// The grid of spacing 2^exponent (exponent <= 0) for vertex UVs with |x|, |y| <= bound (a power
/// of two): any multiple of the spacing within the bound, and each of its copies R^k x + t under
/// the structure's corner motions, is exactly a double (|R^k x + t| < 2^(exponent + 53)).
struct DyadicGrid {
  int exponent = 0;
  double bound = 0;
};

/// A corner motion with its translation exactly as doubles (GridMotion with |t| < 2^53).
struct GridMotionD {
  int k = 0;
  double tx = 0, ty = 0;
};

/// R^k p + t in doubles: exact whenever the exact result is a double (on a DyadicGrid it is).
Vec2d apply(const GridMotionD& m, const Vec2d& p);

/// A map given by one double UV per vertex on a grid: corner c of vertex v is
/// apply(corner_motion[c], vertex_uv[v]), exactly.
struct GridMap {
  DyadicGrid grid;
  std::vector<GridMotionD> corner_motion;  // per corner (half-edge of SeamlessStructure::mesh)
  std::vector<Vec2d> vertex_uv;            // per vertex, on the grid, within the bound
};

/// The grid for `s`: bound = the least power of two >= 8 max(1, max |coordinate of x_v|) (room for
/// the vertices to move: a smoothed vertex may leave its reference chart's layout quad), spacing
/// 2^(e - 53) with 2^e > bound + max |t| over the corner motions (for the pipeline's maps, whose
/// UVs lie in [0, 1]^2: 2^-49 or so); and the structure's vertex UVs rounded to it (nearest
/// multiple, halves rounded up; cones are integer points, kept exactly). nullopt when no such grid
/// exists: a translation of 2^51 or a vertex UV of 2^48 or more in magnitude. Cost O(F) (the
/// rationals' sizes aside).
std::optional<GridMap> round_to_grid(const SeamlessStructure& s);

/// x rounded to the nearest multiple of 2^grid.exponent (ties to even); nullopt when the result is
/// beyond grid.bound or x is not finite.
std::optional<double> round_to_grid(double x, const DyadicGrid& grid);

/// Every corner UV of `map` (three per face of s.mesh, in face order), exact doubles.
void grid_corners(const SeamlessStructure& s, const GridMap& map,
                  std::vector<std::array<Vec2d, 3>>& corners);
/// The same with the vertex UVs `vertex_uv` (one per vertex, on map.grid) in place of map's.
void grid_corners(const SeamlessStructure& s, const GridMap& map, const std::vector<Vec2d>& vertex_uv,
                  std::vector<std::array<Vec2d, 3>>& corners);

/// The exact checks that make a map rebuilt from vertex UVs (grid_corners) a valid IGM, all else
/// holding by construction (see the top of this file): every UV triangle strictly positive
/// (orient2d on the doubles), then every boundary edge on its isoline (the structure's
/// BoundaryIsoline: exact equality of doubles with its integer), then every vertex's angle the
/// structure's (angle_indices, seamless.h). Orientation alone does not fix the angles of a map
/// that jumped (rounding, a Newton step): a vertex's link could wind around it once more, and a
/// cone once less. A boundary edge stays on its isoline when its ends keep their fixed coordinates
/// (the structure's cones, boundary corners and sliding coordinates): the check is a second line.
/// Cost O(F).
struct MapCheck {
  int nonpositive = 0;           // triangles not strictly positive
  int first_nonpositive = -1;    // the first of them (-1: none)
  int off_isoline = 0;           // boundary edges off their isoline (checked only when every
  int first_off_isoline = -1;    // triangle is positive): the first one's half-edge
  int angles_changed = 0;        // vertices whose angle is not the structure's (checked only when
  int first_angle_changed = -1;  // every triangle is positive and every boundary edge on its line)
  bool valid() const { return nonpositive == 0 && off_isoline == 0 && angles_changed == 0; }
};
MapCheck check_map(const SeamlessStructure& s, const std::vector<std::array<Vec2d, 3>>& corners);

/// The corners as exact rationals (every coordinate's exact value). Pre: finite.
std::vector<std::array<Point2q, 3>> to_exact(const std::vector<std::array<Vec2d, 3>>& corners);

/// Largest bit_size (rational.h) of a coordinate.
std::size_t max_uv_bits(const std::vector<std::array<Point2q, 3>>& corner_uv);

struct DyadicStats {
  bool on_grid = false;         // the returned UVs are the rounded map: every coordinate a double
  int grid_exponent = 0;        // the grid's spacing is 2^grid_exponent (when a grid exists)
  int nonpositive = 0;          // triangles that rounding made non-positive (then on_grid is false)
  int first_nonpositive = -1;   // the first of them
  int off_isoline = 0;          // boundary edges rounding moved off their isolines (never: a check)
  int angles_changed = 0;       // vertices whose angle rounding changed (then on_grid is false)
  std::size_t max_uv_bits = 0;  // largest bit_size of a returned UV coordinate
  std::string reason;           // why the map stayed exact (empty when on_grid)
};

struct DyadicResult {
  /// Three per face: the rounded map when stats.on_grid (certified: every triangle strictly
  /// positive by exact orient2d, every angle the input's, transitions and cones as in the input
  /// by construction), else a copy of the input's exact UVs.
  std::vector<std::array<Point2q, 3>> corner_uv;
  DyadicStats stats;
};

/// round_to_grid and check_map together: `map` the grid map of `s` (nullopt if none exists) and
/// `corners` its corner UVs; stats.on_grid when the rounded map passes the checks, else the stats
/// say why (max_uv_bits is left 0). Cost O(F).
DyadicStats place_on_grid(const SeamlessStructure& s, std::optional<GridMap>& map,
                          std::vector<std::array<Vec2d, 3>>& corners);

/// Places the exact map `igm` on its dyadic grid (round_to_grid) and certifies it (check_map);
/// where no grid exists or the rounded map fails a check the map stays exact and the stats say why.
/// Pre: `igm` is a valid IGM (seamless_structure throws igm::Error otherwise).
/// Cost: seamless_structure plus O(F).
DyadicResult round_to_dyadic(const IgmMesh& igm);
/// The same with the structure already derived from `igm`.
DyadicResult round_to_dyadic(const IgmMesh& igm, const SeamlessStructure& s);

}  // namespace igm
