#pragma once
// The IGM of a sized quad layout: every layout quad's patch of the surface mapped onto its integer
// rectangle [0,a] x [0,b], exactly, orientation preserving, with the same parameters on both sides
// of every layout edge and of every glued pair of polygon sides (so that every seam's transition is
// a rotation by a multiple of 90 degrees plus an integer translation).
#include <array>
#include <cstddef>
#include <vector>

#include "igm/embed/tutte.h"
#include "igm/embed/weights.h"
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

struct PatchMapOptions {
  PatchMapKind kind = PatchMapKind::Tutte;
  WeightKind weights = WeightKind::MeanValue;
  /// Arc-length parameters along layout edges are multiples of 2^-parameter_bits (1..52): with 32
  /// bits and counts below 2^20 every boundary coordinate is exactly a double.
  int parameter_bits = 32;
  /// 3D lengths and weights are computed on the positions times this (mesh/scale.h: unit_scale of
  /// the input keeps hostile coordinates in range).
  double length_scale = 1;
  TutteOptions tutte;
};

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

/// Maps every patch. Tutte: the patch (triangles of mesh.triangle_quad == q, which must meet the
/// pre-conditions of tutte_embed: build_patch_mesh with split_chords) onto [0,a] x [0,b] =
/// sizing.quad_size[q], Q0 -> (0,0), Q1 -> (a,0), Q2 -> (a,b), Q3 -> (0,b); a vertex of layout edge e
/// at arc-length parameter t (arc_length_parameters of the 3D lengths along the edge's surface
/// edge, computed once for a glued pair) sits at t along its rectangle side. Affine: through
/// `overlay_positions` (the overlay's plane positions; the overlay must hold the diagonals of
/// quad_diagonals). Post: every UV triangle strictly positive (checked exactly by tutte_embed, and
/// here for the affine maps), layout points at integer points, every seam rigid with an integer
/// translation (checked by the certifier downstream). Throws igm::Error(Internal) if a map fails.
/// Cost: one certified Tutte solve per patch (embed/tutte.h), O(F) for the affine maps.
PatchMaps map_patches(const QuadLayout& layout, const PatchMesh& mesh, const Sizing& sizing,
                      const std::vector<Point2q>& overlay_positions, const PatchMapOptions& options = {});

}  // namespace igm
