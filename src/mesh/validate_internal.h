#pragma once
// Internal to validation (igm/mesh/validate.h, igm/mesh/validate_surfaces.h): the analysis of a
// polygon soup that validate(), inspect() and validate_surfaces() share. Not installed, not part
// of the API.
#include <array>
#include <cstdint>
#include <vector>

#include "igm/mesh/soup.h"
#include "igm/mesh/validate.h"

namespace igm::validate_internal {

/// What analyze() does at edges with more than two faces and at vertices with several fans.
enum class Mode {
  Closed,        // validate(), inspect(): both are problems (checks 8 and 9 of validate.h)
  Surfaces,      // the same problems, and the twins and corner classes are kept
  SplitSurfaces  // both are cut (validate_surfaces.h, split_nonmanifold), with warnings
};

/// One piece of an edge with more than two faces cut by Mode::SplitSurfaces: two half-edges of
/// opposite directions paired (h2 >= 0) or one half-edge left as a boundary edge (h2 = -1).
struct EdgePiece {
  int group;  // the cut edge (pieces of one edge share it)
  int h1, h2;
};

struct Analysis {
  MeshReport report;
  std::vector<std::array<int, 3>> tris;  // input vertex ids, as triangulated (before flips)
  std::vector<int> tri_face;             // triangle -> input polygon
  std::vector<char> flip;                // triangle -> flip to repair the orientation
  std::vector<char> keep_vertex;         // input vertex -> present in the mesh
  // Modes Surfaces and SplitSurfaces, when the topology was checked (else empty):
  std::vector<int> twin;          // half-edge 3t+i (tris[t][i] -> tris[t][i+1]) -> its pair, or -1
  std::vector<int> corner_class;  // half-edge -> representative of its fan (corner class)
  std::vector<EdgePiece> pieces;  // SplitSurfaces: the pieces of the cut edges, grouped by edge
};

/// Checks 1..12 of validate.h and the repairs, as described there, in `mode`. Cost O(C log C) for
/// C corners.
Analysis analyze(const PolygonSoup& soup, const ValidateOptions& options, Mode mode);

}  // namespace igm::validate_internal
