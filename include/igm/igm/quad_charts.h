#pragma once
// Piecewise-affine IGM charts on the overlay of the quad template (paper §4.2, §5): every
// layout quad is mapped to the unit square [0,1]^2 by two affine maps, one per triangle of the
// quad cut along its diagonal (or one affine map if the quad is a parallelogram). Exact,
// continuous inside each quad, orientation-preserving; no inverse bilinear coordinates.
#include <array>
#include <cstddef>
#include <vector>

#include "igm/arrange/overlay.h"
#include "igm/arrange/quad_template.h"

namespace igm {

struct QuadChartsOptions {
  bool check = true;  // verify every UV triangle strictly positive and inside [0,1]^2 (exact, O(F))
};

struct QuadCharts {
  std::vector<int> region;                 // per triangle: index into template_regions(t)
  std::vector<int> quad;                   // per triangle: layout quad
  std::vector<std::array<Point2q, 3>> uv;  // per triangle corner: exact UV in its quad's unit square
  std::size_t max_uv_bits = 0;             // max bit_size over all UV coordinates
};

/// Labels every triangle of `overlay` with its template region by a flood fill bounded by the
/// segment chains (seeded from the chains' sides), then maps each corner by its region's
/// affine map: quad (Q0 Q1 Q2 Q3) -> (0,0),(1,0),(1,1),(0,1).
///
/// Pre: `overlay` = overlay_segments(mesh, template_geometry(t, template_segments(t))) on a
/// triangulation of the template's polygon. Post: every UV triangle strictly positive; polygon
/// corners map to integer points; a point at parameter s along a quad edge maps to parameter s
/// along the matching unit-square edge (so sides glued at equal parameters get transitions
/// R^k x + t, t integer). Throws InvalidArgument if the overlay does not match the template,
/// Internal if a label or UV check fails. Cost O(F log F).
QuadCharts compute_quad_charts(const QuadTemplate& t, const OverlayResult& overlay, const QuadChartsOptions& options = {});

}  // namespace igm
