#pragma once
// Shared by tests/smooth: IGMs to derive, round and smooth, and the checks they share.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "certify/certify.h"
#include "generated_mesh.h"
#include "igm/core/error.h"
#include "igm/output/igm_mesh.h"
#include "igm/pipeline/pipeline.h"
#include "igm/smooth/seamless.h"
#include "square_torus.h"

namespace igm_test {

/// Vertex (1, 1) of the 4 x 4 square torus (id 5; every corner of it is at (1, 1), away from the
/// seams) moved in all its corners to `uv`: a valid IGM as long as its six triangles stay positive.
inline igm::IgmMesh moved_torus(const igm::Point2q& uv) {
  igm::IgmMesh m = square_torus(4);
  for (std::size_t f = 0; f < m.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i)
      if (m.triangles[f][i] == 5) m.corner_uv[f][i] = uv;
  return m;
}

/// The face of moved_torus that sliver_torus makes thin: (1, 0), (2, 1), (1, 1), the second
/// triangle of square (1, 0).
inline constexpr int kSliverFace = 3;

/// moved_torus((3/2, 1/2 + eps)): vertex (1, 1) lies eps above the diagonal from (1, 0) to (2, 1),
/// so kSliverFace has UV area eps/2 (exactly; the other five triangles at the vertex keep areas
/// of about 1/4 to 1). Rounding the vertex to (3/2, 1/2) makes that triangle degenerate.
inline igm::IgmMesh sliver_torus(const igm::Rational& eps) {
  return moved_torus({igm::Rational(3, 2), igm::Rational(1, 2) + eps});
}

/// The options of a hard starting map for the smoother: the paper's template, its affine map, 4 x 4
/// quads per layout quad (the pipeline before the per-patch maps: large distortion), unsmoothed.
inline igm::PipelineOptions paper_affine_map() {
  igm::PipelineOptions o;
  o.layout = igm::LayoutKind::Paper;
  o.patch_map = igm::PatchMapKind::Affine;
  o.resolution = 4;
  o.smooth = false;
  o.quality = false;
  return o;
}

/// The pipeline's IGM of a generated mesh (certified by the pipeline), as paper_affine_map makes it.
inline igm::IgmMesh pipeline_igm(int genus, std::int64_t faces, std::uint64_t seed) {
  return igm::compute_igm(generated_mesh(genus, faces, seed), paper_affine_map()).igm;
}

/// The independent certifier on the mesh of `igm` with the UVs `corner_uv`.
inline igm::certify::Report certify_uv(const igm::IgmMesh& igm,
                                       const std::vector<std::array<igm::Point2q, 3>>& uv) {
  return igm::certify::certify_igm(igm::certify_input(igm, uv));
}

/// How many corner UVs differ between two maps of the same mesh (exactly).
inline int changed_corners(const std::vector<std::array<igm::Point2q, 3>>& a,
                           const std::vector<std::array<igm::Point2q, 3>>& b) {
  int changed = 0;
  for (std::size_t f = 0; f < a.size(); ++f)
    for (int i = 0; i < 3; ++i) changed += a[f][i].x != b[f][i].x || a[f][i].y != b[f][i].y;
  return changed;
}

/// The igm::Error that `run` throws, or nullopt if it returns.
template <class Run>
std::optional<igm::Error> error_of(Run run) {
  try {
    run();
  } catch (const igm::Error& e) {
    return e;
  }
  return std::nullopt;
}

/// "" if the seamless structures of two maps of the same mesh agree bit for bit on everything a
/// map may not change (transitions, angles, reference corners, corner maps, cone points), else
/// the first difference.
inline std::string structure_difference(const igm::SeamlessStructure& a,
                                        const igm::SeamlessStructure& b) {
  if (a.transition.size() != b.transition.size() || a.angle_index.size() != b.angle_index.size())
    return "sizes";
  for (std::size_t h = 0; h < a.transition.size(); ++h) {
    if (!(a.transition[h] == b.transition[h]))
      return "transition of half-edge " + std::to_string(h);
    if (!(a.corner_motion[h] == b.corner_motion[h]))
      return "corner map of corner " + std::to_string(h);
  }
  for (std::size_t v = 0; v < a.angle_index.size(); ++v) {
    if (a.angle_index[v] != b.angle_index[v]) return "angle of vertex " + std::to_string(v);
    if (a.reference_corner[v] != b.reference_corner[v])
      return "reference corner of vertex " + std::to_string(v);
    if (a.is_cone(static_cast<int>(v)) &&
        (a.vertex_uv[v].x != b.vertex_uv[v].x || a.vertex_uv[v].y != b.vertex_uv[v].y))
      return "cone point of vertex " + std::to_string(v);
  }
  return "";
}

}  // namespace igm_test
