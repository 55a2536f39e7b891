#pragma once
// Twice the exact UV area of an IGM, summed over its triangles' corner UVs. An IGM on its quad
// mesh's grid has one UV unit per quad, so this is twice the number of quads (the pipeline tests').
#include "igm/exact/rational.h"
#include "igm/output/igm_mesh.h"

namespace igm_test {

inline igm::Rational uv_area2(const igm::IgmMesh& igm) {
  igm::Rational sum = 0;
  for (const auto& t : igm.corner_uv) sum += (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[1].y - t[0].y) * (t[2].x - t[0].x);
  return sum;
}

}  // namespace igm_test
