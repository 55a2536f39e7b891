#include "igm/extract/orbifold_quads.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "igm/core/error.h"

namespace igm {

int orbifold_grid_orbits(int N) { return 2 * N * N + 2; }

int orbifold_grid_orbit(int N, long i, long j) {
  const long M = 2L * N;
  i = ((i % M) + M) % M;
  j = ((j % M) + M) % M;
  if (j > N) {  // rotation by pi about the origin: (i, j) -> (-i, -j)
    i = (M - i) % M;
    j = M - j;
  }
  if ((j == 0 || j == N) && i > N) i = M - i;  // bottom and top rows fold about their midpoints
  if (j == 0) return static_cast<int>(i);
  if (j == N) return static_cast<int>((N + 1) + (N - 1) * M + i);
  return static_cast<int>((N + 1) + (j - 1) * M + i);
}

OrbifoldQuadMesh extract_orbifold_quads(const std::vector<std::array<int, 3>>& tris, const std::vector<Point2q>& uv,
                                        int N) {
  if (N < 1 || N > 4096)
    throw Error(ErrorKind::InvalidArgument, "resolution must be in 1..4096, got " + std::to_string(N));
  OrbifoldQuadMesh q;
  q.resolution = N;
  const int orbits = orbifold_grid_orbits(N);
  q.grid.assign(orbits, {0, 0});
  q.triangle.assign(orbits, -1);
  q.barycentric.resize(orbits);
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < 2 * N; ++i)
      q.quads.push_back({orbifold_grid_orbit(N, i, j), orbifold_grid_orbit(N, i + 1, j),
                         orbifold_grid_orbit(N, i + 1, j + 1), orbifold_grid_orbit(N, i, j + 1)});
  // Canonical representatives: the lowest (j, i) in the domain.
  for (int j = N; j >= 0; --j)
    for (int i = 2 * N; i >= 0; --i) q.grid[orbifold_grid_orbit(N, i, j)] = {i, j};
  q.cone_vertices = {orbifold_grid_orbit(N, N, 0), orbifold_grid_orbit(N, 0, 0), orbifold_grid_orbit(N, 0, N),
                     orbifold_grid_orbit(N, N, N)};

  const Rational invN(1, N);
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
      const double L = std::ceil(N * lo - margin), H = std::floor(N * hi + margin);  // candidates L..H
      if (!(L > -0x1p40 && H < 0x1p40))
        throw Error(ErrorKind::Internal, "extract_orbifold_quads: UV of triangle " + std::to_string(f) + " out of range",
                    {static_cast<std::int64_t>(f)});
      range[d][0] = static_cast<long>(L);
      range[d][1] = static_cast<long>(H);
    }
    for (long i = range[0][0]; i <= range[0][1]; ++i)
      for (long j = range[1][0]; j <= range[1][1]; ++j) {
        const int orbit = orbifold_grid_orbit(N, i, j);
        if (q.triangle[orbit] >= 0) continue;
        const Point2q p{Rational(i) * invN, Rational(j) * invN};
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
        q.triangle[orbit] = static_cast<int>(f);
        q.barycentric[orbit] = {Rational(area2(p, b, c) / total), Rational(area2(a, p, c) / total),
                                Rational(area2(a, b, p) / total)};
        ++found;
      }
  }
  if (found != orbits) {
    int missing = 0;
    while (q.triangle[missing] >= 0) ++missing;
    throw Error(ErrorKind::Internal, "extract_orbifold_quads: grid point (" + std::to_string(q.grid[missing][0]) + "/" +
                                         std::to_string(N) + ", " + std::to_string(q.grid[missing][1]) + "/" +
                                         std::to_string(N) + ") lies in no disk triangle",
                {missing});
  }
  return q;
}

}  // namespace igm
