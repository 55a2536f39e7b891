// Certifier timings: the three shared third-party IGMs and a generated ~1M-triangle torus IGM
// (written as OBJ text to /tmp, then certified from the file), with one vt per grid point and
// with one vt per face corner (the libQEx layout).
//   igm_bench_certify [SHARED_DIR]   (default: $IGM_DATA_DIR, else ../shared beside the source tree)
#include <chrono>
#include <ctime>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "certify/certify.h"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// n x n torus, chart [0, n/2]^2 with uv = (i/2, j/2) printed as decimals ("12.5"); seams are
// translations by n/2 (n even). per_corner: one vt line per face corner, else one per grid point.
void write_torus(const fs::path& path, int n, bool per_corner) {
  std::ofstream o(path, std::ios::binary);
  std::string buf;
  buf.reserve(1 << 20);
  auto flush = [&] {
    o.write(buf.data(), static_cast<std::streamsize>(buf.size()));
    buf.clear();
  };
  auto half = [](int i) {
    std::string h = std::to_string(i / 2);
    h += i % 2 ? ".5" : ".0";
    return h;
  };
  buf += "# generated torus IGM\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      buf += "v ";
      buf += std::to_string(i);
      buf += ' ';
      buf += std::to_string(j);
      buf += " 0\n";
      if (buf.size() > (1u << 20)) flush();
    }
  auto vid = [n](int i, int j) { return (i % n) + n * (j % n) + 1; };
  auto gid = [n](int i, int j) { return i + (n + 1) * j + 1; };
  if (!per_corner) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        buf += "vt ";
        buf += half(i);
        buf += ' ';
        buf += half(j);
        buf += '\n';
        if (buf.size() > (1u << 20)) flush();
      }
  }
  long long vt = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int tri[2][3][2] = {{{i, j}, {i + 1, j}, {i + 1, j + 1}}, {{i, j}, {i + 1, j + 1}, {i, j + 1}}};
      for (const auto& t : tri) {
        std::string f = "f";
        for (const auto& c : t) {
          long long uvid;
          if (per_corner) {
            buf += "vt ";
            buf += half(c[0]);
            buf += ' ';
            buf += half(c[1]);
            buf += '\n';
            uvid = ++vt;
          } else {
            uvid = gid(c[0], c[1]);
          }
          f += ' ';
          f += std::to_string(vid(c[0], c[1]));
          f += '/';
          f += std::to_string(uvid);
        }
        buf += f + "\n";
      }
      if (buf.size() > (1u << 20)) flush();
    }
  flush();
}

void time_file(const std::string& label, const fs::path& p, int repeats) {
  double best = 1e30, best_cpu = 1e30;
  igm::certify::Report r;
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = Clock::now();
    const std::clock_t c0 = std::clock();
    r = igm::certify::certify_igm_file(p.string());
    best_cpu = std::min(best_cpu, double(std::clock() - c0) / CLOCKS_PER_SEC);
    best = std::min(best, seconds_since(t0));
  }
  std::printf("%-30s F=%-9lld %-8s wall %.3f s  cpu %.3f s (best of %d)\n  %s\n", label.c_str(),
              static_cast<long long>(r.num_faces), igm::certify::to_string(r.verdict), best, best_cpu, repeats,
              igm::certify::summary(r).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  fs::path shared;
  if (argc > 1) {
    shared = argv[1];
  } else if (const char* env = std::getenv("IGM_DATA_DIR"); env && *env) {
    shared = env;
  } else {
    shared = fs::path(__FILE__).parent_path().parent_path().parent_path() / "shared";
  }
  for (const char* f : {"duck_miq_4_param.obj", "duck_qc_8_param.obj", "fandisk_param.obj"}) {
    const fs::path p = shared / "igm" / f;
    if (fs::exists(p)) {
      time_file(f, p, 3);
    } else {
      std::printf("%-28s missing (%s)\n", f, p.string().c_str());
    }
  }
  const int n = 708;  // 2 n^2 = 1,002,528 triangles
  for (bool per_corner : {false, true}) {
    const fs::path p = fs::temp_directory_path() / (per_corner ? "igm_bench_torus_1M_corner.obj" : "igm_bench_torus_1M.obj");
    auto t0 = Clock::now();
    write_torus(p, n, per_corner);
    std::printf("generated %s (%.1f MB) in %.2f s\n", p.string().c_str(), double(fs::file_size(p)) / 1e6,
                seconds_since(t0));
    time_file(per_corner ? "torus 1M (vt per corner)" : "torus 1M (vt per grid point)", p, 1);
    fs::remove(p);
  }
  return 0;
}
