#pragma once
// Separatrices of a cross field traced as a motorcycle graph (Eppstein & Erickson 1999; Myles,
// Pietroni & Zorin 2014 "Robust field-aligned global parametrization"): from every cone and every
// concave boundary corner, a curve leaves along each field direction and runs straight through
// the faces (the field is constant per face), turning across edges by the field's matchings, until
// it meets a curve already drawn (or itself), the surface's boundary or a cone; curves advance in
// turns by length, so the first to arrive wins. The curves are exact polylines on the input
// surface: crossings with edges at dyadic parameters (field-notes.md: a trace need only be a simple
// path, not an exact streamline), meeting points exact rationals inside faces, every decision of
// where a curve stops taken by exact predicates. Doubles only choose the directions.
//
// Every point where curves meet carries a cyclic numbering of the field's directions ("rays"): at
// a vertex its separatrix directions (k for an interior vertex of field valence k; 0..k for a
// boundary vertex whose boundary angle is k quarter turns, rays 0 and k along the boundary), at a
// point inside an edge or a face the four directions of one face's field. Two consecutive curves
// around a point enclose as many quarter turns as their rays differ: the corners of the patches.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "igm/exact/predicates.h"
#include "igm/exact/rational.h"
#include "igm/mesh/trimesh.h"

namespace igm {

/// A point of the input surface: a vertex, a point inside an edge at a dyadic parameter, or a
/// point inside a face at exact barycentric coordinates.
struct TracePoint {
  enum class Kind : std::uint8_t { Vertex, Edge, Face };
  Kind kind = Kind::Vertex;
  /// Vertex: its id. Edge: the edge's canonical half-edge (the smaller of the pair; a boundary
  /// half-edge itself). Face: the face.
  int element = -1;
  Rational t;                 // Edge: the point is (1 - t) origin(element) + t target(element), 0 < t < 1
  std::array<Rational, 3> w;  // Face: weights of face_vertices(element), each > 0, summing to 1
};

/// How a curve ended.
enum class CurveEnd : std::uint8_t {
  Curve,     // on another curve (or itself): a T-junction, inside a face, on an edge or at a vertex
  Cone,      // at a cone or a boundary corner, arriving along one of its free rays
  Boundary,  // on the surface's boundary
  Bound,     // the step bound (TraceOptions::max_segments): a dangling end, the layout is unusable
  Stuck,     // no direction to go on (degenerate face, or a direction that leaves the face backwards)
};
const char* to_string(CurveEnd end);

/// One traced curve: its points in order (ids into TraceGraph::points); segment i joins points i
/// and i+1 inside face segment_face[i], or along a mesh edge when segment_face[i] == -1. Per
/// point, the rays (in that point's numbering, TraceGraph::ray_count) pointing back along the
/// curve and forward along it (-1 at the start, resp. the end).
struct TraceCurve {
  std::vector<int> points;
  std::vector<int> segment_face;
  std::vector<int> ray_back, ray_forward;
  CurveEnd end = CurveEnd::Bound;
  double length = 0;  // 3D length (doubles; for ordering and statistics only)
};

struct TraceOptions {
  /// Edge crossings are multiples of 2^-parameter_bits (in 2..40), at least one step from either end.
  int parameter_bits = 24;
  /// Per curve, at most this many segments (0: 2 F + 64 for F faces). A curve that reaches it ends
  /// with CurveEnd::Bound.
  int max_segments = 0;
  /// Two separatrices that run into each other's start are one curve: a ray traced alone (no
  /// other curve) is taken into a vertex whose rays are traced when, inside a face with that vertex
  /// as a corner ahead of it, the vertex lies within this slope of its line (lateral offset <=
  /// slope x distance along); when two rays take each other so, only one curve is traced, from the
  /// first, and it ends in the other's vertex by the other's ray. 0: no such pairs.
  double capture_slope = 0.35;
  /// A curve ending on another one within snap_length (3D, along the other curve; 0: snap_distance
  /// mean edge lengths) of a node where a curve from the other side ended already ends at that
  /// node (one node instead of two a short way apart, whose short arc no integer length could fit;
  /// the pipeline sets snap_length from the quad size). Both 0: never.
  double snap_length = 0;
  double snap_distance = 0.5;
  /// Vertices whose every field direction is traced as well, even where the field is regular
  /// (build_field_layout seeds patches that are not disks this way).
  std::vector<int> seeds;
  /// Rays (vertex, ray index) that are not traced (build_field_layout leaves out the rays of curves
  /// that could not end well, when the vertex keeps no angle above two quarter turns).
  std::vector<std::pair<int, int>> banned_rays;
  /// Walls (issue 45: feature curves): chains of vertices joined by interior mesh edges (closed
  /// when the first vertex is repeated last), each edge in at most one wall. They are drawn
  /// first, whole, as curves along their edges (each vertex left and entered by its ray nearest
  /// to the edge), and every other curve ends on them. A wall's ends and the vertices where it
  /// turns in the field (not leaving by the ray opposite to the one it came in by) are traced like
  /// seeds. A wall whose ray at a vertex is missing or already taken ends there (CurveEnd::Stuck:
  /// the layout is then unusable and says so).
  std::vector<std::vector<int>> walls;
  /// Which free rays of a wall's end or turn are traced. false: only the one continuing the wall
  /// (at an end: the ray opposite the wall's; at a turn: the one opposite the ray it came in by),
  /// which is all a patch needs there (no angle of three quarter turns, no curve ending inside a
  /// patch); true: every free ray (the two side rays too, which run beside the wall and cut thin
  /// strips; bench/README.md "stop 54").
  bool wall_side_rays = false;
  /// Return right after drawing the walls when one could not be drawn whole (stuck_walls set, no
  /// other curve traced): for a caller that then leaves those walls out and starts again.
  bool stop_at_stuck_wall = false;
};

struct TraceStats {
  int cones = 0;              // interior vertices of field valence != 4
  int boundary_corners = 0;   // boundary vertices of angle != 2 quarter turns
  int curves = 0;
  std::int64_t segments = 0;
  int ends_on_curves = 0, ends_at_cones = 0, ends_on_boundary = 0, ends_at_bound = 0, ends_stuck = 0;
  int vertex_passes = 0;      // regular vertices a curve went through
  int cone_pairs = 0;         // separatrices traced once between two starting vertices
  int head_on_merges = 0;     // two curves met head-on and became one
  int parallel_meets = 0;     // a curve ran into a parallel one (not head-on, or not mergeable)
  int same_direction_meets = 0;  // of those, the two curves running the same way
  int slides = 0;             // curves that ran along the edge they entered by
  int blocked_arrivals = 0;   // curves that reached a vertex by a ray already taken
  int steers = 0;             // curves that headed straight for a cone within the snap length
  int node_snaps = 0;         // curves ended at a node close by instead of a new T-junction
  int vertex_joins = 0;       // parallel meetings resolved by going on to the vertex ahead
  int dropped = 0;            // of those, curves removed whole (nothing rested on them)
  int walls = 0;              // walls drawn (TraceOptions::walls)
  int stuck_walls = 0;        // of those, walls that could not be drawn whole
  double seconds = 0;
};

/// The traced curves on the input mesh (the motorcycle graph) and the field data they used.
struct TraceGraph {
  std::vector<TracePoint> points;
  std::vector<TraceCurve> curves;
  /// Per point: how many rays it has (4 inside an edge or a face; a vertex's separatrix count k,
  /// or k + 1 on the boundary) and whether they are cyclic (not for boundary points, whose rays run
  /// from the boundary ahead (0) to the boundary behind).
  std::vector<int> ray_count;
  std::vector<char> ray_cyclic;
  /// The walls (TraceOptions::walls, by index) that could not be drawn whole, ascending.
  std::vector<int> stuck_walls;
  /// Per vertex: its field valence (interior: 4 - 4 x index, 4 regular; boundary: its angle in
  /// quarter turns), from the matchings used here.
  std::vector<int> valence;
  TraceStats stats;
};

/// Traces the motorcycle graph of the cross field given by one tangent direction per face
/// (`face_direction[f]`, any non-zero vector; only its projection on the face plane matters; the
/// field's four directions are it and its rotations by quarter turns about the face normal). The
/// matchings across edges are the nearest ones (each edge's rotation below 45 degrees); a vertex's
/// separatrices are the rays from it along which the field points radially, counted with the
/// sign of each crossing and cancelled in adjacent pairs of opposite sign, so that an interior
/// vertex of valence k has exactly k rays a quarter turn apart in the field. Curves start from
/// every vertex of valence != 4 (interior) or != 2 (boundary: its interior rays) and from
/// options.seeds.
/// Pre: `mesh` is a connected orientable manifold (boundary allowed), positions finite. Throws
/// igm::Error(InvalidArgument) for sizes that do not match, a seed out of range, or a wall that is
/// not a chain of interior mesh edges (naming the wall and its vertices). Every loop is bounded: curves
/// <= sum of ray counts of the starting vertices, each <= max_segments segments, each segment
/// checked against the segments already in its face (exact). Cost: O(total segments x segments
/// per face) exact tests.
TraceGraph trace_motorcycles(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                             const std::vector<Vec3d>& face_direction, const TraceOptions& options = {});

/// Independent check of a trace graph, exactly: every point where it claims to be (edge
/// parameters in (0,1), face weights positive and summing to 1), consecutive points of a curve in
/// the claimed face or edge, no two segments crossing or overlapping except where one ends on the
/// other (a T-junction recorded by that curve's end), rays within range. "" or the first violation.
std::string check_trace_graph(const TriMesh& mesh, const TraceGraph& graph);

}  // namespace igm
