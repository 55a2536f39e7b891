// The quality table (docs/quality.md) of the pipeline's outputs over the shared clean meshes and
// generated meshes, several configurations side by side in one run: the paper's map as it was (its
// template, the disk's affine map, N = 4 per layout edge, uniform Tutte weights and uniform side
// parameters) against the layouts of layout/quad_layout.h with sizing and per-patch maps.
// usage: igm_bench_layouts [--quads Q] [--config NAME ...] [--only MESH ...] [--generated G,G,...]
//   configs: before, paper, kite, spread, field (the field layout, its fallback named on the line), and the spread layout with one choice changed: s-nosm
//   (not smoothed), s-udisk
//   (uniform disk map, uniform sides), s-cotan, s-unif (cotangent or uniform patch weights),
//   s-affine (the affine map), s-d1e-2 .. s-d1e-4 and s-it100 (smoothing's relative-decrease stop);
//   default: all. Every output is certified or the line says NOT CERTIFIED.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/pipeline/pipeline.h"

namespace {

struct Config {
  std::string name;
  igm::PipelineOptions options;
};

std::vector<Config> configs(std::int64_t quads) {
  std::vector<Config> c;
  igm::PipelineOptions before;
  before.layout = igm::LayoutKind::Paper;
  before.patch_map = igm::PatchMapKind::Affine;
  before.resolution = 4;
  before.disk_weights = igm::WeightKind::Uniform;
  before.disk_arc_length = false;
  before.patch_weights = igm::WeightKind::Uniform;  // genus 0: the orbifold map as it was
  before.smooth = false;
  c.push_back({"before", before});
  for (igm::LayoutKind kind : {igm::LayoutKind::Paper, igm::LayoutKind::Kite, igm::LayoutKind::Spread, igm::LayoutKind::Field}) {
    igm::PipelineOptions o;
    o.layout = kind;
    o.quads = quads;
    c.push_back({igm::to_string(kind), o});
  }
  // Ablations of the spread layout (the topological default): one choice changed each (docs/layouts.md).
  const auto spread = [] {
    igm::PipelineOptions s;
    s.layout = igm::LayoutKind::Spread;
    return s;
  };
  igm::PipelineOptions o = spread();
  o.quads = quads;
  o.smooth = false;
  c.push_back({"s-nosm", o});  // the layout's map as it is, unsmoothed
  o = spread();
  o.quads = quads;
  o.disk_weights = igm::WeightKind::Uniform;
  o.disk_arc_length = false;
  c.push_back({"s-udisk", o});  // the disk's map with uniform weights and uniformly spaced sides
  o = spread();
  o.quads = quads;
  o.patch_weights = igm::WeightKind::Cotan;
  c.push_back({"s-cotan", o});
  o.patch_weights = igm::WeightKind::Uniform;
  c.push_back({"s-unif", o});
  o = spread();
  o.quads = quads;
  o.patch_map = igm::PatchMapKind::Affine;
  c.push_back({"s-affine", o});
  // Smoothing's stop (PipelineOptions::smooth_min_decrease; bench/README.md, "Smoothing's stop"):
  // s-dX stops after an iteration that lowers the energy by less than X of it, s-it100 runs the
  // 100 iterations (the stall rule and convergence stop all of them too).
  for (const char* x : {"1e-2", "3e-3", "1e-3", "3e-4", "1e-4"}) {
    o = spread();
    o.quads = quads;
    o.smooth_min_decrease = std::atof(x);
    c.push_back({std::string("s-d") + x, o});
  }
  o.smooth_min_decrease = 0;
  c.push_back({"s-it100", o});
  return c;
}

void header() {
  std::printf("%-16s %-8s %6s %6s | %6s %6s %6s %6s %6s | %5s %5s | %7s %6s %6s | %6s %6s | %7s %7s %6s | %6s\n", "mesh",
              "config", "layout", "quads", "SJmed", "SJp5", "SJmin", "<0.5%", "<=0%", "dev50", "dev95", "ap95/5",
              "A/in", "half%", "dmax%", "d99%", "conf99", "area99", "SD", "sec");
}

void run(const std::string& name, const igm::ValidMesh& mesh, const Config& c) {
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const igm::PipelineResult r = igm::compute_igm(mesh, c.options);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const igm::QuadQuality& q = r.quad_quality;
    const igm::IgmQuality& m = r.igm_quality;
    std::printf("%-16s %-8s %6d %6d | %6.3f %6.3f %6.2f %6.1f %6.1f | %5.1f %5.1f | %7.1f %6.3f %6.1f | %6.2f %6.2f | %7.3g %7.3g %6.3g | %6.2f%s%s\n",
                name.c_str(), c.name.c_str(), r.stats.layout_quads, r.stats.quads, q.sj_median, q.sj_p5, q.sj_min,
                100 * q.sj_below_half, 100 * q.sj_nonpositive, q.angle_deviation_median, q.angle_deviation_p95,
                q.area_p95_over_p5, q.area_ratio, 100 * q.smallest_half_area, 100 * q.distance_max,
                100 * q.distance_p99, m.conformal.p99, m.area.p99, m.symmetric_dirichlet, sec,
                r.certified() ? "" : "  NOT CERTIFIED", r.stats.layout_fallback.empty() ? "" : ("  fallback: " + r.stats.layout_fallback).c_str());
  } catch (const igm::Error& e) {
    std::printf("%-16s %-8s error: %s\n", name.c_str(), c.name.c_str(), e.what());
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::int64_t quads = igm::kDefaultQuads;
  std::set<std::string> only, wanted;
  std::vector<int> generated = {1, 2, 3, 5, 8, 12, 20, 30, 50};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quads" && i + 1 < argc) quads = std::atoll(argv[++i]);
    else if (a == "--config" && i + 1 < argc) wanted.insert(argv[++i]);
    else if (a == "--only" && i + 1 < argc) only.insert(argv[++i]);
    else if (a == "--generated" && i + 1 < argc) {
      generated.clear();
      std::stringstream ss(argv[++i]);
      for (std::string g; std::getline(ss, g, ',');) generated.push_back(std::atoi(g.c_str()));
    } else {
      std::fprintf(stderr, "usage: igm_bench_layouts [--quads Q] [--config NAME ...] [--only MESH ...] [--generated G,G,...]\n");
      return 2;
    }
  }
  std::vector<Config> cs;
  for (const Config& c : configs(quads))
    if (wanted.empty() || wanted.count(c.name)) cs.push_back(c);
  const char* env = std::getenv("IGM_DATA_DIR");
  const std::filesystem::path data = env && *env ? env : "../shared";
  std::vector<std::pair<std::string, igm::ValidMesh>> meshes;
  for (const char* m : {"pipe", "mpi_triang", "knot", "eight", "joint", "helmet", "elephant", "anchor", "couplingdown",
                        "cheese"}) {
    if (!only.empty() && !only.count(m)) continue;
    const auto path = data / "meshes" / "clean" / (std::string(m) + ".off");
    if (std::filesystem::exists(path)) meshes.emplace_back(m, igm::load_mesh(path));
    else std::printf("%s: not found (set IGM_DATA_DIR)\n", path.string().c_str());
  }
  for (int g : generated) {
    const std::string name = "gen-g" + std::to_string(g);
    if (!only.empty() && !only.count(name)) continue;
    igm::GenerateOptions o;
    o.genus = g;
    o.faces = std::max<std::int64_t>(20000, 2000 * g);
    o.seed = 1;
    meshes.emplace_back(name, igm::validate(igm::generate_closed_mesh(o)));
  }
  header();
  for (const auto& [name, mesh] : meshes)
    for (const Config& c : cs) run(name, mesh, c);
  return 0;
}
