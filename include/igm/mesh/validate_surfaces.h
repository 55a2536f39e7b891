#pragma once
// Validation of a polygon soup into surfaces: connected, manifold, oriented triangle meshes,
// closed or with boundary, one per connected component (validate.h asks for one closed mesh).
//
// The element checks and the repairs are validate()'s (validate.h, checks 1..7; orientation,
// unreferenced vertices, polygon triangulation, each with a warning); so are the fatal
// topological problems: non_manifold_edge (an edge with more than two faces, or, with
// repair_orientation off, two faces of the same direction), non_manifold_vertex (the faces
// around a vertex form more than one fan: a cycle or a chain of faces; two boundary loops
// touching at a vertex make two fans) and non_orientable (e.g. a Moebius strip: a component
// with boundary may still admit no orientation), in this order, with validate()'s messages and
// element ids. Boundary loops and several components are fatal only when not allowed.
//
// split_nonmanifold cuts instead of rejecting (nothing geometric decides: the cut is
// combinatorial):
//   - an edge with k > 2 faces: its half-edges u -> v and v -> u are paired in input order (the
//     first u -> v with the first v -> u, ...), as their orientations in the input allow; the
//     others become boundary edges; a warning names every cut edge (input vertex ids) and its
//     faces. Pairing is by order, not by the angle around the edge: two sheets crossing along
//     the edge may be paired crosswise (both results are surfaces);
//   - then every fan of faces around a vertex gets a vertex of its own; a warning names every
//     cut vertex (input id) and its number of fans.
// The result is then processed as open surfaces. One case cannot be cut this way: two pieces of
// one cut edge that end up between the same two vertices (the fans at both ends join them): an
// igm::Error(NonManifoldEdge) names the edge.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/mesh/soup.h"
#include "igm/mesh/validate.h"

namespace igm {

/// One connected, edge- and vertex-manifold, consistently oriented triangle surface, closed or
/// with boundary. Every vertex is used; a boundary vertex has one fan (a chain of faces).
struct SurfaceComponent {
  std::vector<std::array<int, 3>> triangles;  // local vertex ids, counter-clockwise
  std::vector<Vec3d> positions;               // per local vertex
  std::vector<std::int64_t> input_vertex;     // local vertex -> vertex id in the input soup
                                              // (several local vertices for a cut vertex)
  std::vector<std::int64_t> input_face;       // triangle -> polygon id in the input soup
  /// Each loop a cycle of local vertex ids v0, v1, ..., vk-1: the half-edges vi -> vi+1 (and
  /// vk-1 -> v0) are the boundary half-edges, i.e. the surface lies to their left. A loop
  /// starts at its smallest vertex id; loops in increasing order of it.
  std::vector<std::vector<int>> boundary_loops;
  std::int64_t euler_characteristic = 0;  // V - E + F
  int genus = 0;                          // from euler_characteristic = 2 - 2 genus - #loops
};

struct SurfaceSet {
  /// In increasing order of their smallest input polygon id.
  std::vector<SurfaceComponent> components;
  std::vector<std::string> warnings;  // the reader's (soup.warnings), then the repairs and cuts
};

struct SurfaceOptions {
  ValidateOptions base;            // orientation repair, unreferenced vertices (validate.h)
  bool allow_boundary = true;      // off: boundary loops are an igm::Error(Boundary)
  bool allow_components = true;    // off: more than one component is igm::Error(SeveralComponents)
  bool split_nonmanifold = false;  // cut non-manifold edges and vertices (see the top of the file)
};

/// The surfaces of the soup: element checks, triangulation, repairs, cuts (split_nonmanifold),
/// then one SurfaceComponent per connected component (faces joined through edges, which after
/// the checks or cuts is the same as through vertices). Local vertices are numbered by input id
/// (copies of a cut vertex in the order of their first corner), triangles kept in input order:
/// for a closed connected soup, components[0] is validate()'s mesh (to_valid_mesh gives it back).
/// Throws igm::Error with validate()'s kind, message and element ids for a fatal problem (see the
/// top of the file); with drop_unreferenced off, an unreferenced vertex is
/// igm::Error(SeveralComponents) naming it (a component without faces is no surface).
/// Post: every component has at least one triangle and its genus is >= 0. Cost O(C log C) for
/// C corners.
SurfaceSet validate_surfaces(const PolygonSoup& soup, const SurfaceOptions& options = {});

/// How to go on after validate_surfaces(soup, options) threw `refused`: "" unless `refused` is a
/// non-manifold edge or vertex and options.split_nonmanifold is off. Then what cutting them apart
/// would give, with the caller's name for the option (`option`: "--split-nonmanifold" for the CLI,
/// "split_nonmanifold=True" for Python): "OPTION cuts its non-manifold vertices and edges apart
/// (N surfaces: genus g with b loops, ...)" when validate_surfaces accepts the soup with it, else
/// "OPTION would cut its non-manifold vertices and edges apart, but then: KIND: MESSAGE" (what
/// would still be wrong). Cost: validate_surfaces with the split, O(C log C).
std::string split_nonmanifold_hint(const PolygonSoup& soup, const SurfaceOptions& options, const Error& refused,
                                   const std::string& option);

/// A closed component as validate()'s ValidMesh (with `warnings`, e.g. the set's). Throws
/// igm::Error(Boundary) naming one input face per loop if the component has boundary loops.
/// Cost O(F log F).
ValidMesh to_valid_mesh(const SurfaceComponent& component, std::vector<std::string> warnings = {});

}  // namespace igm
