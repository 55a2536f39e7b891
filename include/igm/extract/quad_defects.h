#pragma once
// Why the quads of a valid IGM's integer isolines (extract/isolines.h) are not a manifold quad
// mesh: the certifier's quad check (check 5) judges a mesh by its vertex ids, so a loop, two edges
// between the same two vertices or a quad with a repeated vertex make it fail. On a valid IGM these
// come only from a grid too coarse for the cones (a 1 x 1 torus: one quad on one vertex; a genus-0
// pillowcase of 2 x 1 quads per unit: two edges between two vertices). This names each such
// defect with its elements and the cones of the quads around it, for people (the pipeline and
// `igm extract` print it instead of only the certifier's counts).
#include <cstddef>
#include <string>
#include <vector>

#include "igm/extract/isolines.h"

namespace igm {

enum class QuadDefectKind {
  Loop,            // an edge from a vertex to itself
  MultiEdge,       // two or more edges between the same two vertices
  RepeatedVertex,  // a quad with a vertex at two of its corners
};

/// "loop", "multi_edge", "repeated_vertex".
const char* to_string(QuadDefectKind kind);

struct QuadDefect {
  QuadDefectKind kind = QuadDefectKind::Loop;
  std::vector<int> vertices;  // Loop, RepeatedVertex: the vertex; MultiEdge: the two ends
  std::vector<int> edges;     // the edges (IsolineQuads::quad_edges ids); RepeatedVertex: none
  std::vector<int> quads;     // the quads with one of those edges, or with the repeated vertex
  std::vector<int> cones;     // the vertices of those quads of valence != 4 (cones, boundary corners)
  int component = 0;          // the quad mesh's connected component (numbered by their first quad)
};

/// Every defect, in order of the lowest quad id involved, at most `max_defects` (0: all). Loops
/// and multi-edges from the quads' edges (quad_edges tells edges apart where vertex ids do not), a
/// repeated vertex only in a quad with neither. Empty for a manifold quad mesh (the certifier's
/// check 5 then fails, if at all, for another reason: its witnesses say which). Pre: `quads` from
/// extract_isolines. Cost O(Q log Q).
std::vector<QuadDefect> find_quad_defects(const IsolineQuads& quads, std::size_t max_defects = 0);

/// One line for people: "" for no defect; else the first few defects with their vertices, edges,
/// quads and cones (with the component where there are several) and what to do (more quads).
std::string describe_quad_defects(const IsolineQuads& quads, const std::vector<QuadDefect>& defects);

}  // namespace igm
