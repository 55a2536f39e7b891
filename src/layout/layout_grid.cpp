#include "igm/layout/layout_grid.h"

#include <string>
#include <unordered_map>

#include "igm/core/error.h"

namespace igm {

LayoutGrid layout_grid(const QuadLayout& L, const std::vector<std::array<int, 2>>& quad_size) {
  const int nq = static_cast<int>(L.quads.size());
  if (static_cast<int>(quad_size.size()) != nq)
    throw Error(ErrorKind::InvalidArgument, "layout_grid: one size per layout quad is needed");
  LayoutGrid out;
  std::unordered_map<int, int> layout_id;                                     // layout vertex -> grid vertex
  std::vector<std::unordered_map<int, int>> edge_point(L.num_surface_edges);  // position along -> grid vertex
  auto add = [&](int q, int i, int j, int lv) {
    out.vertices.push_back({q, i, j, lv});
    return static_cast<int>(out.vertices.size()) - 1;
  };
  for (int q = 0; q < nq; ++q) {
    const auto& Q = L.quads[q];
    const int a = quad_size[q][0], b = quad_size[q][1];
    if (a < 1 || b < 1)
      throw Error(ErrorKind::InvalidArgument, "layout_grid: layout quad " + std::to_string(q) + " has a count below 1", {q});
    std::vector<int> grid(static_cast<std::size_t>(a + 1) * (b + 1), -1);
    for (int j = 0; j <= b; ++j)
      for (int ii = 0; ii <= a; ++ii) {
        const int i = (j % 2 == 0) ? ii : a - ii;  // snake order
        const bool bi = i == 0 || i == a, bj = j == 0 || j == b;
        int id = -1;
        if (bi && bj) {  // a corner: its layout vertex
          const int k = (j == 0) ? (i == 0 ? 0 : 1) : (i == a ? 2 : 3);
          const int lv = L.layout_vertex[Q[k]];
          const auto it = layout_id.find(lv);
          id = it != layout_id.end() ? it->second : layout_id.emplace(lv, add(q, i, j, lv)).first->second;
        } else if (bi || bj) {  // on side k at integer position r from Q_k
          int k = 0, r = 0;
          if (j == 0) k = 0, r = i;
          else if (i == a) k = 1, r = j;
          else if (j == b) k = 2, r = a - i;
          else k = 3, r = b - j;
          const int e = L.quad_edge[q][k];
          const int len = (k % 2 == 0) ? a : b;
          // Position along the surface edge, in its own direction.
          const bool along = (L.quad_edge_forward[q][k] != 0) == (L.surface_edge_forward[e] != 0);
          auto& slot = edge_point[L.surface_edge[e]];
          const int pos = along ? r : len - r;
          const auto it = slot.find(pos);
          id = it != slot.end() ? it->second : slot.emplace(pos, add(q, i, j, -1)).first->second;
        } else {
          id = add(q, i, j, -1);
        }
        grid[static_cast<std::size_t>(j) * (a + 1) + i] = id;
      }
    for (int j = 0; j < b; ++j)
      for (int i = 0; i < a; ++i) {
        const std::size_t r0 = static_cast<std::size_t>(j) * (a + 1), r1 = r0 + a + 1;
        out.quads.push_back({grid[r0 + i], grid[r0 + i + 1], grid[r1 + i + 1], grid[r1 + i]});
        out.quad_patch.push_back(q);
      }
  }
  return out;
}

}  // namespace igm
