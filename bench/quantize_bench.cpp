// quantize_layout (layout/quantize.h) and map_layout (igm/layout_map.h) on synthetic T-meshes: random
// guillotine splits of a block grid on a torus of revolution (tests/support/layout_builder.h) with
// about 10, 100, 1,000 and 10,000 patches, at about 10 and 100 quads per patch; and on the canonical
// layouts of shared and generated meshes (converted by to_surface_layout) beside today's chord
// sizing (size_layout). Per solve: CPU seconds (this thread), CBC nodes, status, quads against the
// target, and the deviation: per arc |log(x / t)| (t = 3D length / H), per patch the aspect error
// |log((a / b) / (w / h))| (w, h: mean 3D lengths of its opposite sides), mean and p95; both
// objective weights side by side (QuantizeWeight).
// usage: igm_bench_quantize [--patches P,P,...] [--per-patch Q,Q,...] [--map] [--no-canonical]
//   --map: also map_layout on each T-mesh (one certified Tutte map per patch) and certify it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "../tests/igm/patch_fixture.h"
#include "../tests/support/generated_mesh.h"
#include "../tests/support/layout_builder.h"
#include "igm/igm/layout_map.h"
#include "igm/io/read_mesh.h"
#include "igm/layout/quantize.h"
#include "igm/mesh/scale.h"
#include "thread_cpu.h"

namespace {

using namespace igm;

std::vector<int> parse_list(const char* s) {
  std::vector<int> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::atoi(item.c_str()));
  return v;
}

double p95(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(0.95 * static_cast<double>(v.size())))];
}
double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / static_cast<double>(v.size());
}

std::vector<double> arc_lengths(const SurfaceLayout& L, double scale) {
  std::vector<double> len(L.arcs.size(), 0.0);
  for (std::size_t a = 0; a < L.arcs.size(); ++a)
    for (std::size_t k = 0; k + 1 < L.arcs[a].vertices.size(); ++k)
      len[a] += scaled_distance(L.positions[L.arcs[a].vertices[k]], L.positions[L.arcs[a].vertices[k + 1]], scale);
  return len;
}

