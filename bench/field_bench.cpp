// Cross field benchmark (field/cross_field.h): per mesh the faces, the field's time (its
// factorization), iterations, energy, the interior cones by valence (3/5/2/6/other), boundary
// corners (k = 1 / 3 / 0 / other), close +-pairs, Poincare-Hopf.
// usage: igm_bench_field [--alignment W] [--lanczos] [--iterations N] [--tolerance T] [--no-cleanup] [--split6]
//                        [--pair-distance D] [--cones] [--generated FACES] [--no-shared] [--hostile N]
//                        [--real-form-above F] [--again] [MESH ...]
// --real-form-above F: CrossFieldOptions::real_form_above; --again: each field a second time with
// the first one's CrossFieldCache (its analysis kept), its time printed.
// Default: every mesh of $IGM_DATA_DIR/meshes/clean and /open (or ../shared), then a generated
// genus-20 mesh of about 1M faces (--generated 0 skips it). --cones prints every cone's vertex,
// valence and position. --hostile N: instead, N random small meshes (tests/support/random_mesh.h:
// genus 0..8, closed or with 1..6 boundary loops, every geometry in turn) and per geometry how many
// fields were computed, threw (and why), had an interior valence <= 1 or a boundary k <= 0.
#include <algorithm>
#include <array>
#include <random>
#include <chrono>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/field/cross_field.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate_surfaces.h"
#include "../tests/support/random_mesh.h"

