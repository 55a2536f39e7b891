#include "igm/extract/patch_grid.h"

#include <string>
#include <unordered_map>

#include "igm/arrange/planar_walk.h"
#include "igm/core/error.h"
#include "igm/layout/layout_grid.h"

namespace igm {

PatchGrid extract_patch_grids(const QuadLayout& L, const PatchMesh& m, const Sizing& sizing,
                              const std::vector<std::array<Point2q, 3>>& corner_uv) {
  const int nq = static_cast<int>(L.quads.size());
  const int nf = static_cast<int>(m.triangles.size());
  if (static_cast<int>(corner_uv.size()) != nf || static_cast<int>(sizing.quad_size.size()) != nq)
    throw Error(ErrorKind::InvalidArgument, "extract_patch_grids: the UVs or the sizing do not match the mesh");
  std::vector<std::vector<int>> patch_tris(nq);
  for (int t = 0; t < nf; ++t) patch_tris[m.triangle_quad[t]].push_back(t);
  for (int q = 0; q < nq; ++q)
    if (patch_tris[q].empty()) throw Error(ErrorKind::Internal, "extract_patch_grids: layout quad " + std::to_string(q) + " is empty", {q});
  LayoutGrid grid = layout_grid(L, sizing.quad_size);
  PatchGrid out;
  out.quads = std::move(grid.quads);
  out.quad_patch = std::move(grid.quad_patch);
  out.vertices.reserve(grid.vertices.size());
  // Each vertex is located in the patch of its first occurrence; they come patch by patch, in the
  // snake order that keeps the walks short.
  std::unordered_map<int, int> local;
  std::vector<Point2q> uv;
  std::vector<std::array<int, 3>> lt;
  PlanarAdjacency adj;
  int patch = -1, from = -1;
  for (const LayoutGridVertex& g : grid.vertices) {
    const std::vector<int>& tris = patch_tris[g.quad];
    if (g.quad != patch) {  // the patch's UV triangulation
      patch = g.quad;
      local.clear();
      uv.clear();
      lt.clear();
      for (int t : tris) {
        std::array<int, 3> T{};
        for (int i = 0; i < 3; ++i) {
          auto [it, fresh] = local.emplace(m.triangles[t][i], static_cast<int>(uv.size()));
          if (fresh) uv.push_back(corner_uv[t][i]);
          T[i] = it->second;
        }
        lt.push_back(T);
      }
      adj = PlanarAdjacency::build(static_cast<int>(uv.size()), lt);
      from = lt[0][0];
    }
    const Point2q target{Rational(g.i), Rational(g.j)};
    GridVertex v;
    v.layout_vertex = g.layout_vertex;
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
    out.vertices.push_back(std::move(v));
  }
  return out;
}

}  // namespace igm
