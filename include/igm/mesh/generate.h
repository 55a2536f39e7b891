#pragma once
// Procedural closed orientable triangle meshes of any genus, for self-contained tests,
// fuzzing and benchmarks.
#include <cstdint>

#include "igm/mesh/soup.h"

namespace igm {

struct GenerateOptions {
  int genus = 2;                // 0 .. 100000
  std::int64_t faces = 2000;    // target face count; the result is within a factor ~2 (min 16)
  std::uint64_t seed = 1;       // deterministic: the same options give the same mesh
  bool shuffle = true;          // randomly permute vertex and face order and rotate each face's corners
  double jitter = 0.25;         // in-plane random displacement of grid vertices, in cell units (< 0.5)
};

/// A closed, connected, consistently oriented triangle surface of the requested genus: the
/// "double" of a planar grid region with `genus` square holes (two sheets glued along the
/// region's boundary). Every edge has two faces, every vertex one fan; no edge off the
/// boundary joins two boundary vertices. Cost O(faces). Throws igm::Error(InvalidArgument)
/// for genus < 0, genus > 100000 or faces > 2^28.
PolygonSoup generate_closed_mesh(const GenerateOptions& options);

}  // namespace igm
