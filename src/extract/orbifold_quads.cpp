#include "igm/extract/orbifold_quads.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "igm/core/error.h"

namespace igm {

int orbifold_grid_orbits(int N) { return orbifold_grid_orbits(N, N); }
int orbifold_grid_orbits(int nx, int ny) { return 2 * nx * ny + 2; }

int orbifold_grid_orbit(int N, long i, long j) { return orbifold_grid_orbit(N, N, i, j); }

int orbifold_grid_orbit(int nx, int ny, long i, long j) {
  const long Mx = 2L * nx, My = 2L * ny;
  i = ((i % Mx) + Mx) % Mx;
  j = ((j % My) + My) % My;
  if (j > ny) {  // rotation by pi about the origin: (i, j) -> (-i, -j)
    i = (Mx - i) % Mx;
    j = My - j;
  }
  if ((j == 0 || j == ny) && i > nx) i = Mx - i;  // bottom and top rows fold about their midpoints
  if (j == 0) return static_cast<int>(i);
  if (j == ny) return static_cast<int>((nx + 1) + (ny - 1) * Mx + i);
  return static_cast<int>((nx + 1) + (j - 1) * Mx + i);
}

OrbifoldQuadMesh extract_orbifold_quads(const std::vector<std::array<int, 3>>& tris, const std::vector<Point2q>& uv,
                                        int N) {
  return extract_orbifold_quads(tris, uv, N, N);
}

OrbifoldQuadMesh extract_orbifold_quads(const std::vector<std::array<int, 3>>& tris, const std::vector<Point2q>& uv,
                                        int nx, int ny) {
  if (nx < 1 || nx > 4096 || ny < 1 || ny > 4096)
    throw Error(ErrorKind::InvalidArgument, "resolution must be in 1..4096, got " + std::to_string(nx) + " x " +
                                                std::to_string(ny));
  OrbifoldQuadMesh q;
  q.resolution = nx;
  q.resolution_y = ny;
  const int orbits = orbifold_grid_orbits(nx, ny);
  auto orbit = [&](long i, long j) { return orbifold_grid_orbit(nx, ny, i, j); };
  q.grid.assign(orbits, {0, 0});
  q.triangle.assign(orbits, -1);
  q.barycentric.resize(orbits);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < 2 * nx; ++i) q.quads.push_back({orbit(i, j), orbit(i + 1, j), orbit(i + 1, j + 1), orbit(i, j + 1)});
  // Canonical representatives: the lowest (j, i) in the domain.
  for (int j = ny; j >= 0; --j)
    for (int i = 2 * nx; i >= 0; --i) q.grid[orbit(i, j)] = {i, j};
  q.cone_vertices = {orbit(nx, 0), orbit(0, 0), orbit(0, ny), orbit(nx, ny)};

  const int N = std::max(nx, ny);  // the filter's margin below holds for the larger count
  const int scale[2] = {nx, ny};
  const Rational inv[2] = {Rational(1, nx), Rational(1, ny)};
  std::vector<Vec2d> uvd(uv.size());  // for the candidate filter only
  for (std::size_t v = 0; v < uv.size(); ++v) uvd[v] = {approximate(uv[v].x), approximate(uv[v].y)};
  int found = 0;
  for (std::size_t f = 0; f < tris.size() && found < orbits; ++f) {  // bound: F triangles
    const Point2q& a = uv[tris[f][0]];
    const Point2q& b = uv[tris[f][1]];
    const Point2q& c = uv[tris[f][2]];
    // Double filter: |x - xd| < 2^-51 |xd| + 2^-1074 (igm::approximate), and N * xd rounds with
    // relative error 2^-53, so a margin of 2^-30 N (1 + |xd|) grid units keeps every candidate.
    long range[2][2];
    for (int d = 0; d < 2; ++d) {
      double lo = HUGE_VAL, hi = -HUGE_VAL;
      for (int corner = 0; corner < 3; ++corner) {
        const Vec2d& p = uvd[tris[f][corner]];
        const double v = d == 0 ? p.x : p.y;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      const double margin = 0x1p-30 * N * (1 + std::max(std::fabs(lo), std::fabs(hi)));
      const double L = std::ceil(scale[d] * lo - margin), H = std::floor(scale[d] * hi + margin);  // candidates L..H
      if (!(L > -0x1p40 && H < 0x1p40))
        throw Error(ErrorKind::Internal, "extract_orbifold_quads: UV of triangle " + std::to_string(f) + " out of range",
                    {static_cast<std::int64_t>(f)});
      range[d][0] = static_cast<long>(L);
      range[d][1] = static_cast<long>(H);
    }
    for (long i = range[0][0]; i <= range[0][1]; ++i)
      for (long j = range[1][0]; j <= range[1][1]; ++j) {
        const int o = orbit(i, j);
        if (q.triangle[o] >= 0) continue;
        const Point2q p{Rational(i) * inv[0], Rational(j) * inv[1]};
        if (orient2d(a, b, p) == Sign::Negative || orient2d(b, c, p) == Sign::Negative ||
            orient2d(c, a, p) == Sign::Negative)
          continue;
        // Exact barycentric coordinates: areas of the sub-triangles over the area.
        auto area2 = [](const Point2q& u, const Point2q& v, const Point2q& w) {
          Rational r = (v.x - u.x) * (w.y - u.y) - (v.y - u.y) * (w.x - u.x);
          return r;
        };
        const Rational total = area2(a, b, c);
        if (sgn(total) <= 0)
          throw Error(ErrorKind::Internal, "extract_orbifold_quads: triangle " + std::to_string(f) + " is not positive",
                      {static_cast<std::int64_t>(f)});
        q.triangle[o] = static_cast<int>(f);
        q.barycentric[o] = {Rational(area2(p, b, c) / total), Rational(area2(a, p, c) / total),
                                Rational(area2(a, b, p) / total)};
        ++found;
      }
  }
  if (found != orbits) {
    int missing = 0;
    while (q.triangle[missing] >= 0) ++missing;
    throw Error(ErrorKind::Internal, "extract_orbifold_quads: grid point (" + std::to_string(q.grid[missing][0]) + "/" +
                                         std::to_string(nx) + ", " + std::to_string(q.grid[missing][1]) + "/" +
                                         std::to_string(ny) + ") lies in no disk triangle",
                {missing});
  }
  return q;
}

}  // namespace igm
