#include "igm/extract/patch_grid.h"

#include <string>
#include <unordered_map>

#include "igm/arrange/planar_walk.h"
#include "igm/core/error.h"

namespace igm {

PatchGrid extract_patch_grids(const QuadLayout& L, const PatchMesh& m, const Sizing& sizing,
                              const std::vector<std::array<Point2q, 3>>& corner_uv) {
  const int nq = static_cast<int>(L.quads.size());
  const int nf = static_cast<int>(m.triangles.size());
  if (static_cast<int>(corner_uv.size()) != nf || static_cast<int>(sizing.quad_size.size()) != nq)
    throw Error(ErrorKind::InvalidArgument, "extract_patch_grids: the UVs or the sizing do not match the mesh");
  std::vector<std::vector<int>> patch_tris(nq);
  for (int t = 0; t < nf; ++t) patch_tris[m.triangle_quad[t]].push_back(t);
  PatchGrid out;
  std::unordered_map<int, int> layout_id;                   // layout vertex -> grid vertex
  std::vector<std::unordered_map<int, int>> edge_point(L.num_surface_edges);  // position along -> grid vertex
  std::unordered_map<int, int> local;
  for (int q = 0; q < nq; ++q) {
    const auto& tris = patch_tris[q];
    if (tris.empty()) throw Error(ErrorKind::Internal, "extract_patch_grids: layout quad " + std::to_string(q) + " is empty", {q});
    local.clear();
    std::vector<Point2q> uv;
    std::vector<std::array<int, 3>> lt;
    for (int t : tris) {
      std::array<int, 3> T{};
      for (int i = 0; i < 3; ++i) {
        auto [it, fresh] = local.emplace(m.triangles[t][i], static_cast<int>(uv.size()));
        if (fresh) uv.push_back(corner_uv[t][i]);
        T[i] = it->second;
      }
      lt.push_back(T);
    }
    const PlanarAdjacency adj = PlanarAdjacency::build(static_cast<int>(uv.size()), lt);
    const auto& Q = L.quads[q];
    const int a = sizing.quad_size[q][0], b = sizing.quad_size[q][1];
    int from = lt[0][0];
    auto locate = [&](const Point2q& target) {
      GridVertex v;
      const PlanarLocation loc = locate_point(uv, lt, adj, from, target);
      const auto& T = lt[loc.triangle];
      v.triangle = tris[loc.triangle];
      v.barycentric = {0, 0, 0};
      if (loc.kind == PlanarLocation::Kind::Vertex) {
        v.barycentric[loc.index] = 1;
      } else if (loc.kind == PlanarLocation::Kind::Edge) {
        const int i = loc.index, j = (i + 1) % 3;
        const Rational s = dot(uv[T[i]], target, uv[T[j]]) / dot(uv[T[i]], uv[T[j]], uv[T[j]]);
        v.barycentric[i] = 1 - s;
        v.barycentric[j] = s;
      } else {
        const Point2q &A = uv[T[0]], &B = uv[T[1]], &C = uv[T[2]];
        const Rational area = cross(A, B, C);
        v.barycentric = {cross(target, B, C) / area, cross(A, target, C) / area, cross(A, B, target) / area};
      }
      from = T[0];
      return v;
    };
    auto add = [&](GridVertex v) {
      out.vertices.push_back(std::move(v));
      return static_cast<int>(out.vertices.size()) - 1;
    };
    std::vector<int> grid((a + 1) * (b + 1), -1);
    for (int j = 0; j <= b; ++j)
      for (int ii = 0; ii <= a; ++ii) {
        const int i = (j % 2 == 0) ? ii : a - ii;  // snake order keeps the walks short
        const Point2q target{Rational(i), Rational(j)};
        const bool bi = i == 0 || i == a, bj = j == 0 || j == b;
        int id = -1;
        if (bi && bj) {  // a corner: its layout vertex
          const int k = (j == 0) ? (i == 0 ? 0 : 1) : (i == a ? 2 : 3);
          const int lv = L.layout_vertex[Q[k]];
          auto it = layout_id.find(lv);
          if (it != layout_id.end()) {
            id = it->second;
          } else {
            GridVertex v = locate(target);
            v.layout_vertex = lv;
            id = add(std::move(v));
            layout_id.emplace(lv, id);
          }
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
          const int pos = along ? r : len - r;
          auto& slot = edge_point[L.surface_edge[e]];
          auto it = slot.find(pos);
          if (it != slot.end()) {
            id = it->second;
          } else {
            id = add(locate(target));
            slot.emplace(pos, id);
          }
        } else {
          id = add(locate(target));
        }
        grid[j * (a + 1) + i] = id;
      }
    for (int j = 0; j < b; ++j)
      for (int i = 0; i < a; ++i) {
        out.quads.push_back({grid[j * (a + 1) + i], grid[j * (a + 1) + i + 1], grid[(j + 1) * (a + 1) + i + 1],
                             grid[(j + 1) * (a + 1) + i]});
        out.quad_patch.push_back(q);
      }
  }
  return out;
}

}  // namespace igm
