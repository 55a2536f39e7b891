#pragma once
// The artefacts of a run: the IGM (triangle mesh with exact per-corner UV) and the quad mesh,
// and their writers. File formats:
//  - NAME.igm.obj   : `v x y z`, one `vt u v` per face corner, `f a/ta b/tb c/tc` (1-based) —
//                     readable by libQEx. A UV coordinate that is exactly a double is written
//                     as its exact decimal expansion (finite: at most 1074 digits after the
//                     point; the certifier reads it as that exact rational, strtod gives back
//                     the same double), so a map on a double grid (smooth/dyadic.h) certifies
//                     from this file too; any other coordinate as %.17g of its value rounded
//                     toward zero (not exact).
//  - NAME.igm.exact : the same with exact `vt p/q r/s` rationals (the certified artefact; the
//                     certifier reads it exactly, see certify/README.md).
//  - NAME.quad.obj  : `v x y z`, `f a b c d`.
#include <array>
#include <iosfwd>
#include <vector>

#include "certify/certify.h"
#include "igm/exact/predicates.h"
#include "igm/mesh/surface_point.h"

namespace igm {

/// The IGM triangle mesh: a refinement of the input mesh (ValidMesh) it was computed from.
struct IgmMesh {
  std::vector<Vec3d> positions;                 // per vertex: evaluate(locations[v]), the exact point rounded toward zero
  std::vector<std::array<int, 3>> triangles;    // ccw
  std::vector<std::array<Point2q, 3>> corner_uv;  // per face corner, exact
  /// Per vertex, its exact location on the input surface (ids of the input mesh's vertices):
  /// vertices 0..n-1 are the n input vertices, each the weight-1 point of itself; every other
  /// vertex is a convex combination, with exact weights > 0 summing to 1, of the two end points
  /// of an input edge or the three corners of an input face. The three corners of every
  /// triangle have a joint support inside one input face (the triangle lies in that face), and
  /// the triangles inside each input face tile it. Filled by compute_igm (pipeline.h); the
  /// writers below do not use it. Memory: about 0.2 KB per vertex plus the weights' limbs.
  std::vector<SurfacePoint> locations;
};

struct QuadMesh {
  std::vector<Vec3d> positions;
  std::vector<std::array<int, 4>> quads;  // ccw
  /// Per vertex, its exact location on the input surface (as IgmMesh::locations); positions[v] is
  /// evaluate(locations[v]). Filled by compute_igm; the writers do not use it.
  std::vector<SurfacePoint> locations;
};

/// Writes the IGM with double UVs (exact == false: exact decimals for the coordinates that are
/// doubles, see the top of this file) or exact rational UVs (exact == true).
/// Pre: corner_uv.size() == triangles.size(). Cost O(F) (plus the size of the rationals).
void write_igm_obj(std::ostream& out, const IgmMesh& igm, bool exact);

/// The certifier's in-memory input for the triangles and vertices of `igm` with the UVs
/// `corner_uv` (three per triangle: igm.corner_uv, or another map of the same mesh). Pre:
/// corner_uv.size() == triangles.size() (throws igm::Error(InvalidArgument) otherwise).
/// Cost O(F) copies.
certify::IgmInput certify_input(const IgmMesh& igm,
                                const std::vector<std::array<Point2q, 3>>& corner_uv);

/// Writes the quad mesh as OBJ.
void write_quad_obj(std::ostream& out, const QuadMesh& quads);

}  // namespace igm
