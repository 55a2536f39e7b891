#pragma once
// The seamless structure of an IGM, derived exactly from its corner UVs: the rigid transition
// across every edge, the total angle of every vertex, and per vertex a reference corner with the
// rigid map of each of its corners from the reference chart. With it a map is given by one UV per
// vertex (x_v, in the vertex's reference chart): corner c of vertex v gets T_c(x_v). Moving the
// x_v of non-cone vertices keeps every transition and every cone exactly as they are, so any such
// map whose triangles stay positive is again a valid IGM (smooth.h, dyadic.h).
// Surfaces with boundary and several components (certify/README.md, "Surfaces with boundary and
// components"): every boundary edge lies on an integer isoline of its chart; a boundary vertex has
// a fan of corners from its outgoing to its incoming boundary edge and a boundary angle k pi/2;
// a boundary corner (k != 2) is fixed at its integer point like a cone, a straight boundary vertex
// (k = 2) slides along its isoline: one coordinate of x_v is that isoline's integer value and
// stays, the other moves. Such moves keep every boundary edge on its isoline.
#include <array>
#include <utility>
#include <vector>

#include "igm/exact/predicates.h"
#include "igm/mesh/trimesh.h"
#include "igm/output/igm_mesh.h"

namespace igm {

/// The rigid motion x -> R^k x + t of the plane: R the rotation by +90 degrees, k in 0..3, t an
/// integer vector.
struct GridMotion {
  int k = 0;
  Integer tx = 0, ty = 0;
  bool is_identity() const { return k == 0 && sgn(tx) == 0 && sgn(ty) == 0; }
  friend bool operator==(const GridMotion& a, const GridMotion& b) {
    return a.k == b.k && a.tx == b.tx && a.ty == b.ty;
  }
};

/// m(p) = R^k p + t, exact.
Point2q apply(const GridMotion& m, const Point2q& p);
/// a after b: x -> a(b(x)).
GridMotion compose(const GridMotion& a, const GridMotion& b);
/// The inverse motion: inverse(m)(m(x)) = x.
GridMotion inverse(const GridMotion& m);

/// A boundary edge on its integer isoline: in the chart of face(halfedge), coordinate `axis`
/// (0: u, 1: v) of both ends equals `value`.
struct BoundaryIsoline {
  int halfedge = -1;
  int axis = 0;
  Integer value = 0;
};

struct SeamlessStructure {
  /// The IGM's triangles as a half-edge mesh. Corner i of face f is half-edge c = 3f + i (its
  /// origin is triangles[f][i]); "corner c" below means that half-edge. A boundary half-edge has
  /// twin -1 (TriMesh::from_triangles with allow_boundary).
  TriMesh mesh;
  /// Per half-edge h: the transition from the chart of face(h) to the chart of face(twin(h)):
  /// the UV of either end of the edge in face(twin(h)) is transition[h] of its UV in face(h).
  /// transition[twin(h)] == inverse(transition[h]). The identity on boundary half-edges.
  std::vector<GridMotion> transition;
  /// Per vertex: its total UV angle is angle_index[v] * pi/2 (4: a regular vertex), counted
  /// exactly as the certifier does (quadrant crossings of each corner's wedge); at a boundary
  /// vertex the angle of its fan from one boundary edge to the other (2: straight).
  std::vector<int> angle_index;
  /// Per vertex: its reference corner (mesh.vertex_halfedge(v); at a boundary vertex the first
  /// corner of its fan, whose outgoing edge is a boundary edge); x_v is that corner's UV.
  std::vector<int> reference_corner;
  /// Per corner c of vertex v: uv_c = corner_motion[c](x_v), exactly; the identity at the
  /// reference corner.
  std::vector<GridMotion> corner_motion;
  /// Per vertex: x_v, the UV of its reference corner (exact; an integer point at a cone).
  std::vector<Point2q> vertex_uv;
  /// Per vertex: on a boundary loop.
  std::vector<char> boundary;
  /// Per vertex: at a straight boundary vertex (angle 2 pi/2) the coordinate of x_v (0: u, 1: v)
  /// that is its boundary isoline's integer value (the other one slides); -1 elsewhere.
  std::vector<signed char> isoline_axis;
  /// Every boundary edge, by increasing half-edge, with its isoline.
  std::vector<BoundaryIsoline> boundary_edges;
  /// Interior edges held on integer isolines (issue 45: feature edges; hold_isoline_edges), each
  /// as its half-edge with the isoline in that face's chart, and per vertex the coordinates of
  /// x_v they fix (bit 0: u, bit 1: v; both: the vertex stays at its integer point). Empty unless
  /// hold_isoline_edges was called.
  std::vector<BoundaryIsoline> isoline_edges;
  std::vector<std::uint8_t> fixed_axes;
  int components = 0;      // connected components
  int boundary_loops = 0;  // in all components
  int genus = 0;           // the sum of the components' genera: (2 - chi - loops) / 2 each

