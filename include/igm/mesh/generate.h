#pragma once
// Procedural orientable triangle meshes of any genus, closed or with boundary loops, for
// self-contained tests, fuzzing and benchmarks.
#include <cstdint>

#include "igm/mesh/soup.h"

namespace igm {

struct GenerateOptions {
  int genus = 2;                // 0 .. 100000
  std::int64_t faces = 2000;    // target face count; the result is within a factor ~2 (min 16)
  std::uint64_t seed = 1;       // deterministic: the same options give the same mesh
  bool shuffle = true;          // randomly permute vertex and face order and rotate each face's corners
  double jitter = 0.25;         // in-plane random displacement of grid vertices, in cell units (< 0.5)
  int boundaries = 0;           // boundary loops (holes cut into the closed surface), 0 .. 100000
};

/// A connected, consistently oriented triangle surface of the requested genus: the "double" of
/// a planar grid region with `genus` square holes (two sheets glued along the region's
/// boundary), then `boundaries` holes cut into it. Every vertex has one fan; no edge off the
/// seam joins two seam vertices.
///
/// boundaries = 0: closed, every edge has two faces (the same meshes as before the option).
/// boundaries = B > 0: B disjoint k x k squares of grid cells (2 k^2 triangles each, a
/// topological disk) are removed from the sheets, at random (per seed) among the positions of a
/// lattice whose squares use no seam vertex and lie at least max(2, k) cells apart: each leaves a
/// boundary loop of 4k edges without pinched vertices, no triangle touches two loops, and the
/// result has genus `genus` and B loops. k is the largest size <= max(1, min(width, height) / 16)
/// cells for which B squares fit. The removed faces (at most about a quarter) and the vertices
/// inside the squares are gone, so the face count is below the target. Capacity (loops that
/// fit): genus 0: 2 at 100 faces, 50 at 1,000, 200 at 4,000, about 1,000 at 20,000; handles
/// cost room at small sizes (genus 1 or 2 at 100 faces: none; genus 3 at 1,000 faces: 44). B
/// larger than the capacity: igm::Error(InvalidArgument) naming the capacity.
///
/// Cost O(faces log faces) with B > 0 (the size search), O(faces) without. Throws
/// igm::Error(InvalidArgument) for genus or boundaries out of 0..100000 or faces > 2^28.
PolygonSoup generate_mesh(const GenerateOptions& options);

/// generate_mesh for a closed mesh: throws igm::Error(InvalidArgument) if options.boundaries != 0.
PolygonSoup generate_closed_mesh(const GenerateOptions& options);

}  // namespace igm
