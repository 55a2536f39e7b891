#pragma once
// The combinatorics of a sized layout's quad mesh: the a x b unit grid of every layout quad, its
// points shared along layout edges (by their integer position along the surface edge), at layout
// vertices and across glued polygon sides. No geometry: extract/patch_grid.h locates these
// vertices on the surface; the sizing's floor (layout/sizing.h) is tested on these quads.
#include <array>
#include <vector>

#include "igm/layout/quad_layout.h"

namespace igm {

/// A grid vertex by its first occurrence: point (i, j) of layout quad `quad`'s a x b rectangle,
/// and the layout vertex it is (-1 if none).
struct LayoutGridVertex {
  int quad = -1, i = 0, j = 0;
  int layout_vertex = -1;
};

struct LayoutGrid {
  /// Counter-clockwise, quad (i, j) of layout quad q is (i, j) (i + 1, j) (i + 1, j + 1) (i, j + 1),
  /// layout quad by layout quad, row by row.
  std::vector<std::array<int, 4>> quads;
  std::vector<int> quad_patch;  // per quad: its layout quad
  /// In order of first occurrence: layout quad by layout quad, and inside one by rows j = 0..b, row
  /// j from i = 0 up for even j, from i = a down for odd j (the snake order of the locating walks).
  std::vector<LayoutGridVertex> vertices;
};

/// The grid of `layout` with `quad_size[q]` = (a, b) >= (1, 1) per layout quad (Sizing::quad_size:
/// opposite sides, and glued sides, of equal counts). Throws igm::Error(InvalidArgument) for a
/// size list of the wrong length or a count below 1. Cost O(sum a b) hash operations.
LayoutGrid layout_grid(const QuadLayout& layout, const std::vector<std::array<int, 2>>& quad_size);

}  // namespace igm
