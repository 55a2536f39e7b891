// Reading + validation speed: armadillo.off (52k faces, from $IGM_DATA_DIR/meshes/clean or
// /work/shared/meshes/clean, or argv[1]) and a generated 1M-face genus-5 mesh written to /tmp
// as OBJ. Prints one line per measurement (best of several runs for the small mesh).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "igm/core/error.h"
#include "igm/io/read_mesh.h"
#include "igm/io/write_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Timing {
  double read = 1e9, parse = 1e9, validate = 1e9;
  double cpu = 1e9;  // process CPU seconds of the whole read + parse + validate (the machine may be shared)
};

// Times read_file_bytes, read_soup(bytes) and validate separately; keeps the best of `runs`.
Timing measure(const std::filesystem::path& path, int runs, igm::ValidMesh& out) {
  Timing best;
  for (int i = 0; i < runs; ++i) {
    const std::clock_t c0 = std::clock();
    auto t0 = std::chrono::steady_clock::now();
    const std::string bytes = igm::read_file_bytes(path);
    const double tr = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    const igm::PolygonSoup soup = igm::read_soup(bytes, igm::format_from_path(path));
    const double tp = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    out = igm::validate(soup);
    const double tv = seconds_since(t0);
    best.cpu = std::min(best.cpu, static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    best.read = std::min(best.read, tr);
    best.parse = std::min(best.parse, tp);
    best.validate = std::min(best.validate, tv);
  }
  return best;
}

void report(const char* name, const std::filesystem::path& path, const Timing& t, const igm::ValidMesh& m) {
  std::printf(
      "%-26s %6.1f MB  V=%-7d F=%-7d genus=%-2d  wall: file %.3f s  parse %.3f s  validate %.3f s  total %.3f s"
      "  (cpu %.3f s)\n",
      name, static_cast<double>(std::filesystem::file_size(path)) / 1e6, m.mesh.num_vertices(), m.mesh.num_faces(),
      m.genus, t.read, t.parse, t.validate, t.read + t.parse + t.validate, t.cpu);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::filesystem::path arm;
    if (argc > 1)
      arm = argv[1];
    else {
      const char* env = std::getenv("IGM_DATA_DIR");
      arm = std::filesystem::path(env && *env ? env : "/work/shared") / "meshes" / "clean" / "armadillo.off";
    }
    igm::ValidMesh m;
    if (std::filesystem::exists(arm)) {
      report("armadillo.off (best of 5)", arm, measure(arm, 5, m), m);
    } else {
      std::printf("armadillo.off not found at %s (set IGM_DATA_DIR or pass the path)\n", arm.string().c_str());
    }

    const std::filesystem::path big = std::filesystem::temp_directory_path() / "igm_read_bench_1M.obj";
    auto t0 = std::chrono::steady_clock::now();
    const igm::PolygonSoup soup = igm::generate_closed_mesh({.genus = 5, .faces = 1'000'000, .seed = 1});
    const double tg = seconds_since(t0);
    std::vector<std::array<int, 3>> tris(soup.num_faces());
    for (std::size_t f = 0; f < soup.num_faces(); ++f)
      tris[f] = {int(soup.corners[3 * f]), int(soup.corners[3 * f + 1]), int(soup.corners[3 * f + 2])};
    t0 = std::chrono::steady_clock::now();
    igm::write_obj(big, soup.positions, tris);
    const double tw = seconds_since(t0);
    std::printf("generated %zu faces in %.3f s, wrote %s in %.3f s\n", soup.num_faces(), tg, big.string().c_str(), tw);
    report("generated 1M (best of 2)", big, measure(big, 2, m), m);
    std::filesystem::remove(big);
    return 0;
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "read_bench: %s\n", e.what());
    return 1;
  }
}