namespace {

igm::CrossFieldOptions g_options;
bool g_print_cones = false;
bool g_again = false;

void run(const std::string& name, const igm::SurfaceComponent& c) {
  const igm::TriMesh mesh =
      igm::TriMesh::from_triangles(static_cast<int>(c.positions.size()), c.triangles, !c.boundary_loops.empty());
  timespec c0, c1;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
  igm::CrossFieldCache cache;
  const igm::CrossField f = igm::compute_cross_field(mesh, c.positions, g_options, &cache);
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
  const double cpu = (c1.tv_sec - c0.tv_sec) + 1e-9 * (c1.tv_nsec - c0.tv_nsec);
  if (g_again) {  // the same field again with the analysis kept (the pipeline's later rounds)
    const igm::CrossField again = igm::compute_cross_field(mesh, c.positions, g_options, &cache);
    std::printf("%-24s again with the cache: wall %7.3fs (factor %.3fs), analyses %d, same theta %s\n", name.c_str(),
                again.stats.seconds, again.stats.factor_seconds, cache.analyses(), again.theta == f.theta ? "yes" : "NO");
  }
  const igm::CrossFieldStats& s = f.stats;
  const auto& v = s.valence_count;
  const auto& b = s.boundary_count;
  int other = 0;
  for (int k = 0; k <= 8; ++k)
    if (k < 2 || k > 6) other += v[k];
  const std::string ph = igm::check_poincare_hopf(mesh, f);
  const std::string obstruction = igm::seamless_obstruction(mesh, f);
  // Feature alignment: interior edges with a dihedral angle above 30 degrees whose direction is
  // within 5 degrees of a field direction in both faces.
  int sharp = 0, aligned = 0;
  for (int h = 0; h < mesh.num_halfedges(); ++h) {
    const int t = mesh.twin(h);
    if (t < h) continue;
    const igm::Vec3d& n1 = f.frames.normal[h / 3];
    const igm::Vec3d& n2 = f.frames.normal[t / 3];
    const double cosang = n1.x * n2.x + n1.y * n2.y + n1.z * n2.z;
    if (!(cosang < std::cos(30 * std::numbers::pi / 180))) continue;
    ++sharp;
    bool ok = true;
    for (int e : {h, t}) {
      const double d = f.frames.edge_angle[e] - f.theta[e / 3];
      const double r = std::remainder(d, std::numbers::pi / 2);
      if (std::fabs(r) > 5 * std::numbers::pi / 180) ok = false;
    }
    aligned += ok;
  }
  // A hash of the field's bytes (theta per face, FNV-1a): equal hashes across machines, loads
  // and libm kernels (GLIBC_TUNABLES=glibc.cpu.hwcaps=-FMA...) are the determinism claim.
  std::uint64_t hash = 1469598103934665603ull;
  for (double t : f.theta) {
    unsigned char b[sizeof t];
    std::memcpy(b, &t, sizeof t);
    for (unsigned char x : b) hash = (hash ^ x) * 1099511628211ull;
  }
  std::printf(
      "%-24s g=%-3d F=%-8d cpu %7.3fs wall %7.3fs (factor %.3fs) %s it=%-3d%s E=%-9.4g cones %3zu: v3 %-3d v5 %-3d v2 %-2d v6 %-2d "
      "other %-2d | sharp %d aligned %.0f%% | corners k1 %-2d k3 %-2d k0 %-2d | pairs %d -> %zu | PH %s%s%s | hash %016llx\n",
      name.c_str(), c.genus, mesh.num_faces(), cpu, s.seconds, s.factor_seconds, s.linear ? "lin" : igm::to_string(s.solver),
      s.iterations, s.converged ? "" : "!", s.energy, f.cones.size(), v[3], v[5], v[2], v[6], other, sharp, sharp ? 100.0 * aligned / sharp : 0.0, b[1], b[3], b[0],
      s.pairs_before_cleanup, f.close_pairs.size(), ph.empty() ? "ok" : ph.c_str(), obstruction.empty() ? "" : " | ",
      obstruction.c_str(), static_cast<unsigned long long>(hash));
  if (g_print_cones)
    for (const igm::Cone& k : f.cones) {
      const igm::Vec3d& p = c.positions[k.vertex];
      std::printf("    cone v%-6d valence %d at (%.4g, %.4g, %.4g)\n", k.vertex, k.valence, p.x, p.y, p.z);
    }
  if (g_print_cones)
    for (const igm::Cone& k : f.corners) {
      const igm::Vec3d& p = c.positions[k.vertex];
      std::printf("    corner v%-6d k %d at (%.4g, %.4g, %.4g)\n", k.vertex, k.valence, p.x, p.y, p.z);
    }
  std::fflush(stdout);
}

void run_file(const std::filesystem::path& path) {
  try {
    const igm::SurfaceSet set = igm::validate_surfaces(igm::read_soup(path));
    for (std::size_t i = 0; i < set.components.size(); ++i)
      run(path.stem().string() + (set.components.size() > 1 ? "#" + std::to_string(i) : ""), set.components[i]);
  } catch (const igm::Error& e) {
    std::printf("%-24s error: %s\n", path.stem().string().c_str(), e.what());
  }
}

// --hostile N: per geometry, the fields computed, the errors, and the fields with a vertex no
// quad mesh allows (interior valence <= 1, boundary k <= 0). Deterministic (fixed seed).
void run_hostile(int n) {
  using igm_test::Geometry;
  std::mt19937_64 rng(46);
  const int ng = static_cast<int>(Geometry::Count);
  std::vector<std::array<int, 4>> count(ng, std::array<int, 4>{});  // runs, errors, valence <= 1, k <= 0
  for (int i = 0; i < n; ++i) {
    igm_test::RandomMeshSpec s;
    s.genus = static_cast<int>(rng() % 9);
    s.boundaries = rng() % 2 == 0 ? 0 : 1 + static_cast<int>(rng() % 6);
    s.faces = static_cast<std::int64_t>((200.0 + 250.0 * s.genus + 40.0 * s.boundaries) *
                                        std::pow(4.0, std::uniform_real_distribution<double>(0, 1)(rng)));
    s.seed = rng();
    s.jitter = std::uniform_real_distribution<double>(0, 0.45)(rng);
    s.edge_splits = static_cast<int>(rng() % 21);
    s.face_splits = static_cast<int>(rng() % 21);
    s.geometry = static_cast<Geometry>(i % ng);
    auto& c = count[static_cast<std::size_t>(i % ng)];
    ++c[0];
    try {
      const igm::SurfaceSet set = igm::validate_surfaces(igm_test::random_mesh(s));
      const igm::SurfaceComponent& comp = set.components.at(0);
      const igm::TriMesh mesh = igm::TriMesh::from_triangles(static_cast<int>(comp.positions.size()), comp.triangles,
                                                             !comp.boundary_loops.empty());
      const igm::CrossField f = igm::compute_cross_field(mesh, comp.positions, g_options);
      bool v1 = false, k0 = false;
      for (const igm::Cone& k : f.cones) v1 = v1 || k.valence <= 1;
      for (const igm::Cone& k : f.corners) k0 = k0 || k.valence <= 0;
      c[2] += v1;
      c[3] += k0;
      if (g_print_cones && (v1 || k0))
        std::printf("  %s: %s\n", igm_test::describe(s).c_str(), igm::seamless_obstruction(mesh, f).c_str());
    } catch (const igm::Error& e) {
      ++c[1];
      std::printf("  %s: %s\n", igm_test::describe(s).c_str(), e.what());
    }
  }
  for (int g = 0; g < ng; ++g)
    std::printf("%-10s runs %3d errors %3d valence<=1 %3d k<=0 %3d\n", igm_test::to_string(static_cast<Geometry>(g)),
                count[static_cast<std::size_t>(g)][0], count[static_cast<std::size_t>(g)][1],
                count[static_cast<std::size_t>(g)][2], count[static_cast<std::size_t>(g)][3]);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::string> meshes;
    long long generated = 1000000;
    bool shared = true;
    int hostile = 0;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--alignment" && i + 1 < argc)
        g_options.alignment = std::atof(argv[++i]);
      else if (a == "--lanczos")
        g_options.solver = igm::FieldSolver::ShiftInvertLanczos;
      else if (a == "--iterations" && i + 1 < argc)
        g_options.max_iterations = std::atoi(argv[++i]);
      else if (a == "--tolerance" && i + 1 < argc)
        g_options.tolerance = std::atof(argv[++i]);
      else if (a == "--cleanup")
        g_options.remove_close_pairs = true;
      else if (a == "--no-cleanup")
        g_options.remove_close_pairs = g_options.split_valence2 = g_options.split_valence6 = false;
      else if (a == "--split6")
        g_options.split_valence6 = true;
      else if (a == "--pair-distance" && i + 1 < argc)
        g_options.close_pair_distance = std::atof(argv[++i]);
      else if (a == "--cones")
        g_print_cones = true;
      else if (a == "--real-form-above" && i + 1 < argc)
        g_options.real_form_above = std::atoi(argv[++i]);
      else if (a == "--again")
        g_again = true;
      else if (a == "--generated" && i + 1 < argc)
        generated = std::atoll(argv[++i]);
      else if (a == "--no-shared")
        shared = false;
      else if (a == "--hostile" && i + 1 < argc)
        hostile = std::atoi(argv[++i]);
      else
        meshes.push_back(a);
    }
    if (hostile > 0) {
      run_hostile(hostile);
      return 0;
    }
    if (meshes.empty() && shared) {
      const char* env = std::getenv("IGM_DATA_DIR");
      const std::filesystem::path dir = std::filesystem::path(env && *env ? env : "../shared") / "meshes";
      for (const char* sub : {"clean", "open"}) {
        std::vector<std::filesystem::path> files;
        if (std::filesystem::is_directory(dir / sub))
          for (const auto& e : std::filesystem::directory_iterator(dir / sub)) files.push_back(e.path());
        std::sort(files.begin(), files.end());
        for (const auto& f : files) run_file(f);
      }
    }
    for (const std::string& m : meshes) run_file(m);
    if (generated > 0 && meshes.empty()) {
      igm::GenerateOptions o;
      o.genus = 20;
      o.faces = generated;
      const auto t0 = std::chrono::steady_clock::now();
      const igm::SurfaceSet set = igm::validate_surfaces(igm::generate_closed_mesh(o));
      std::printf("(generated in %.2fs)\n",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      run("generated-g20", set.components[0]);
    }
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
