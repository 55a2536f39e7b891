#include "igm/igm/patch_maps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <string>

#include "../core/parallel.h"
#include "igm/arrange/planar_walk.h"
#include "igm/core/error.h"

namespace igm {

namespace {

std::string str(std::int64_t x) { return std::to_string(x); }

// The rectangle [0,a] x [0,b]: corner k and the unit direction of side k (Q_k -> Q_(k+1)).
Point2q rect_corner(int k, int a, int b) {
  static constexpr int cx[4] = {0, 1, 1, 0}, cy[4] = {0, 0, 1, 1};
  return {Rational(cx[k] * a), Rational(cy[k] * b)};
}

// Barycentric coordinates of x in (A, B, C) (positive triangle), exactly.
std::array<Rational, 3> barycentric(const Point2q& A, const Point2q& B, const Point2q& C, const Point2q& x) {
  const Rational area = cross(A, B, C);
  return {cross(x, B, C) / area, cross(A, x, C) / area, cross(A, B, x) / area};
}

// Maps the patch of layout quad q (its triangles `tris`) onto its rectangle by a certified Tutte map
// (map_patches); writes its triangles' corner UVs and its statistics.
void map_patch(const QuadLayout& L, const PatchMesh& m, const Sizing& sizing,
               const std::vector<std::vector<Rational>>& params, const std::vector<int>& tris, int q,
               const PatchMapOptions& options, std::vector<std::array<Point2q, 3>>& corner_uv, PatchMapStats& st) {
  if (tris.empty()) throw Error(ErrorKind::Internal, "map_patches: layout quad " + str(q) + " has no triangle", {q});
  const int a = sizing.quad_size[q][0], b = sizing.quad_size[q][1];
  std::unordered_map<int, int> local;
  std::vector<int> plane;  // local -> plane id
  std::vector<std::array<int, 3>> lt;
  lt.reserve(tris.size());
  for (int t : tris) {
    std::array<int, 3> T{};
    for (int i = 0; i < 3; ++i) {
      auto [it, fresh] = local.emplace(m.triangles[t][i], static_cast<int>(plane.size()));
      if (fresh) plane.push_back(m.triangles[t][i]);
      T[i] = it->second;
    }
    lt.push_back(T);
  }
  std::vector<int> boundary;
  std::vector<Point2q> boundary_uv;
  for (int k = 0; k < 4; ++k) {
    const int e = L.quad_edge[q][k];
    const bool fwd = L.quad_edge_forward[q][k];
    const auto& c = m.edge_chain[e];
    const auto& t = params[e];
    const int len = (k % 2 == 0) ? a : b;
    const Point2q R = rect_corner(k, a, b);
    const std::size_t n = c.size() - 1;
    for (std::size_t i = 0; i < n; ++i) {  // the side's last vertex is the next side's first
      const int v = fwd ? c[i] : c[n - i];
      const Rational tau = fwd ? t[i] : Rational(1 - t[n - i]);
      auto it = local.find(v);
      if (it == local.end())
        throw Error(ErrorKind::Internal, "map_patches: a vertex of layout edge " + str(e) + " is in no triangle of quad " +
                                             str(q),
                    {q});
      boundary.push_back(it->second);
      const Rational step = tau * len;
      boundary_uv.push_back({Rational(R.x + kDirX[k] * step), Rational(R.y + kDirY[k] * step)});
    }
  }
  std::vector<Vec3d> pos(plane.size());
  for (std::size_t i = 0; i < plane.size(); ++i) {
    const Vec3d& p = m.positions[m.vertex_of[plane[i]]];
    pos[i] = {options.length_scale * p.x, options.length_scale * p.y, options.length_scale * p.z};
  }
  const std::vector<int> w = edge_weights(pos, lt, options.weights);
  TutteResult tr = tutte_embed(static_cast<int>(plane.size()), lt, boundary, boundary_uv, w, options.tutte);
  st.max_patch_vertices = static_cast<int>(plane.size());
  st.flips_double = tr.stats.flips_double;
  st.patches_refined = tr.stats.iterations > 0 ? 1 : 0;
  st.max_refinement_steps = tr.stats.iterations;
  st.max_uv_bits = tr.stats.max_bits;
  for (std::size_t k = 0; k < tris.size(); ++k)
    for (int i = 0; i < 3; ++i) corner_uv[tris[k]][i] = tr.uv[lt[k][i]];
  }

}  // namespace

const char* to_string(PatchMapKind kind) { return kind == PatchMapKind::Tutte ? "tutte" : "affine"; }

std::vector<int> quad_diagonals(const QuadLayout& L) {
  std::vector<int> d;
  d.reserve(L.quads.size());
  for (const auto& Q : L.quads) {
    const Point2q &a = L.points[Q[0]], &b = L.points[Q[1]], &c = L.points[Q[2]], &e = L.points[Q[3]];
    if (a.x + c.x == b.x + e.x && a.y + c.y == b.y + e.y) d.push_back(-1);
    else d.push_back(cmp(dot(a, c, c), dot(b, e, e)) <= 0 ? 0 : 1);
  }
  return d;
}

PatchMaps map_patches(const QuadLayout& L, const PatchMesh& m, const Sizing& sizing,
                      const std::vector<Point2q>& overlay_positions) {
  const auto t_start = std::chrono::steady_clock::now();
  const int nq = static_cast<int>(L.quads.size());
  const int nf = static_cast<int>(m.triangles.size());
  if (static_cast<int>(sizing.quad_size.size()) != nq || static_cast<int>(m.triangle_quad.size()) != nf)
    throw Error(ErrorKind::InvalidArgument, "map_patches: the sizing or the mesh does not match the layout");
  PatchMaps out;
  PatchMapStats& st = out.stats;
  st.patches = nq;
  out.corner_uv.resize(nf);
  std::vector<std::vector<int>> patch_tris(nq);
  for (int t = 0; t < nf; ++t) patch_tris[m.triangle_quad[t]].push_back(t);

  const std::vector<int> diag = quad_diagonals(L);
  for (int q = 0; q < nq; ++q) {
    const auto& Q = L.quads[q];
    const int a = sizing.quad_size[q][0], b = sizing.quad_size[q][1];
    Point2q K[4], U[4];
    for (int k = 0; k < 4; ++k) K[k] = L.points[Q[k]], U[k] = rect_corner(k, a, b);
    for (int t : patch_tris[q]) {
      const auto& T = m.triangles[t];
      for (int v : T)
        if (v < 0 || v >= m.num_overlay_vertices)
          throw Error(ErrorKind::Internal, "map_patches: the affine maps need the overlay's own vertices", {t});
      // The half of the quad the triangle lies in: any corner strictly off the diagonal tells.
      int r0 = 0, r1 = 1, r2 = 2;  // region corners (indices into K/U)
      if (diag[q] >= 0) {
        const int d0 = diag[q] == 0 ? 0 : 1, d1 = d0 + 2;
        Sign side = Sign::Zero;
        for (int i = 0; i < 3 && side == Sign::Zero; ++i) side = orient2d(K[d0], K[d1], overlay_positions[T[i]]);
        if (side == Sign::Zero) throw Error(ErrorKind::Internal, "map_patches: a triangle lies on a diagonal", {t});
        if (diag[q] == 0) {
          if (side == Sign::Negative) r0 = 0, r1 = 1, r2 = 2;
          else r0 = 0, r1 = 2, r2 = 3;
        } else {
          if (side == Sign::Negative) r0 = 1, r1 = 2, r2 = 3;
          else r0 = 0, r1 = 1, r2 = 3;
        }
      } else {
        r0 = 0, r1 = 1, r2 = 3;
      }
      for (int i = 0; i < 3; ++i) {
        const auto w = barycentric(K[r0], K[r1], K[r2], overlay_positions[T[i]]);
        Point2q& uv = out.corner_uv[t][i];
        uv.x = w[0] * U[r0].x + w[1] * U[r1].x + w[2] * U[r2].x;
        uv.y = w[0] * U[r0].y + w[1] * U[r1].y + w[2] * U[r2].y;
        st.max_uv_bits = std::max({st.max_uv_bits, bit_size(uv.x), bit_size(uv.y)});
      }
      if (orient2d(out.corner_uv[t][0], out.corner_uv[t][1], out.corner_uv[t][2]) != Sign::Positive)
        throw Error(ErrorKind::Internal, "map_patches: affine UV triangle " + str(t) + " is not positive", {t});
    }
  }
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return out;
}

}  // namespace igm
