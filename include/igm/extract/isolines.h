#pragma once
// Exact quad extraction from ANY Integer Grid Map the certifier accepts (certify/README.md):
// the quad mesh of its integer isolines, located exactly on the input triangles. Algorithm and
// guarantees: docs/extract.md. Independent of how the IGM was made (igm run, MIQ, ...); the
// pipeline's own quads (extract/quad_extract.h) come from its layout instead.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "certify/certify.h"
#include "igm/exact/predicates.h"
#include "igm/exact/rational.h"

namespace igm {

/// One IGM: a closed oriented triangle mesh with one exact UV per face corner.
struct IsolineInput {
  std::vector<std::array<int, 3>> triangles;      // 0-based vertex ids
  std::vector<std::array<Point2q, 3>> corner_uv;  // per triangle, per corner, exact
  std::vector<Vec3d> positions;  // optional, per vertex; empty: no 3D positions in the output
};

struct IsolineOptions {
  std::size_t max_witnesses = 20;  // of the certifier's report
  /// Work bound of the grid point search: grid points found plus grid rows scanned (each
  /// triangle scans the integer rows of its UV bounding box). Beyond it igm::Error(TooLarge)
  /// (an IGM scaled far beyond what fits in memory: ~0.4 KB per grid point). 1 .. 2^30.
  std::int64_t max_grid_work = std::int64_t{1} << 26;
};

/// Where a grid point lies on its triangle.
enum class GridPointKind { Vertex, Edge, Face };

/// A quad vertex: an integer point of the IGM, given exactly on one triangle containing it.
struct IsolineQuadVertex {
  int triangle = -1;
  /// Exact barycentric coordinates w.r.t. triangles[triangle]'s corners 0, 1, 2: >= 0, sum 1;
  /// the same in UV (the chart is affine on the triangle) and on the surface.
  std::array<Rational, 3> barycentric;
  GridPointKind kind = GridPointKind::Face;
  int local = -1;  // Vertex: the corner 0..2 of `triangle` it is; Edge: the side from corner
                   // local to local+1 (mod 3) it lies inside; Face: -1
  std::array<std::int64_t, 2> uv{};  // its integer UV in the chart of `triangle`
  int valence = 4;  // outgoing isolines: 4, or the index k of a cone (total angle k pi/2)
};

struct IsolineStats {
  std::int64_t grid_points_on_vertices = 0, grid_points_on_edges = 0, grid_points_in_faces = 0;
  std::int64_t cones = 0;             // grid points of valence != 4 (all on vertices)
  std::int64_t rows_scanned = 0;      // grid rows the point search scanned
  std::int64_t traces = 0;            // unit isoline segments traced (each edge from both ends)
  std::int64_t trace_steps = 0;       // triangles entered by all traces together
  std::int64_t max_trace_steps = 0;   // by the longest trace
  std::int64_t trace_step_bound = 0;  // C below: the bound no trace may pass
  std::int64_t vertex_crossings = 0;  // traces passing through a mesh vertex (not a grid point)
  double seconds_certify = 0, seconds_grid = 0, seconds_trace = 0, seconds_quads = 0;
  double seconds_total = 0;
};

struct IsolineQuads {
  /// Quads, counter-clockwise in UV. A coarse grid may have loops and multi-edges (a torus
  /// 1 x 1: one quad on one vertex): quad_edges tells its sides apart, vertex pairs may not.
  std::vector<std::array<int, 4>> quads;
  std::vector<std::array<int, 4>> quad_edges;  // side k of quad q (corner k -> k+1) as an edge id
  int num_edges = 0;
  std::vector<IsolineQuadVertex> vertices;  // exact surface location of every quad vertex
  /// If IsolineInput::positions: sum w_i p_i over the triangle's corners in doubles (w_i rounded
  /// toward zero; a grid point on a vertex gets the vertex's position). For display only.
  std::vector<Vec3d> positions;
  int genus = 0;
  IsolineStats stats;
};

struct IsolineResult {
  certify::Report report;             // the certifier's checks 1-4 on the input (witnesses)
  std::optional<IsolineQuads> quads;  // present iff report.valid()
};

/// The quad mesh of the integer isolines of an IGM, exactly. First the independent certifier
/// (certify::certify_igm); if it rejects the input, no quads (the report says why). Then:
///  1. every integer point of the surface, once: per triangle the integer points of its closed UV
///     triangle (rows of its bounding box, exact rational row ends); a point on a mesh vertex is
///     that vertex, one inside an edge belongs to the side whose half-edge id is the smaller and
///     is checked to be found from the other side too (through the edge's transition);
///  2. per grid point its outgoing isoline directions in counter-clockwise order: the axis
///     directions in each incident triangle's half-open wedge at the point (4 at a regular point,
///     k at a cone of index k); from each, the unit segment traced through triangles and across
///     seams (transition applied to direction and target) to the grid point at UV distance 1,
///     which must be the target and send its reverse direction back (else igm::Error(Internal)
///     naming the grid point and the direction);
///  3. the faces of that graph (at each end, from the reverse direction one step clockwise): each
///     must have 4 sides, and V - E + F must equal the input's Euler characteristic.
/// Every decision is exact: comparisons of rationals and igm::orient2d; no tolerance.
/// Pre: a valid IGM with |UV coordinate| <= 2^60 (else igm::Error(TooLarge)); positions empty
/// or one per vertex (else the certifier's verdict is Unreadable).
/// Bound: a trace enters at most C triangles, C = sum over triangles of the integer rows and
/// columns meeting its closed UV triangle (a trace meets each such chord at most once: a
/// second meeting would make the isoline close up within length < 1 or fold back at a
/// non-integer point). Not F: a long sliver is crossed by one segment many times (tested).
/// Cost: the certifier (O(F log F)) plus O(F + rows + grid points + trace steps) exact
/// comparisons; measured in bench/isolines_bench.cpp.
IsolineResult extract_isolines(const IsolineInput& input, const IsolineOptions& options = {});

}  // namespace igm
