#include "igm/arrange/synthetic_disk.h"

#include <cmath>
#include <map>
#include <random>

#include "igm/core/error.h"

namespace igm {

PlanarTriangulation make_synthetic_disk(const std::vector<Point2q>& corners, const Point2q& centre,
                                        const SyntheticDiskOptions& o) {
  if (o.subdivisions < 0 || o.subdivisions > 12 || o.insertions < 0 || corners.size() < 3)
    throw Error(ErrorKind::InvalidArgument, "make_synthetic_disk: bad options");
  const int n = static_cast<int>(corners.size());
  PlanarTriangulation m;
  m.positions = corners;
  m.positions.push_back(centre);
  for (int k = 0; k < n; ++k) m.triangles.push_back({n, k, (k + 1) % n});
  for (int s = 0; s < o.subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const Point2q &pa = m.positions[a], &pb = m.positions[b];
      m.positions.push_back({Rational((pa.x + pb.x) / 2), Rational((pa.y + pb.y) / 2)});
      const int id = static_cast<int>(m.positions.size()) - 1;
      mid.emplace(key, id);
      return id;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(4 * m.triangles.size());
    for (const auto& T : m.triangles) {
      const int a = T[0], b = T[1], c = T[2];
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.push_back({a, ab, ca});
      next.push_back({ab, b, bc});
      next.push_back({ca, bc, c});
      next.push_back({ab, bc, ca});
    }
    m.triangles.swap(next);
  }
  std::mt19937_64 rng(o.seed);
  for (int k = 0; k < o.insertions; ++k) {
    const std::size_t t = std::uniform_int_distribution<std::size_t>(0, m.triangles.size() - 1)(rng);
    const auto T = m.triangles[t];
    std::uniform_int_distribution<int> w(1, 16);
    const int w0 = w(rng), w1 = w(rng), w2 = w(rng);
    const Rational s(w0 + w1 + w2);
    const Point2q &a = m.positions[T[0]], &b = m.positions[T[1]], &c = m.positions[T[2]];
    m.positions.push_back({Rational((w0 * a.x + w1 * b.x + w2 * c.x) / s), Rational((w0 * a.y + w1 * b.y + w2 * c.y) / s)});
    const int p = static_cast<int>(m.positions.size()) - 1;
    m.triangles[t] = {T[0], T[1], p};
    m.triangles.push_back({T[1], T[2], p});
    m.triangles.push_back({T[2], T[0], p});
  }
  if (o.perturb > 0) {
    const int nv = static_cast<int>(m.positions.size());
    const PlanarAdjacency adj = PlanarAdjacency::build(nv, m.triangles);
    std::vector<char> boundary(nv, 0);
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      for (int i = 0; i < 3; ++i)
        if (adj.neighbor[t][i] < 0) boundary[m.triangles[t][i]] = boundary[m.triangles[t][(i + 1) % 3]] = 1;
    std::uniform_real_distribution<double> coin(0, 1);
    std::uniform_int_distribution<int> step(-16, 16);
    for (int v = 0; v < nv; ++v) {
      if (boundary[v] || coin(rng) >= o.perturb) continue;
      // Scale: a power of two below a quarter of the shortest incident edge (doubles only
      // choose the offset; acceptance is exact).
      double h = 1e300;
      for (int k = adj.star_begin[v]; k < adj.star_begin[v + 1]; ++k)
        for (int c : m.triangles[adj.star[k]])
          if (c != v) {
            const double dx = to_double(m.positions[c].x - m.positions[v].x), dy = to_double(m.positions[c].y - m.positions[v].y);
            h = std::min(h, std::sqrt(dx * dx + dy * dy));
          }
      int e = static_cast<int>(std::floor(std::log2(h))) - 6;
      const Point2q old = m.positions[v];
      for (int attempt = 0; attempt < 4; ++attempt, --e) {  // bounded: 4 attempts
        Rational scale = 1;
        if (e >= 0) mpq_mul_2exp(scale.get_mpq_t(), scale.get_mpq_t(), e);
        else mpq_div_2exp(scale.get_mpq_t(), scale.get_mpq_t(), -e);
        m.positions[v] = {Rational(old.x + step(rng) * scale), Rational(old.y + step(rng) * scale)};
        bool ok = true;
        for (int k = adj.star_begin[v]; k < adj.star_begin[v + 1] && ok; ++k) {
          const auto& T = m.triangles[adj.star[k]];
          ok = orient2d(m.positions[T[0]], m.positions[T[1]], m.positions[T[2]]) == Sign::Positive;
        }
        if (ok) break;
        m.positions[v] = old;
      }
    }
  }
  return m;
}

}  // namespace igm
