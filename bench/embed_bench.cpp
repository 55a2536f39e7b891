// Embedding benchmark: certified Tutte maps of generated disks (closed genus-0 mesh minus one
// face, boundary on a triangle; and a grid disk on the unit square), 100k and 1M faces.
// Usage: igm_bench_embed [max_faces]   (default 1000000)
// Prints CPU time (getrusage, this process) next to wall time: on a shared machine the wall
// time includes waiting for a core. The per-phase times are wall times from TutteStats.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "igm/embed/polygon.h"
#include "igm/embed/tutte.h"
#include "igm/mesh/generate.h"

using namespace igm;

namespace {

struct Disk {
  int nv = 0;
  std::vector<std::array<int, 3>> tris;
  std::vector<int> boundary;
  std::vector<Point2q> buv;
};

Disk punctured_sphere(std::int64_t faces) {
  const PolygonSoup s = generate_closed_mesh({0, faces, 1, true, 0.25});
  Disk d;
  d.nv = static_cast<int>(s.positions.size());
  d.tris.reserve(s.num_faces());
  for (std::size_t f = 1; f < s.num_faces(); ++f) {
    const auto* c = &s.corners[s.face_begin[f]];
    d.tris.push_back({int(c[0]), int(c[1]), int(c[2])});
  }
  const auto* c = &s.corners[s.face_begin[0]];
  d.boundary = {int(c[0]), int(c[2]), int(c[1])};
  d.buv = {{Rational(0), Rational(0)}, {Rational(1), Rational(0)}, {Rational(0), Rational(1)}};
  return d;
}

Disk grid_disk(std::int64_t faces) {
  int n = 2;
  while (2LL * n * n < faces) ++n;
  Disk d;
  d.nv = (n + 1) * (n + 1);
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  std::uint64_t r = 88172645463325252ULL;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      r ^= r << 13, r ^= r >> 7, r ^= r << 17;
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), e = id(i, j + 1);
      if (r & 1) {
        d.tris.push_back({a, b, c});
        d.tris.push_back({a, c, e});
      } else {
        d.tris.push_back({a, b, e});
        d.tris.push_back({b, c, e});
      }
    }
  d.buv = place_boundary(canonical_polygon(1), {n, n, n, n});
  for (int i = 0; i < n; ++i) d.boundary.push_back(id(i, 0));
  for (int j = 0; j < n; ++j) d.boundary.push_back(id(n, j));
  for (int i = n; i > 0; --i) d.boundary.push_back(id(i, n));
  for (int j = n; j > 0; --j) d.boundary.push_back(id(0, j));
  return d;
}

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_utime.tv_usec * 1e-6 + u.ru_stime.tv_sec + u.ru_stime.tv_usec * 1e-6;
}

// Adversarial disks (same constructions as tests/embed/tutte_test.cpp): a dense fan whose path
// collapses onto an edge like (2 - sqrt 3)^i, and a long tube of 4-vertex rings.
Disk fan_disk(int n) {
  Disk d;
  d.nv = 3 + n;
  auto P = [&](int i) { return i == 0 ? 2 : 2 + i; };
  for (int i = 0; i < n; ++i) {
    d.tris.push_back({0, P(i + 1), P(i)});
    d.tris.push_back({1, P(i), P(i + 1)});
  }
  d.tris.push_back({0, 1, P(n)});
  d.boundary = {0, 1, 2};
  d.buv = {{Rational(0), Rational(1)}, {Rational(1), Rational(1)}, {Rational(1, 3), Rational(2)}};
  return d;
}

Disk tube_disk(int rings) {
  Disk d;
  const int B = 4;
  d.nv = B * (rings + 1) + 1;
  auto id = [&](int k, int i) { return k * B + i % B; };
  for (int k = 0; k < rings; ++k)
    for (int i = 0; i < B; ++i) {
      d.tris.push_back({id(k, i), id(k, i + 1), id(k + 1, i + 1)});
      d.tris.push_back({id(k, i), id(k + 1, i + 1), id(k + 1, i)});
    }
  for (int i = 0; i < B; ++i) d.tris.push_back({id(rings, i), id(rings, i + 1), d.nv - 1});
  d.boundary = {0, 1, 2, 3};
  d.buv = canonical_polygon(1);
  return d;
}

long maxrss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;
}

void run(const char* name, const Disk& d, const TutteOptions& o = {}) {
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds();
  const TutteResult r = tutte_embed(d.nv, d.tris, d.boundary, d.buv, o);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = cpu_seconds() - c0;
  // Independent exact re-check of every triangle (not part of the timing above).
  std::int64_t bad = 0;
  for (const auto& t : d.tris)
    if (orient2d(r.uv[t[0]], r.uv[t[1]], r.uv[t[2]]) != Sign::Positive) ++bad;
  const auto& s = r.stats;
  std::string flips;
  for (auto f : s.flips_per_iteration) flips += std::to_string(f) + " ";
  std::printf(
      "%-36s faces %8d interior %8d boundary %6d | cpu %.3f s, wall %.3f s: validate %.3f "
      "assemble %.3f factor %.3f (L %zu) solve %.3f refine %.3f checks %.3f fallback %.3f | flips_double %lld "
      "iterations %d flips/iter [ %s] max_bits %zu fallback %d | recheck non-positive %lld | "
      "maxrss %ld MB\n",
      name, s.triangles, s.interior_vertices, s.boundary_vertices, cpu, wall,
      s.seconds_validate, s.seconds_assemble, s.seconds_factorization, s.factor_entries, s.seconds_solve, s.seconds_refinement,
      s.seconds_checks, s.seconds_fallback, static_cast<long long>(s.flips_double), s.iterations,
      flips.c_str(), s.max_bits, int(s.exact_fallback), static_cast<long long>(bad), maxrss_mb());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const std::int64_t max_faces = argc > 1 ? std::atoll(argv[1]) : 1000000;
  for (int g : {2, 10, 100, 1000, 10000}) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto c = canonical_polygon(g);  // includes the exact convexity check
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::size_t bits = 0;
    for (const auto& p : c) bits = std::max({bits, bit_size(p.x), bit_size(p.y)});
    std::printf("canonical_polygon(%d): %zu corners, max bits per coordinate %zu, %.4f s\n", g, c.size(), bits, sec);
  }
  for (int n : {100, 400, 1000}) run(("dense fan " + std::to_string(n)).c_str(), fan_disk(n));
  for (int k : {50, 150, 300}) run(("tube of 4-rings " + std::to_string(k)).c_str(), tube_disk(k));
  for (std::int64_t faces : {std::int64_t(100000), std::int64_t(1000000)}) {
    if (faces > max_faces) break;
    run(("punctured sphere " + std::to_string(faces)).c_str(), punctured_sphere(faces));
    const Disk g = grid_disk(faces);
    run(("grid square " + std::to_string(faces)).c_str(), g);
    TutteOptions forced;
    forced.min_iterations = 2;  // measure the exact refinement at this size
    run(("grid square, 2 refinements " + std::to_string(faces)).c_str(), g, forced);
  }
  return 0;
}
