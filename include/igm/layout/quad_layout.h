#pragma once
// Quad layouts of the canonical polygonal schema: a subdivision of the convex 4g-gon (all corners
// copies of the root) into strictly convex quads whose sides split every polygon side into whole
// layout edges, paired sides at the same parameters. Any such layout gives a valid IGM once every
// layout quad is mapped onto an integer rectangle whose opposite sides, and glued sides, have equal
// integer lengths (docs/layouts.md). Three layouts are built here:
//  - paper  (Livesu 2023, §4.2): per group of four sides three inner points and five quads around
//           the centre; the root has valence 8g, the centre 3g, the 3g inner points 3;
//  - kite   every side split at its midpoint, 4g kites around the centre: valence 4g at the root
//           and at the centre, every other vertex regular;
//  - spread a ring of 8g quads along the boundary (sides split in thirds, one quad per corner) and a
//           grid of rows x (2g - rows) quads inside it: the root has valence 4g (the least any
//           layout of the canonical schema allows), the 4g - 4 grid boundary vertices other than the
//           grid's corners valence 5, every other vertex regular; for a torus the square itself.
#include <array>
#include <string>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

/// The layouts of the canonical schema (paper, kite, spread), and Field: the field-driven layout
/// (field/field_layout.h), which the pipeline tries first and replaces by the spread layout (or the
/// genus-0 orbifold, or the open cut's spread) where it cannot finish (pipeline.h). make_layout
/// builds only the schema's layouts.
enum class LayoutKind { Paper, Kite, Spread, Field };

/// "paper", "kite", "spread", "field".
const char* to_string(LayoutKind kind);

struct LayoutOptions {
  LayoutKind kind = LayoutKind::Spread;
  /// Spread only: rows of the inner grid (1 <= rows <= n/4 for n corners, 4g for a closed surface
  /// of genus g; the grid has rows x (n/2 - rows) quads). 0: automatic, clamp(round(sqrt(n/2)), 1,
  /// n/4) (for n = 4g: min(g, max(1, round(sqrt(2g)))); docs/layouts.md).
  int rows = 0;
  /// Spread only: the ring's depth, in units of the depth that would make its quads square on the
  /// regular polygon ((2/3) tan(pi/4g) R); at least twice the depth of the corners' chords, and
  /// less than the polygon's inradius (docs/layouts.md). > 0.
  double ring_depth = 1;
};

/// A layout edge (a segment between two layout points). `quad[0]` lies on its left when it runs
/// from `a` to `b` (`quad_side[0]` is that quad's side index k, the side running Q_k -> Q_(k+1)),
/// `quad[1]` on its right (-1 on the polygon boundary). A boundary edge is piece `piece` of polygon
/// side `side` (pieces numbered from corner `side`), running in the side's direction.
struct LayoutEdge {
  int a = -1, b = -1;
  std::array<int, 2> quad{-1, -1};
  std::array<int, 2> quad_side{-1, -1};
  int side = -1, piece = -1;
};

/// A quad layout of a convex polygon: 4g corners for a closed surface of genus g (every corner the
/// root), any even number >= 4 for the disks of open surfaces (topology/open_cut.h), whose sides are
/// glued in pairs or free (on the surface's boundary).
struct QuadLayout {
  int corners = 0;
  LayoutKind kind = LayoutKind::Spread;
  /// Exact points: 0 .. 4g-1 are the polygon corners (corner k = P_k), then the others.
  std::vector<Point2q> points;
  /// Strictly convex, counter-clockwise quads (Q0 Q1 Q2 Q3), mapped onto [0,a] x [0,b] with
  /// Q0 -> (0,0), Q1 -> (a,0), Q2 -> (a,b), Q3 -> (0,b).
  std::vector<std::array<int, 4>> quads;
  /// Per polygon side s: the layout points along it, from corner s to corner s+1 inclusive, in order.
  std::vector<std::vector<int>> side_points;
  /// How the sides are glued: side s to side_mate[s], in opposite directions (the point at
  /// parameter t of side s is the point at 1 - t of its mate); -1: a free side.
  std::vector<int> side_mate;
  /// Per corner: a label; corners with equal labels are one vertex of the glued surface (all 0 for
  /// a closed surface's schema: every corner is the root). Glued sides identify their ends too.
  std::vector<int> corner_label;