  /// A vertex fixed at its integer point: an interior cone (angle != 2 pi) or a boundary corner
  /// (boundary angle != pi).
  bool is_cone(int v) const { return angle_index[v] != (boundary[v] ? 2 : 4); }
  /// A straight boundary vertex: x_v moves along its isoline only.
  bool slides(int v) const { return isoline_axis[v] >= 0; }
  int num_vertices() const { return mesh.num_vertices(); }
};

/// Per vertex of `mesh`, the total UV angle of its corners in units of pi/2, counted exactly as the
/// certifier does (certify/README.md check 4: each corner's wedge crosses (q_b - q_a) mod 4 of the
/// half-open quadrants' boundaries, decided by exact comparisons). A regular vertex has 4. Pre:
/// three UVs per face of `mesh`, every triangle strictly positive (else the count means nothing).
/// Cost O(F).
std::vector<int> angle_indices(const TriMesh& mesh,
                               const std::vector<std::array<Point2q, 3>>& corner_uv);
std::vector<int> angle_indices(const TriMesh& mesh,
                               const std::vector<std::array<Vec2d, 3>>& corner_uv);

/// Derives the seamless structure of `igm` from its exact corner UVs. Across every interior edge
/// the transition is the unique x -> R^k x + t (k in 0..3) with R^k e_A = e_B for the edge's UV
/// vectors in both faces, and t must be integer (the same for both ends by construction). The
/// corner maps compose these transitions around each vertex's fan from its reference corner; at a
/// regular vertex the composition around the whole fan must be the identity (at a cone it is a
/// rotation about the cone's integer point, or the identity when the angle is a multiple of 2 pi);
/// a boundary vertex's fan is open (no closing condition). Boundary edges and several components
/// are accepted as the certifier accepts them with allow_boundary and allow_components.
/// Everything is exact; doubles only pick the first rotation to try.
/// Pre: `igm` is a valid IGM (what the certifier checks): manifold oriented triangles over
/// positions.size() vertices, every vertex used, every UV triangle strictly positive (exact
/// orient2d), every interior transition rigid with integer translation, every cone (angle != 2 pi)
/// at an integer point, every boundary edge on an integer isoline, every boundary vertex of
/// boundary angle k pi/2 with k >= 1 and at an integer point when k != 2. Throws igm::Error
/// naming the element otherwise: InvalidArgument (sizes, a vertex used by no face, a face
/// repeating a vertex, a non-positive UV triangle (face), an edge without a rigid transition or a
/// boundary edge off every integer isoline (its two vertices), a cone or boundary corner off an
/// integer point, an angle index <= 0 or a regular vertex whose fan does not close up (vertex)),
/// NonManifoldEdge / NonManifoldVertex from the half-edge construction or the fan walk.
/// Cost: O(F log F) plus O(F) exact operations on the UVs' rationals.
SeamlessStructure seamless_structure(const IgmMesh& igm);

/// Holds the edges (a, b) (vertex pairs of s.mesh, either order) on their integer isolines: each
/// must be an edge whose two corner UVs in the chart of a face beside it share an integer u or an
/// integer v (checked exactly: igm::Error(InvalidArgument) naming the pair otherwise). Fills
/// s.isoline_edges and s.fixed_axes: at each end the coordinate of x_v that the isoline fixes,
/// carried into the vertex's reference chart by its corner motion (a quarter turn swaps u and v).
/// Smoothing then moves such a vertex along its isoline only (both coordinates fixed where two
/// isolines cross), and check_map checks these edges as it checks boundary edges. Cost
/// O(edges x valence) plus O(1) exact operations per edge.
void hold_isoline_edges(SeamlessStructure& s, const std::vector<std::pair<int, int>>& edges);

}  // namespace igm
