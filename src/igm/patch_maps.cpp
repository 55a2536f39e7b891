#include "igm/igm/patch_maps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

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
