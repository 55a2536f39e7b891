#pragma once
// How each patch of a sized layout is mapped onto its integer rectangle [0,a] x [0,b] (exactly,
// orientation preserving, the same parameters on both sides of every seam, so that every seam's
// transition is a rotation by a multiple of 90 degrees plus an integer translation): the Tutte
// maps of every layout (igm/layout_map.h), and here the paper's affine maps of the canonical
// layouts, and the maps' statistics.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "igm/igm/patch_mesh.h"
#include "igm/layout/sizing.h"

namespace igm {

enum class PatchMapKind {
  /// Each patch re-embedded from its own geometry: a Tutte map onto its rectangle with positive
  /// weights from its 3D triangles (embed/weights.h), its four sides placed by 3D arc length.
  Tutte,
  /// Each layout quad mapped through the disk's embedding: two affine maps, one per triangle of the
  /// quad cut along its shorter diagonal (the paper's map); needs the diagonals in the overlay.
  Affine,
};

/// "tutte", "affine".
const char* to_string(PatchMapKind kind);

/// Statistics of the patch maps (map_layout, map_patches).
struct PatchMapStats {
  int patches = 0;
  int max_patch_vertices = 0;
  int patches_refined = 0;           // patches whose double Tutte solution needed exact refinement
  int max_refinement_steps = 0;
  std::int64_t flips_double = 0;     // non-positive triangles over all patches' double solutions
  std::size_t max_uv_bits = 0;       // largest bit_size of a UV coordinate
  int splits = 0;                    // edges split for the Tutte maps' pre-conditions (map_layout)
  double seconds = 0;
};

struct PatchMaps {
  std::vector<std::array<Point2q, 3>> corner_uv;  // per triangle corner of the patch mesh, exact
  PatchMapStats stats;
};

/// Per layout quad: 0 if its map cuts it along Q0-Q2, 1 along Q1-Q3 (the shorter diagonal,
/// exactly; ties to Q0-Q2), -1 for a parallelogram (one affine map). O(quads).
std::vector<int> quad_diagonals(const QuadLayout& layout);

/// The paper's affine maps: every layout quad q (triangles of mesh.triangle_quad == q) mapped
/// through `overlay_positions` (the overlay's plane positions; the overlay must hold the diagonals
/// of quad_diagonals) onto [0,a] x [0,b] = sizing.quad_size[q], Q0 -> (0,0), Q1 -> (a,0),
/// Q2 -> (a,b), Q3 -> (0,b): one affine map per half of the quad. Post: every UV triangle strictly
/// positive (checked exactly), layout points at integer points, every seam rigid with an integer
/// translation (checked by the certifier downstream). Throws igm::Error(InvalidArgument) if the
/// sizing or the mesh does not match the layout, Internal if a map fails. Cost O(F) exact
/// operations.
PatchMaps map_patches(const QuadLayout& layout, const PatchMesh& mesh, const Sizing& sizing,
                      const std::vector<Point2q>& overlay_positions);

}  // namespace igm
