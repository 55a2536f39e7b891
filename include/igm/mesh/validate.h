#pragma once
// Validation of a polygon soup into a closed, manifold, oriented, connected triangle mesh.
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
  std::string message;
  std::vector<std::int64_t> elements;
};

/// What `igm info` prints: counts and every problem found (no exception).
struct MeshReport {
  std::int64_t vertices = 0, faces = 0, triangles = 0, edges = 0;
  std::int64_t components = 0, boundary_loops = 0;
  std::int64_t unreferenced_vertices = 0;
  bool orientable = true;
  std::int64_t inconsistently_oriented_edges = 0;  // edges whose two faces disagree, before repair
  int euler_characteristic = 0;
  int genus = -1;  // -1 unless the mesh is valid after repairs (closed, manifold, orientable, connected)
  std::vector<MeshProblem> problems;  // fatal problems (the mesh is rejected if non-empty)
  std::vector<std::string> warnings;  // repairs that validate() would apply
};

struct ValidateOptions {
  bool repair_orientation = true;   // re-orient faces of an orientable surface (with a warning)
  bool drop_unreferenced = true;    // drop vertices used by no face (with a warning)
};

/// A validated mesh: closed, edge- and vertex-manifold, consistently oriented, connected.
struct ValidMesh {
  TriMesh mesh;
  std::vector<Vec3d> positions;         // per vertex of `mesh`
  std::vector<std::int64_t> input_vertex;  // vertex of `mesh` -> vertex id in the input soup
  std::vector<std::int64_t> input_face;    // face of `mesh` -> polygon id in the input soup
  std::vector<std::string> warnings;    // repairs applied
  int genus = 0;
};

/// Inspects without throwing: counts, all problems, the repairs that would be applied. O(F log F).
MeshReport inspect(const PolygonSoup& soup);

/// Triangulates polygons, applies the allowed repairs (each with a warning) and builds the
/// mesh. Throws igm::Error with the first fatal problem's kind and elements. O(F log F).
ValidMesh validate(const PolygonSoup& soup, const ValidateOptions& options = {});

/// read_soup + validate.
ValidMesh load_mesh(const std::filesystem::path& path, const ValidateOptions& options = {});

}  // namespace igm
