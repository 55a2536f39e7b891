// Smoothing benchmark (smooth/smooth.h): the pipeline's IGM of each mesh, then smooth_igm on it:
// time, iterations, symmetric Dirichlet energy first -> last, the area-weighted p99 of the
// conformal distortion s1/s2 before and after, and the certifier's verdict on the result.
// usage: igm_bench_smooth [--iterations N] [--seconds S] [--min-decrease X] [--threads N] [--progress]
//        [--igm NAME.igm.exact ...] [MESH ...]
// (default: elephant, couplingdown, cheese from $IGM_DATA_DIR or ../shared, and a generated
// genus-3 mesh whose IGM has about 100k triangles)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "../tests/support/distortion.h"
#include "certify/obj.h"
#include "igm/core/error.h"
#include "igm/core/threads.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/pipeline/pipeline.h"
#include "igm/smooth/smooth.h"
#include "thread_cpu.h"

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

igm::SmoothOptions g_options;

int g_threads = 0;

// An IGM written by `igm run` (NAME.igm.exact: exact UVs), as the pipeline's result.
igm::PipelineResult load_igm(const std::string& path) {
  igm::PipelineResult r;
  const std::string text = igm::read_file_bytes(path);
  const igm::certify::ObjReadResult obj = igm::certify::read_obj(text);
  if (!obj.ok) throw igm::Error(igm::ErrorKind::Parse, path + ": not an IGM");
  const igm::certify::ObjMesh& m = obj.mesh;
  r.igm.triangles.resize(static_cast<std::size_t>(m.num_faces()));
  r.igm.corner_uv.resize(r.igm.triangles.size());
  for (std::size_t f = 0; f < r.igm.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t corner = m.face_begin[f] + k;
      r.igm.triangles[f][k] = m.corner_vertex[corner];
      const auto& uv = m.uv[m.corner_uv[corner]];
      r.igm.corner_uv[f][k] = {uv[0], uv[1]};
    }
  r.igm.positions = igm::read_soup(text, igm::MeshFormat::Obj).positions;
  return r;
}

void run(const std::string& name, const igm::ValidMesh* mesh, const std::string& igm_path = "") {
  auto t0 = Clock::now();
  igm::PipelineOptions po;
  po.layout = igm::LayoutKind::Spread;  // the topological pipeline (the field layout is the default)
  po.smooth = false;  // the layout's map, smoothed below
  po.threads = g_threads;
  igm::PipelineResult r;
  if (mesh)
    r = igm::compute_igm(*mesh, po);
  else
    r = load_igm(igm_path);
  const double pipeline_s = since(t0);
  t0 = Clock::now();
  const igm::SeamlessStructure s = igm::seamless_structure(r.igm);
  const double seamless_s = since(t0);
  t0 = Clock::now();
  const igm::DyadicResult d = igm::round_to_dyadic(r.igm, s);
  const double dyadic_s = since(t0);
  const double cpu0 = igm_bench::thread_cpu_ns();
  igm::SmoothResult sm;
  igm::with_threads(g_threads, [&] { sm = igm::smooth_igm(r.igm, g_options); });
  const double smooth_cpu = (igm_bench::thread_cpu_ns() - cpu0) * 1e-9;
  const igm::SmoothStats& st = sm.stats;
  std::printf(
      "%-14s g=%-3d IGM F=%-7zu V=%-7zu pipeline %.2fs | structure %.2fs, doubles %s (2^%d) %.2fs "
      "| smooth "
      "%.2fs (cpu %.2fs; setup %.2fs, certify %.2fs), %d it (%s), E %.4g -> %.4g, p99 s1/s2 %.4g "
      "-> %.4g, free %d cones %d, reg %d+%d, factorizations %d, halvings %d, "
      "exact rejections %d, certified %s; solver %s, %zu factor entries, structure %.2fs, analysis %.2fs, "
      "factorizations %.2fs\n",
      name.c_str(), r.stats.genus, r.igm.triangles.size(), r.igm.positions.size(), pipeline_s,
      seamless_s, d.stats.on_grid ? "yes" : "NO", d.stats.grid_exponent, dyadic_s, st.seconds,
      smooth_cpu, st.setup_seconds, st.certify_seconds, st.iterations, igm::to_string(st.stop),
      st.energy.front(), st.energy.back(),
      igm_test::measure_distortion(r.igm, r.igm.corner_uv).p99_conformal,
      igm_test::measure_distortion(r.igm, sm.corner_uv).p99_conformal, st.free_vertices, st.cones,
      st.enlarged_references, st.fattened_references, st.factorizations, st.step_halvings, st.exact_rejections,
      st.certified ? "yes" : "NO", st.supernodal ? "supernodal" : "simplicial", st.factor_entries,
      st.structure_seconds, st.analyze_seconds, st.factorize_seconds);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::string> meshes, igms;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--iterations" && i + 1 < argc)
        g_options.max_iterations = std::atoi(argv[++i]);
      else if (a == "--seconds" && i + 1 < argc)
        g_options.time_budget_seconds = std::atof(argv[++i]);
      else if (a == "--threads" && i + 1 < argc)
        g_threads = std::atoi(argv[++i]);
      else if (a == "--min-decrease" && i + 1 < argc)
        g_options.min_relative_decrease = std::atof(argv[++i]);
      else if (a == "--igm" && i + 1 < argc)
        igms.push_back(argv[++i]);
      else if (a == "--progress")
        g_options.progress = [](const igm::SmoothProgress& p) {
          std::printf("  it %3d  E %.6g  step %.3g  %.2fs\n", p.iteration, p.energy, p.step,
                      p.seconds);
          std::fflush(stdout);
        };
      else
        meshes.push_back(a);
    }
    if (!meshes.empty() || !igms.empty()) {
      for (const std::string& m : meshes) {
        const igm::ValidMesh mesh = igm::load_mesh(m);
        run(std::filesystem::path(m).stem().string(), &mesh);
      }
      for (const std::string& m : igms) run(std::filesystem::path(m).stem().string(), nullptr, m);
      return 0;
    }
    const char* env = std::getenv("IGM_DATA_DIR");
    const std::filesystem::path data = env && *env ? env : "../shared";
    for (const char* m : {"elephant", "couplingdown", "cheese"}) {
      const auto path = data / "meshes" / "clean" / (std::string(m) + ".off");
      if (std::filesystem::exists(path)) {
        const igm::ValidMesh mesh = igm::load_mesh(path);
        run(m, &mesh);
      }
      else
        std::printf("%s: not found (set IGM_DATA_DIR)\n", path.string().c_str());
    }
    igm::GenerateOptions g;
    g.genus = 3;
    g.faces = 83000;  // an IGM of about 100k triangles
    const igm::ValidMesh mesh = igm::validate(igm::generate_closed_mesh(g));
    run("generated-g3", &mesh);
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
