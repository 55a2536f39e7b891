// Benchmark of the planar IGM core: exact template overlay, piecewise-affine charts and quad
// extraction on synthetic disks (fan of a rational near-regular 4g-gon, midpoint-subdivided,
// random face splits, half of the interior vertices perturbed exactly).
// Usage: igm_bench_arrange [max_triangles=200000]. Times are CPU seconds.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "igm/arrange/overlay.h"
#include "igm/arrange/quad_template.h"
#include "igm/arrange/synthetic_disk.h"
#include "igm/extract/quad_extract.h"
#include "igm/igm/quad_charts.h"

using namespace igm;
// CPU seconds of this process (the bench machine is shared, so wall time says little).
static double since(std::clock_t t) { return double(std::clock() - t) / CLOCKS_PER_SEC; }

int main(int argc, char** argv) {
  const long max_tris = argc > 1 ? std::atol(argv[1]) : 200000;
  std::printf("%5s %9s %9s %6s %9s %9s %8s %9s %8s %9s %7s\n", "g", "in_tris", "out_tris", "ratio", "overlay_s", "charts_s",
              "in_bits", "out_bits", "uv_bits", "N=8_s", "quads");
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
      const QuadTemplate t = make_quad_template(corners, centre);
      const auto segs = template_segments(t);
      const auto geo = template_geometry(t, segs);
      auto t0 = std::clock();
      const OverlayResult ov = overlay_segments(disk, geo);
      const double t_overlay = since(t0);
      t0 = std::clock();
      const QuadCharts ch = compute_quad_charts(t, ov);
      const double t_charts = since(t0);
      t0 = std::clock();
      const PlanarQuadMesh qm = extract_quads(t, ov, ch, 8, SidePairing::canonical(g));
      const double t_extract = since(t0);
      std::size_t in_bits = 0;
      for (const auto& p : disk.positions) in_bits = std::max({in_bits, bit_size(p.x), bit_size(p.y)});
      std::printf("%5d %9zu %9zu %6.3f %9.3f %9.3f %8zu %9zu %8zu %9.3f %7zu\n", g, disk.triangles.size(),
                  ov.mesh.triangles.size(), double(ov.mesh.triangles.size()) / double(disk.triangles.size()), t_overlay,
                  t_charts, in_bits, ov.stats.max_coordinate_bits, ch.max_uv_bits, t_extract, qm.quads.size());
      std::fflush(stdout);
    }
  }
  return 0;
}
