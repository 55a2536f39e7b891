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

/// One IGM: an oriented triangle mesh (closed and connected unless IsolineOptions allow otherwise)
/// with one exact UV per face corner.
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
  /// Accept IGMs of surfaces with boundary (the certifier's Options::allow_boundary: every
  /// boundary edge on an integer isoline of its chart, boundary corners at integer points) and of
  /// several connected components (Options::allow_components). Off: closed, connected IGMs only,
  /// as the certifier's defaults judge them.
  bool allow_boundary = false;
  bool allow_components = false;
  /// Threads for the certifier (certify::Options::threads; 0: all cores). The other steps run in
  /// the caller's oneTBB arena (igm/core/threads.h). The result is the same for any count.
  int threads = 0;
  /// Edges the certifier checks on integer isolines (certify::Options::feature_edges: issue 45's
  /// feature edges); none: no features check.
  std::optional<std::vector<certify::FeatureEdge>> feature_edges;
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
  /// Outgoing isolines: 4, or the index k of a cone (total angle k pi/2); on the boundary k + 1
  /// for the boundary angle k pi/2 (3 on a straight boundary, 2 at a convex corner, 4 at a
  /// reflex one, 5 at the tip of a slit), the two along the boundary included.
  int valence = 4;
  bool boundary = false;  // on a boundary vertex or inside a boundary edge of the IGM
};

struct IsolineStats {
  std::int64_t grid_points_on_vertices = 0, grid_points_on_edges = 0, grid_points_in_faces = 0;
  std::int64_t cones = 0;             // interior grid points of valence != 4 (all on vertices)
  std::int64_t grid_points_on_boundary = 0;  // on boundary vertices or inside boundary edges
  std::int64_t boundary_corners = 0;         // boundary grid points of valence != 3
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
  int genus = 0;           // the input's (the sum over its components)
  int boundary_loops = 0;  // of the quad mesh: the input's, each made of isoline segments
  IsolineStats stats;
};

struct IsolineResult {
  certify::Report report;             // the certifier's checks 1-4 on the input (witnesses)
  std::optional<IsolineQuads> quads;  // present iff report.valid()
};

/// The quad mesh of the integer isolines of an IGM, exactly. First the independent certifier
/// (certify::certify_igm, with options.allow_boundary / allow_components); if it rejects the
/// input, no quads (the report says why). Then:
///  1. every integer point of the surface, once: per triangle the integer points of its closed UV
///     triangle (rows of its bounding box, exact rational row ends); a point on a mesh vertex is
///     that vertex, one inside an edge belongs to the side whose half-edge id is the smaller and
///     is checked to be found from the other side too (through the edge's transition); one inside
///     a boundary edge belongs to its triangle;
///  2. per grid point its outgoing isoline directions in counter-clockwise order: the axis
///     directions in each incident triangle's half-open wedge at the point (4 at a regular point,
///     k at a cone of index k; on the boundary the closed wedge, both boundary directions
///     included: a boundary edge lies on an isoline); from each, the unit segment traced through
///     triangles and across seams (transition applied to direction and target) to the grid point
///     at UV distance 1, which must be the target and send its reverse direction back (else
///     igm::Error(Internal) naming the grid point and the direction). A segment meets the
///     boundary only at grid points or runs along it: leaving the surface is an error;
///  3. the faces of that graph (at each end, from the reverse direction one step clockwise): the
///     bounded ones are the quads and must have 4 sides; the others run backwards along the
///     boundary, one per boundary loop of the input; V - E + F of the quads must equal the
///     input's Euler characteristic.
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

/// The certifier's quad mode on the extraction's quads (certify::certify_quads): pure quads,
/// manifold, oriented, of the input's genus; with options.allow_boundary / allow_components also
/// with the input's boundary loops and per component the input's (genus, boundary loops), as a
/// multiset. Pre: result.quads (else igm::Error(InvalidArgument)). Cost O(Q log Q).
certify::Report certify_isoline_quads(const IsolineResult& result,
                                      const IsolineOptions& options = {});

}  // namespace igm
