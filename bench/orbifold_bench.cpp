// Genus-0 benchmark: sphere cut, orbifold Tutte embedding (factorization, solve, refinement,
// checks), quad extraction and the whole pipeline (with the certifier), refinement steps, bits,
// peak memory (getrusage, process-wide: meshes run smallest first).
// usage: igm_bench_orbifold [MESH ...]   (default: armadillo from $IGM_DATA_DIR or ../shared, and a
// generated 1M-face sphere); --refine K also runs the embedding with K forced refinement steps.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/embed/orbifold_tutte.h"
#include "igm/extract/orbifold_quads.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/pipeline/pipeline.h"
#include "igm/topology/sphere_cut.h"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double peak_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

void run(const std::string& name, const igm::ValidMesh& mesh, int forced) {
  std::printf("== %s: V=%d F=%d\n", name.c_str(), mesh.mesh.num_vertices(), mesh.mesh.num_faces());
  auto t0 = Clock::now();
  const igm::SphereCut cut = igm::cut_sphere(mesh.mesh, mesh.positions);
  const double t_cut = since(t0);
  std::printf("  cut      %.3f s  cones %d %d %d %d, path %d edges (legs %d %d %d), %d cone + %d chord splits, V %d -> %d\n",
              t_cut, cut.cones[0], cut.cones[1], cut.cones[2], cut.cones[3], cut.stats.path_edges, cut.stats.leg_edges[0],
              cut.stats.leg_edges[1], cut.stats.leg_edges[2], cut.stats.cone_splits, cut.stats.chord_splits,
              cut.stats.vertices_before, cut.stats.vertices_after);
  for (int min_it : {0, forced}) {
    if (min_it < 0) continue;
    igm::RefinementOptions ro;
    ro.min_iterations = min_it;
    ro.max_iterations = std::max(40, min_it);
    t0 = Clock::now();
    const igm::OrbifoldTutteResult e = igm::orbifold_tutte_embed(cut, ro);
    const double t_embed = since(t0);
    const igm::RefinementStats& r = e.stats.refinement;
    std::printf("  embed    %.3f s  (min_iterations %d) %d free vertices: assemble %.3f, factor %.3f (%zu entries), "
                "solve %.3f, refine %.3f, checks %.3f s; flips in double %lld, steps %d, grid 2^-%lld, bits %zu, "
                "fallback %s\n",
                t_embed, min_it, e.stats.free_vertices, e.stats.seconds_assemble, r.seconds_factorization,
                r.factor_entries, r.seconds_solve, r.seconds_refinement, r.seconds_checks,
                static_cast<long long>(r.flips_double), r.iterations, static_cast<long long>(r.grid_exponent),
                e.stats.max_bits, r.exact_fallback ? "yes" : "no");
    if (min_it == 0) {
      t0 = Clock::now();
      const igm::OrbifoldQuadMesh q = igm::extract_orbifold_quads(cut.disk_triangles, e.uv, 4);
      std::printf("  extract  %.3f s  N=4: %zu quads, %zu vertices\n", since(t0), q.quads.size(), q.triangle.size());
    }
    if (forced <= 0) break;
  }
  igm::PipelineOptions o;
  o.layout = igm::LayoutKind::Spread;  // the topological pipeline (the field layout is the default)
  o.resolution = 4;
  t0 = Clock::now();
  const igm::PipelineResult p = igm::compute_igm(mesh, o);
  const double total = since(t0);
  std::printf("  pipeline %.3f s:", total);
  for (const igm::StageEvent& s : p.stats.stages) std::printf(" %s %.3f", s.stage.c_str(), s.seconds);
  std::printf(" | steps %d, UV bits %zu, certified %s, peak %.0f MB\n", p.stats.orbifold.refinement.iterations,
              p.stats.max_uv_bits, p.certified() ? "yes" : "NO", peak_mb());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    int forced = -1;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--refine" && i + 1 < argc)
        forced = std::atoi(argv[++i]);
      else
        files.push_back(a);
    }
    if (!files.empty()) {
      for (const std::string& f : files) run(std::filesystem::path(f).stem().string(), igm::load_mesh(f), forced);
      return 0;
    }
    const char* env = std::getenv("IGM_DATA_DIR");
    const std::filesystem::path data = env && *env ? env : "../shared";
    const auto armadillo = data / "meshes" / "clean" / "armadillo.off";
    if (std::filesystem::exists(armadillo))
      run("armadillo", igm::load_mesh(armadillo), forced);
    else
      std::printf("%s: not found (set IGM_DATA_DIR)\n", armadillo.string().c_str());
    igm::GenerateOptions g;
    g.genus = 0;
    g.faces = 1000000;
    run("sphere-1M", igm::validate(igm::generate_closed_mesh(g)), forced);
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "igm_bench_orbifold: %s\n", e.what());
    return 1;
  }
  return 0;
}
