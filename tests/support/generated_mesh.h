#pragma once
// A validated generated closed mesh (igm::generate_closed_mesh with the generator's defaults for
// everything but genus, size and seed), shared by the tests that need a self-contained mesh.
#include <cstdint>

#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"

namespace igm_test {

inline igm::ValidMesh generated_mesh(int genus, std::int64_t faces, std::uint64_t seed) {
  igm::GenerateOptions o;
  o.genus = genus;
  o.faces = faces;
  o.seed = seed;
  return igm::validate(igm::generate_closed_mesh(o));
}

}  // namespace igm_test