// Deviation of integer lengths x at edge length H from the 3D lengths: per arc, per patch aspect.
void deviation(const SurfaceLayout& L, const std::vector<double>& len, const std::vector<int>& x, double H, double out[4]) {
  std::vector<double> arc, aspect;
  for (std::size_t a = 0; a < x.size(); ++a)
    if (len[a] > 0) arc.push_back(std::abs(std::log(x[a] / (len[a] / H))));
  for (const LayoutPatch& P : L.patches) {
    double s3[4] = {0, 0, 0, 0}, s[4] = {0, 0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (const ArcUse& u : P.sides[k]) s3[k] += len[u.arc], s[k] += x[u.arc];
    const double w = 0.5 * (s3[0] + s3[2]), h = 0.5 * (s3[1] + s3[3]);
    if (w > 0 && h > 0) aspect.push_back(std::abs(std::log((s[0] / s[1]) / (w / h))));
  }
  out[0] = mean(arc), out[1] = p95(arc), out[2] = mean(aspect), out[3] = p95(aspect);
}

void header() {
  std::printf("%-22s %7s %7s %6s %9s %9s %7s %8s %11s | %6s %6s %6s %6s\n", "layout", "patches", "arcs", "weight",
              "target", "quads", "nodes", "cpu s", "status", "arc", "arc95", "asp", "asp95");
}

void quantize_row(const std::string& name, const SurfaceLayout& L, std::int64_t target, QuantizeWeight w) {
  QuantizeOptions o;
  o.quads = target;
  o.weight = w;
  const double c0 = igm_bench::thread_cpu_ns();
  const Quantization q = quantize_layout(L, o);
  const double cpu = (igm_bench::thread_cpu_ns() - c0) * 1e-9;
  double d[4] = {0, 0, 0, 0};
  if (q.ok()) deviation(L, arc_lengths(L, 1), q.arc_length, q.edge_length, d);
  std::printf("%-22s %7zu %7zu %6s %9lld %9lld %7lld %8.3f %11s | %6.3f %6.3f %6.3f %6.3f\n", name.c_str(),
              L.patches.size(), L.arcs.size(), w == QuantizeWeight::Relative ? "rel" : "abs", static_cast<long long>(target),
              static_cast<long long>(q.quads), static_cast<long long>(q.stats.nodes), cpu, to_string(q.status), d[0], d[1],
              d[2], d[3]);
  std::fflush(stdout);
}

void map_row(const SurfaceLayout& L, std::int64_t target) {
  QuantizeOptions o;
  o.quads = target;
  const Quantization q = quantize_layout(L, o);
  if (!q.ok()) return;
  const double c0 = igm_bench::thread_cpu_ns();
  const LayoutMap m = map_layout(L, q.arc_length);
  const double cpu = (igm_bench::thread_cpu_ns() - c0) * 1e-9;
  const certify::Report r = certify::certify_igm(certify_input(m.igm, m.igm.corner_uv));
  std::printf("  map_layout: %zu triangles, %d patches, %.3f s CPU (check, %d splits, max %d patch vertices), %s\n",
              m.igm.triangles.size(), m.stats.patches, cpu, m.stats.splits, m.stats.max_patch_vertices,
              r.valid() ? "certified" : "NOT CERTIFIED");
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> patches = {10, 100, 1000, 10000}, per_patch = {10, 100};
  bool map = false, canonical = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--patches" && i + 1 < argc) patches = parse_list(argv[++i]);
    else if (a == "--per-patch" && i + 1 < argc) per_patch = parse_list(argv[++i]);
    else if (a == "--map") map = true;
    else if (a == "--no-canonical") canonical = false;
    else {
      std::fprintf(stderr, "usage: igm_bench_quantize [--patches P,P,...] [--per-patch Q,Q,...] [--map] [--no-canonical]\n");
      return 2;
    }
  }
  header();
  for (int P : patches) {
    // k x k blocks of 8 x 8 cells, then P - k^2 splits (k = round(sqrt(P / 4)), at least 1).
    const int k = std::max(1, static_cast<int>(std::lround(std::sqrt(P / 4.0))));
    const int n = 8 * k;
    const SurfaceLayout L = igm_test::build_layout(igm_test::grid_spec(
        n, n, true, true, igm_test::random_t_mesh(n, n, k, P - k * k, 1), igm_test::torus_embedding(n, n, 3, 1)));
    const std::string name = "t-mesh " + std::to_string(P);
    for (int per : per_patch)
      for (QuantizeWeight w : {QuantizeWeight::Relative, QuantizeWeight::Absolute})
        quantize_row(name, L, static_cast<std::int64_t>(per) * static_cast<std::int64_t>(L.patches.size()), w);
    if (map) map_row(L, 10 * static_cast<std::int64_t>(L.patches.size()));
  }
  if (!canonical) return 0;
  // Canonical layouts: the converted patch mesh, quantized, beside size_layout's chords.
  std::vector<std::pair<std::string, ValidMesh>> meshes;
  for (int g : {2, 8, 20}) meshes.push_back({"generated g" + std::to_string(g), igm_test::generated_mesh(g, 4000 * g, 1)});
  const char* env = std::getenv("IGM_DATA_DIR");
  const std::filesystem::path dir = env && *env ? env : "../shared";
  for (const char* name : {"elephant", "couplingdown"}) {
    const std::filesystem::path path = dir / "meshes" / "clean" / (std::string(name) + ".off");
    if (std::filesystem::exists(path)) meshes.push_back({name, validate(read_soup(path))});
  }
  for (auto& [name, mesh] : meshes) {
    igm_test::PatchSetup s = igm_test::patch_setup(mesh, LayoutKind::Spread, false);
    const std::vector<double> edge_len = layout_edge_lengths(s.layout, s.mesh, 1);
    const SurfaceLayout L = to_surface_layout(s.layout, s.mesh, mesh.mesh.num_vertices());
    for (std::int64_t target : {1000, 10000}) {
      for (QuantizeWeight w : {QuantizeWeight::Relative, QuantizeWeight::Absolute}) quantize_row(name, L, target, w);
      SizingOptions so;
      so.quads = target;
      const Sizing sz = size_layout(s.layout, edge_len, so);
      double d[4];
      deviation(L, arc_lengths(L, 1), sz.edge_count, sz.edge_length, d);
      std::printf("%-22s %7zu %7zu %6s %9lld %9lld %7s %8s %11s | %6.3f %6.3f %6.3f %6.3f\n", name.c_str(), L.patches.size(),
                  L.arcs.size(), "chord", static_cast<long long>(target), static_cast<long long>(sz.quads), "-", "-",
                  "size_layout", d[0], d[1], d[2], d[3]);
    }
  }
  return 0;
}
