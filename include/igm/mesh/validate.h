#pragma once
// Validation of a polygon soup into a closed, manifold, oriented, connected triangle mesh
// (validate_surfaces.h accepts boundaries and several components, and cuts non-manifold input).
//
// Checks, in this order (the order decides which problem validate() throws when several
// exist; inspect() reports every one of them, in the same order):
//   1. empty            no vertices at all                      (then nothing else is checked)
//   2. no_faces         vertices but no faces                   (then nothing else is checked)
//   3. too_large        more vertices or triangles than 32-bit ids hold
//   4. invalid_argument a face with fewer than 3 corners, or a malformed soup
//   5. index_out_of_range  a face uses a vertex id < 0 or >= #vertices
//   6. repeated_vertex  a face uses the same vertex twice
//   7. non_finite       a coordinate of a vertex used by a face is NaN or Inf
//      (too_large stops all checks; if any of 4..6 is found, the topological checks 8..12 are
//       skipped: the faces are not a well-defined complex; report.topology_checked is false)
//   8. non_manifold_edge   an edge with more than two faces (also when the edge is a diagonal
//                          made by the fan triangulation of a polygon; the message says so)
//   9. non_manifold_vertex the faces around a vertex form more than one fan (edge-connected
//                          cycle or chain of faces); a vertex on a non-manifold edge counts too
//  10. non_orientable   a component admits no consistent orientation
//  11. boundary         edges with one face; a boundary loop is a connected component of the
//                       graph of these edges (loops touching at a vertex count as one)
//  12. several_components  faces connected through shared vertices form > 1 component
//      (with drop_unreferenced off, each unreferenced vertex is one more component)
// Local defects come before global ones: a boundary is reported before several components.
//
// Repairs (each reported as a warning, never silently):
//   - inconsistent orientation of an orientable component: the faces of the minority
//     orientation of each component are flipped (off: reported as non_manifold_edge);
//   - vertices used by no face are dropped;
//   - polygons are fan-triangulated (apex chosen, for polygons of up to 64 corners, so that no
//     diagonal coincides with an existing edge when possible).
// Element ids in problems refer to the input soup (0-based vertex and polygon ids): faces for
// 4, 5, 6, 8 (all faces of each edge), 10 (the two faces of one contradicting edge per
// component), 11 (one face per loop), 12 (the first face of each component); vertices for 7, 9.
// With repair_orientation off, inconsistent edges are a non_manifold_edge problem placed after 10.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/mesh/soup.h"
#include "igm/mesh/trimesh.h"

namespace igm {

/// One problem found in the input, with the offending elements (ids as in the input file).
struct MeshProblem {
  ErrorKind kind;
  std::string message;                 // names the count and the first few offending elements
  std::vector<std::int64_t> elements;  // the first (at most 100) offending ids, see validate.h top
  std::int64_t count = 0;              // exact number of offending items (faces, edges, vertices, loops, components)
};

/// What `igm info` prints: counts and every problem found (no exception).
struct MeshReport {
  std::int64_t vertices = 0, faces = 0, triangles = 0, edges = 0;  // input vertices/polygons; after triangulation
  std::int64_t polygons = 0;                                       // input faces with more than 3 corners
  std::int64_t components = 0, boundary_loops = 0;
  std::int64_t boundary_edges = 0, non_manifold_edges = 0, non_manifold_vertices = 0;
  std::int64_t unreferenced_vertices = 0;
  bool topology_checked = false;  // false when element errors (checks 3..6) prevented checks 8..12
  bool orientable = true;
  std::int64_t inconsistently_oriented_edges = 0;  // edges whose two faces disagree, before repair
  std::int64_t flipped_faces = 0;                  // triangles the repair would flip
  std::int64_t euler_characteristic = 0;           // V - E + F of the triangulated mesh (after repairs)
  int genus = -1;  // -1 unless the mesh is valid after repairs (closed, manifold, orientable, connected)
  std::vector<MeshProblem> problems;  // fatal problems in the order above (rejected if non-empty)
  std::vector<std::string> warnings;  // the reader's skips, then the repairs validate() would apply
};

struct ValidateOptions {
  bool repair_orientation = true;  // re-orient faces of an orientable surface (with a warning)
  bool drop_unreferenced = true;   // drop vertices used by no face (with a warning)
};

/// A validated mesh: closed, edge- and vertex-manifold, consistently oriented, connected.
struct ValidMesh {
  TriMesh mesh;
  std::vector<Vec3d> positions;            // per vertex of `mesh`
  std::vector<std::int64_t> input_vertex;  // vertex of `mesh` -> vertex id in the input soup
  std::vector<std::int64_t> input_face;    // face of `mesh` -> polygon id in the input soup
  std::vector<std::string> warnings;       // the reader's (soup.warnings), then the repairs applied
  int genus = 0;
};

/// Inspects without throwing (except std::bad_alloc): counts, all problems, the repairs that
/// would be applied. Cost O(C log C) for C corners.
MeshReport inspect(const PolygonSoup& soup, const ValidateOptions& options = {});

/// Triangulates polygons, applies the allowed repairs (each with a warning) and builds the
/// mesh. Throws igm::Error with the first fatal problem's kind, message and elements (the
/// same as inspect(soup).problems[0]). Post: mesh.check_invariants() is empty, every vertex
/// is used, genus = (2 - V + E - F) / 2. Cost O(C log C).
ValidMesh validate(const PolygonSoup& soup, const ValidateOptions& options = {});

/// read_soup + validate; error messages start with the path.
ValidMesh load_mesh(const std::filesystem::path& path, const ValidateOptions& options = {});

}  // namespace igm
