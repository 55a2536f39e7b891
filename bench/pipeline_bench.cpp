// Pipeline benchmark: time per stage, peak memory, output/input triangles and UV bits.
// usage: igm_bench_pipeline [--normal-form] [MESH ...]   (default: the shared meshes of the issues, from
// $IGM_DATA_DIR or ../shared, plus generated tori of 100k and 1M faces)
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/pipeline/pipeline.h"

namespace {

double peak_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

bool g_normal_form = false;

void run(const std::string& name, const igm::ValidMesh& mesh) {
  igm::PipelineOptions o;
  o.layout = igm::LayoutKind::Spread;  // the topological pipeline (the field layout is the default)
  o.resolution = 4;
  o.normal_form = g_normal_form;
  const igm::PipelineResult r = igm::compute_igm(mesh, o);
  double total = 0;
  std::printf("%-22s g=%-3d F=%-8d nf=%d", name.c_str(), r.stats.genus, r.stats.input_faces, o.normal_form ? 1 : 0);
  for (const igm::StageEvent& e : r.stats.stages) {
    std::printf(" %s %.2fs", e.stage.c_str(), e.seconds);
    total += e.seconds;
  }
  std::printf(" | total %.2fs, out/in %.2f, refined V %d->%d, UV bits %zu, certified %s, peak %.0f MB\n", total,
              double(r.stats.output_triangles) / r.stats.input_faces, r.stats.input_vertices, r.stats.refined_vertices,
              r.stats.max_uv_bits, r.certified() ? "yes" : "NO", peak_mb());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    int first = 1;
    if (argc > 1 && std::string(argv[1]) == "--normal-form") g_normal_form = true, first = 2;
    if (argc > first) {
      for (int i = first; i < argc; ++i) run(std::filesystem::path(argv[i]).stem().string(), igm::load_mesh(argv[i]));
      return 0;
    }
    const char* env = std::getenv("IGM_DATA_DIR");
    const std::filesystem::path data = env && *env ? env : "../shared";
    for (const char* m : {"knot", "eight", "elephant", "couplingdown", "cheese"}) {
      const auto path = data / "meshes" / "clean" / (std::string(m) + ".off");
      if (std::filesystem::exists(path)) run(m, igm::load_mesh(path));
      else std::printf("%s: not found (set IGM_DATA_DIR)\n", path.string().c_str());
    }
    for (std::int64_t faces : {100000, 1000000}) {
      igm::GenerateOptions g;
      g.genus = 1;
      g.faces = faces;
      run("torus-" + std::to_string(faces), igm::validate(igm::generate_closed_mesh(g)));
    }
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
