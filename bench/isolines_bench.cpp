// Benchmark of extract_isolines (include/igm/extract/isolines.h): the pipeline's IGM of a
// generated mesh, its UVs scaled by an integer so that the isoline quads number about --quads,
// then the extraction (certifier, grid points, traces, quads) timed per phase (wall; CPU of the
// whole call: the machine is shared).
// usage: igm_bench_isolines [--genus G] [--faces F] [--quads Q] [--repeat R]
//        (defaults: genus 2, 20000 faces, 100000 quads, 3 repetitions)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "igm/core/error.h"
#include "igm/extract/isolines.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/pipeline/pipeline.h"
#include "thread_cpu.h"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  int genus = 2, repeat = 3;
  long faces = 20000, quads = 100000;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const long v = std::atol(argv[i + 1]);
    if (a == "--genus")
      genus = static_cast<int>(v);
    else if (a == "--faces")
      faces = v;
    else if (a == "--quads")
      quads = v;
    else if (a == "--repeat")
      repeat = static_cast<int>(v);
    else {
      std::fprintf(stderr,
                   "usage: igm_bench_isolines [--genus G] [--faces F] [--quads Q] [--repeat R]\n");
      return 2;
    }
  }
  try {
    igm::GenerateOptions g;
    g.genus = genus;
    g.faces = faces;
    const igm::ValidMesh mesh = igm::validate(igm::generate_closed_mesh(g));
    igm::PipelineOptions po;
    po.layout = igm::LayoutKind::Spread;  // the topological pipeline (the field layout is the default)
    po.resolution = 3;
    auto t0 = Clock::now();
    const igm::PipelineResult r = igm::compute_igm(mesh, po);
    std::printf("pipeline: genus %d, %d faces -> IGM %zu triangles, %d layout quads, %.2f s\n",
                genus, mesh.mesh.num_faces(), r.igm.triangles.size(), r.stats.layout_quads,
                since(t0));
    // The pipeline's IGM has one UV unit per layout quad (a domain of 2 for genus 0).
    const long scale = std::max(1L, std::lround(std::sqrt(double(quads) / r.stats.layout_quads)));
    igm::IsolineInput in;
    in.triangles = r.igm.triangles;
    in.corner_uv = r.igm.corner_uv;
    in.positions = r.igm.positions;
    for (auto& t : in.corner_uv)
      for (igm::Point2q& p : t) {
        p.x *= scale;
        p.y *= scale;
      }
    std::printf("scale %ld: expect %ld quads\n", scale, r.stats.layout_quads * scale * scale);
    for (int k = 0; k < repeat; ++k) {
      t0 = Clock::now();
      const double cpu0 = igm_bench::thread_cpu_ns();
      const igm::IsolineResult x = igm::extract_isolines(in);
      const double total = since(t0), cpu = (igm_bench::thread_cpu_ns() - cpu0) * 1e-9;
      if (!x.quads) {
        std::printf("REJECTED: %s\n", igm::certify::summary(x.report).c_str());
        return 1;
      }
      const igm::IsolineStats& s = x.quads->stats;
      std::printf(
          "run %d: %zu quads, %zu vertices (%lld on vertices, %lld on edges, %lld in faces, %lld "
          "cones) "
          "in %.3f s (CPU %.3f s): certify %.3f, grid %.3f (%lld rows), trace %.3f (%lld traces, "
          "%lld steps, max %lld, "
          "bound %lld, %lld vertex crossings), quads+output %.3f\n",
          k, x.quads->quads.size(), x.quads->vertices.size(), (long long)s.grid_points_on_vertices,
          (long long)s.grid_points_on_edges, (long long)s.grid_points_in_faces, (long long)s.cones,
          total, cpu, s.seconds_certify, s.seconds_grid, (long long)s.rows_scanned, s.seconds_trace,
          (long long)s.traces, (long long)s.trace_steps, (long long)s.max_trace_steps,
          (long long)s.trace_step_bound, (long long)s.vertex_crossings, s.seconds_quads);
    }
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
