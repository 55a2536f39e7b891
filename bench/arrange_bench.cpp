// Benchmark of the exact overlay of a quad layout (with the quads' diagonals, as the affine maps
// need them) on synthetic disks (fan of a rational near-regular 4g-gon, midpoint-subdivided, random
// face splits, half of the interior vertices perturbed exactly).
// Usage: igm_bench_arrange [max_triangles=200000]. Times are CPU seconds.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "igm/arrange/overlay.h"
#include "igm/arrange/synthetic_disk.h"
#include "igm/embed/polygon.h"
#include "igm/igm/patch_maps.h"
#include "igm/layout/quad_layout.h"

using namespace igm;
// CPU seconds of this process (the bench machine is shared, so wall time says little).
static double since(std::clock_t t) { return double(std::clock() - t) / CLOCKS_PER_SEC; }

int main(int argc, char** argv) {
  const long max_tris = argc > 1 ? std::atol(argv[1]) : 200000;
  std::printf("%5s %-7s %9s %9s %6s %9s %8s %9s\n", "g", "layout", "in_tris", "out_tris", "ratio", "overlay_s", "in_bits",
              "out_bits");
  for (int g : {2, 9, 133}) {
    for (long target : {10000L, 50000L, 200000L}) {
      if (target > max_tris) continue;
      const auto corners = rational_circle_polygon(4 * g);
      const Point2q centre{Rational(0), Rational(0)};
      SyntheticDiskOptions o;
      o.subdivisions = 0;
      while (4L * g * (1L << (2 * (o.subdivisions + 1))) <= target) ++o.subdivisions;
      o.insertions = static_cast<int>(std::max(0L, (target - 4L * g * (1L << (2 * o.subdivisions))) / 2));
      o.perturb = 0.5;
      o.seed = 42;
      const PlanarTriangulation disk = make_synthetic_disk(corners, centre, o);
      const std::vector<int> mates = canonical_side_mates(g);
      for (LayoutKind kind : {LayoutKind::Paper, LayoutKind::Spread}) {
        LayoutOptions lo;
        lo.kind = kind;
        const QuadLayout L = make_layout(corners, centre, mates, lo);
        std::vector<Segment2> geo;
        for (const LayoutEdge& e : L.edges) geo.push_back({L.points[e.a], L.points[e.b]});
        const std::vector<int> d = quad_diagonals(L);
        for (std::size_t q = 0; q < d.size(); ++q)
          if (d[q] >= 0) geo.push_back({L.points[L.quads[q][d[q]]], L.points[L.quads[q][d[q] + 2]]});
        const auto t0 = std::clock();
        const OverlayResult ov = overlay_segments(disk, geo);
        const double t_overlay = since(t0);
        std::size_t in_bits = 0;
        for (const auto& p : disk.positions) in_bits = std::max({in_bits, bit_size(p.x), bit_size(p.y)});
        std::printf("%5d %-7s %9zu %9zu %6.3f %9.3f %8zu %9zu\n", g, to_string(kind), disk.triangles.size(),
                    ov.mesh.triangles.size(), double(ov.mesh.triangles.size()) / double(disk.triangles.size()), t_overlay,
                    in_bits, ov.stats.max_coordinate_bits);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