  // --- derived by finish_layout ---
  std::vector<LayoutEdge> edges;
  /// Per quad: edge id of its side k (Q_k -> Q_(k+1)) and whether that edge runs a -> b along it (1)
  /// or b -> a (0).
  std::vector<std::array<int, 4>> quad_edge;
  std::vector<std::array<char, 4>> quad_edge_forward;
  /// Per point: its vertex on the glued surface (corners by their labels, corner 0's vertex is 0;
  /// points glued across paired sides share one). num_layout_vertices = max + 1.
  std::vector<int> layout_vertex;
  int num_layout_vertices = 0;
  /// Per edge: its edge on the glued surface (a boundary piece and its mate's share one).
  /// `surface_edge_forward[e]` says whether edge e runs in the direction of the surface edge, whose
  /// direction is that of its first (lowest-id) planar edge.
  std::vector<int> surface_edge;
  std::vector<char> surface_edge_forward;
  int num_surface_edges = 0;
  /// Per surface edge: its chord (the class of edges linked by opposite sides of a quad and by the
  /// gluing; every edge of a chord must be given the same integer length). num_chords = max + 1.
  std::vector<int> chord;
  int num_chords = 0;

  int num_corners() const { return corners; }
  /// Per layout vertex: whether it lies on a free side (a boundary vertex of the surface).
  std::vector<char> on_boundary() const;
  /// Number of layout quads at each surface vertex (its valence in the quad layout).
  std::vector<int> valences() const;
};

/// Builds the layout `options.kind` on `corners` (a strictly convex counter-clockwise n-gon,
/// embed/polygon.h) with interior reference point `centre` (strictly inside), glued by `side_mate`
/// (an involution of the n sides without fixed points, -1 for a free side; any such pairing: every
/// layout here splits all sides alike and symmetrically), its corners identified by
/// `corner_label` (empty: all one vertex, the closed schema's root). paper needs n % 4 == 0, spread
/// an even n; for n = 4 both are the polygon itself. Every quad is checked strictly convex, and the
/// whole layout by check_layout, with exact predicates. Throws igm::Error(InvalidArgument) for a bad
/// polygon, centre, pairing, labels or rows; Internal if a check fails (never returns a bad
/// layout). Cost O(layout quads + n) exact operations (O(n) rational points of O(log n) bits).
QuadLayout make_layout(const std::vector<Point2q>& corners, const Point2q& centre, const std::vector<int>& side_mate,
                       const LayoutOptions& options = {}, const std::vector<int>& corner_label = {});

/// The side pairing of the canonical word a1 b1 a1^-1 b1^-1 ... ag bg ag^-1 bg^-1: side 4i with
/// 4i + 2, 4i + 1 with 4i + 3 (genus >= 1). O(g).
std::vector<int> canonical_side_mates(int genus);

/// The number of quads make_layout gives for this kind, number of corners n (4g for a closed
/// surface of genus g) and rows (0: automatic): paper 5n/4 (1 for n = 4), kite n, spread 2n + r(n/2
/// - r) (1 for n = 4). O(1).
int layout_quad_count(LayoutKind kind, int corners, int rows = 0);

/// Fills the derived members of `layout` from points, quads, side_points and side_mate: edges and
/// their quads, the glued layout vertices and surface edges, the chords (union-find). Throws
/// igm::Error(Internal) if an edge has two quads on one side or a boundary edge is not a piece of a
/// side, InvalidArgument if paired sides have different numbers of pieces. Cost O(E log E).
void finish_layout(QuadLayout& layout);

/// Independent check of a finished layout, exactly: every quad strictly convex and
/// counter-clockwise; every interior edge in one quad on each side and every boundary edge a side
/// piece; side points on their side in strictly increasing order; paired sides split at mirrored
/// parameters (t on side s, 1 - t on its mate); the quads wind once around every inner point (a
/// tiling of the polygon); Euler characteristic 1 of the planar subdivision; on the glued surface
/// every edge in two quads, or one on a free side, so that the index formula
/// sum_interior (4 - valence) + sum_boundary (2 - valence) = 4 chi holds (chi = V - E + F of the
/// glued quads; 8 - 8g for a closed surface of genus g). Returns "" or the first violation. Cost O(E).
std::string check_layout(const QuadLayout& layout);

}  // namespace igm
