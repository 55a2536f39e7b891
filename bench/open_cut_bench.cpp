// Open surfaces' cut (topology/open_cut.h): time and growth on the shared open meshes, the genus 2
// mesh with 3 holes, generated meshes, and a generated genus 20 mesh of about 1M faces with 50
// loops against cut_to_canonical_disk on the closed generated genus 20 mesh of the same target
// size (default options, and without the normal form as the open cut runs it).
// Usage: igm_bench_open_cut [shared_dir] [--only big|big-open|shared|generated] [--check]
//   --check: also run check_open_cut (exact; slow on the big mesh) and print its verdict.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/topology/cut_to_canonical_disk.h"
#include "igm/topology/open_cut.h"

using namespace igm;

namespace {

bool check = false;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void run(const std::string& name, const SurfaceComponent& s) {
  try {
    const OpenCut c = cut_open_surface(s);
    const OpenCutStats& t = c.stats;
    std::printf("%-26s g=%-2d b=%-3d F=%-8d sides %3zu  V %8d -> %8d (+%5.1f%%) | closed cut +%d (tightened -%d)"
                " chords %d leg-chords %d precond %d boundary %d | legs %d (%d edges) extra corners %d | %.3f s"
                " (loops %.3f, legs %.3f)",
                name.c_str(), t.genus, t.boundary_loops, t.faces_before, c.sides.size(), t.vertices_before,
                t.vertices_after, 100.0 * (t.vertices_after - t.vertices_before - t.boundary_loops) / t.vertices_before,
                t.closed.vertices_after - t.closed.vertices_before, t.tightening.collapsed, t.chord_splits,
                t.leg_chord_splits, t.precondition_splits, t.boundary_splits, t.legs, t.leg_edges, t.extra_corners,
                t.seconds_total, t.seconds_loops, t.seconds_legs);
    if (check) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::string v = check_open_cut(s, c);
      std::printf(" | check %s (%.2f s)", v.empty() ? "ok" : v.c_str(), seconds_since(t0));
    }
    std::printf("\n");
  } catch (const Error& e) {
    std::printf("%-26s error: %s\n", name.c_str(), e.what());
  }
  std::fflush(stdout);
}

SurfaceComponent component(const PolygonSoup& soup) { return validate_surfaces(soup).components.at(0); }

void closed(const std::string& name, int genus, long faces, std::uint64_t seed, bool normal_form) {
  GenerateOptions g;
  g.genus = genus;
  g.faces = faces;
  g.seed = seed;
  const ValidMesh v = validate(generate_closed_mesh(g));
  CutOptions o;
  o.normal_form = normal_form;
  const auto t0 = std::chrono::steady_clock::now();
  const CutResult r = cut_to_canonical_disk(v.mesh, v.positions, o);
  std::printf("%-26s g=%-2d closed F=%-8d nf=%d  V %8d -> %8d (+%5.1f%%) | %.3f s\n", name.c_str(), genus,
              v.mesh.num_faces(), normal_form ? 1 : 0, r.stats.vertices_before, r.stats.vertices_after,
              100.0 * (r.stats.vertices_after - r.stats.vertices_before) / r.stats.vertices_before, seconds_since(t0));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path shared = "../shared";
  std::string only;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--only") == 0 && i + 1 < argc) only = argv[++i];
    else if (std::strcmp(argv[i], "--check") == 0) check = true;
    else shared = argv[i];
  }
  if (only.empty() || only == "shared") {
    std::vector<std::filesystem::path> files;
    if (std::filesystem::is_directory(shared / "meshes" / "open"))
      for (const auto& e : std::filesystem::directory_iterator(shared / "meshes" / "open"))
        if (e.path().extension() == ".off") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    files.push_back(shared / "meshes" / "invalid" / "double-torus-3-holes.off");
    for (const auto& p : files) {
      try {
        run(p.filename().string(), component(read_soup(p)));
      } catch (const Error& e) {
        std::printf("%-26s unreadable: %s\n", p.filename().string().c_str(), e.what());
      }
    }
  }
  if (only.empty() || only == "generated") {
    for (int genus : {0, 1, 3, 6, 10})
      for (int loops : {1, 4, 20}) {
        GenerateOptions g;
        g.genus = genus;
        g.faces = 100000;
        g.seed = 5;
        g.boundaries = loops;
        run("generated 100k", component(generate_mesh(g)));
      }
  }
  if (only.empty() || only == "big" || only == "big-open") {
    GenerateOptions g;
    g.genus = 20;
    g.faces = 1000000;
    g.seed = 3;
    g.boundaries = 50;
    const auto t0 = std::chrono::steady_clock::now();
    const SurfaceComponent s = component(generate_mesh(g));
    std::printf("(generated and validated the open g20 in %.2f s)\n", seconds_since(t0));
    run("generated 1M g20 b50", s);
    if (only == "big-open") return 0;
    closed("generated 1M g20 closed", 20, 1000000, 3, true);
    closed("generated 1M g20 closed", 20, 1000000, 3, false);
  }
  return 0;
}
