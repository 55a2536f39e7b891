// Cost of measure_quads (igm/quality/quality.h) on a generated large input: a genus-2 mesh of
// about INPUT_FACES triangles (default 1M) against a quad mesh of about QUADS quads (default 20k)
// made from a coarse generated mesh of the same region (each triangle split into three quads at
// its edge midpoints and centroid, x and y stretched to the fine mesh's box).
//   igm_bench_quality [INPUT_FACES] [QUADS] [MAX_SAMPLES]
// Prints the wall and CPU time of measure_quads without and with the distance, the hierarchy over
// the input alone, and the summary line.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <map>
#include <utility>
#include <vector>

#include "igm/mesh/generate.h"
#include "igm/quality/quality.h"
#include "igm/quality/surface_distance.h"

namespace {

struct Triangles {
  std::vector<igm::Vec3d> positions;
  std::vector<std::array<int, 3>> triangles;
};

Triangles generated(long long faces) {
  igm::GenerateOptions o;
  o.genus = 2;
  o.faces = faces;
  const igm::PolygonSoup soup = igm::generate_closed_mesh(o);
  Triangles t;
  t.positions = soup.positions;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto* c = &soup.corners[soup.face_begin[f]];
    t.triangles.push_back({static_cast<int>(c[0]), static_cast<int>(c[1]), static_cast<int>(c[2])});
  }
  return t;
}

double width(const std::vector<igm::Vec3d>& p, double igm::Vec3d::*axis) {
  const auto [lo, hi] = std::minmax_element(
      p.begin(), p.end(), [&](const auto& a, const auto& b) { return a.*axis < b.*axis; });
  return (*hi).*axis - (*lo).*axis;
}

struct Quads {
  std::vector<igm::Vec3d> positions;
  std::vector<std::array<int, 4>> quads;
};

// Three quads per triangle of `coarse` (corner, edge midpoint, centroid, edge midpoint), x and y
// stretched by sx, sy.
Quads split_into_quads(const Triangles& coarse, double sx, double sy) {
  Quads q;
  for (const auto& p : coarse.positions) q.positions.push_back({p.x * sx, p.y * sy, p.z});
  std::map<std::pair<int, int>, int> midpoint;
  auto mid = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    const auto [it, fresh] = midpoint.try_emplace(key, static_cast<int>(q.positions.size()));
    if (fresh) {
      const auto& pa = q.positions[a];
      const auto& pb = q.positions[b];
      q.positions.push_back({(pa.x + pb.x) / 2, (pa.y + pb.y) / 2, (pa.z + pb.z) / 2});
    }
    return it->second;
  };
  for (const auto& t : coarse.triangles) {
    const int c = static_cast<int>(q.positions.size());
    const auto& a = q.positions[t[0]];
    const auto& b = q.positions[t[1]];
    const auto& d = q.positions[t[2]];
    q.positions.push_back({(a.x + b.x + d.x) / 3, (a.y + b.y + d.y) / 3, (a.z + b.z + d.z) / 3});
    for (int i = 0; i < 3; ++i)
      q.quads.push_back({t[i], mid(t[i], t[(i + 1) % 3]), c, mid(t[(i + 2) % 3], t[i])});
  }
  return q;
}

struct Timer {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  void print(const char* what) const {
    const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
    const double c = static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC;
    std::printf("%-34s wall %.3f s  cpu %.3f s\n", what, w, c);
  }
};

}  // namespace

int main(int argc, char** argv) {
  const long long input_faces = argc > 1 ? std::atoll(argv[1]) : 1000000;
  const long long quads_wanted = argc > 2 ? std::atoll(argv[2]) : 20000;
  igm::QuadQualityOptions options;
  if (argc > 3) options.max_samples = static_cast<std::size_t>(std::atoll(argv[3]));

  const Triangles input = generated(input_faces);
  const Triangles coarse = generated(quads_wanted / 3);
  const Quads quads = split_into_quads(
      coarse, width(input.positions, &igm::Vec3d::x) / width(coarse.positions, &igm::Vec3d::x),
      width(input.positions, &igm::Vec3d::y) / width(coarse.positions, &igm::Vec3d::y));
  std::printf(
      "input %zu triangles, %zu vertices; quad mesh %zu quads, %zu vertices; max_samples %zu\n",
      input.triangles.size(), input.positions.size(), quads.quads.size(), quads.positions.size(),
      options.max_samples);

  {
    const Timer t;
    const igm::TriangleBvh bvh(input.positions, input.triangles);
    t.print("hierarchy over the input");
  }
  igm::QuadQualityOptions shape_only = options;
  shape_only.distance = false;
  {
    const Timer t;
    const igm::QuadQuality q = igm::measure_quads(quads.positions, quads.quads, input.positions,
                                                  input.triangles, shape_only);
    t.print("measure_quads without distance");
  }
  const Timer t;
  const igm::QuadQuality q =
      igm::measure_quads(quads.positions, quads.quads, input.positions, input.triangles, options);
  t.print("measure_quads with distance");
  std::printf("samples: %zu on the quads, %zu on the input\n%s\n", q.distance_samples_quads,
              q.distance_samples_input, igm::summary_line(igm::IgmQuality{}, q).c_str());
  return 0;
}
