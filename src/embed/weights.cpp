#include "igm/embed/weights.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "igm/core/error.h"

namespace igm {

namespace {

struct V3 {
  double x, y, z;
};
V3 sub(const Vec3d& a, const Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot3(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double norm3(const V3& a) { return std::sqrt(dot3(a, a)); }
double cross_norm(const V3& a, const V3& b) {
  const double x = a.y * b.z - a.z * b.y, y = a.z * b.x - a.x * b.z, z = a.x * b.y - a.y * b.x;
  return std::sqrt(x * x + y * y + z * z);
}

}  // namespace

const char* to_string(WeightKind kind) {
  switch (kind) {
    case WeightKind::Uniform:
      return "uniform";
    case WeightKind::Cotan:
      return "cotan";
    case WeightKind::MeanValue:
      return "mean-value";
  }
  return "?";
}

std::vector<int> edge_weights(const std::vector<Vec3d>& positions, const std::vector<std::array<int, 3>>& triangles,
                              WeightKind kind) {
  const std::size_t nf = triangles.size(), nh = 3 * nf;
  const auto nv = static_cast<std::int64_t>(positions.size());
  for (std::size_t f = 0; f < nf; ++f)
    for (int v : triangles[f])
      if (v < 0 || v >= nv)
        throw Error(ErrorKind::InvalidArgument, "edge_weights: triangle " + std::to_string(f) + " refers to vertex " +
                                                    std::to_string(v),
                    {static_cast<std::int64_t>(f)});
  if (kind == WeightKind::Uniform) return std::vector<int>(nh, 1);
  // Edges: sort the half-edges by their unordered end points; an edge's halves are neighbours.
  std::vector<std::uint64_t> key(nh);
  for (std::size_t h = 0; h < nh; ++h) {
    const int a = triangles[h / 3][h % 3], b = triangles[h / 3][(h % 3 + 1) % 3];
    key[h] = (static_cast<std::uint64_t>(std::min(a, b)) << 32 | static_cast<std::uint32_t>(std::max(a, b)));
  }
  std::vector<std::uint32_t> order(nh);
  for (std::size_t h = 0; h < nh; ++h) order[h] = static_cast<std::uint32_t>(h);
  std::sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) {
    return key[p] != key[q] ? key[p] < key[q] : p < q;
  });
  std::vector<int> edge_of(nh);
  int ne = 0;
  for (std::size_t i = 0; i < nh; ++i) {
    if (i > 0 && key[order[i]] != key[order[i - 1]]) ++ne;
    edge_of[order[i]] = ne;
  }
  ++ne;
  std::vector<double> w(ne, 0.0);
  std::vector<char> got(ne, 0);
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = triangles[f];
    const V3 e[3] = {sub(positions[t[1]], positions[t[0]]), sub(positions[t[2]], positions[t[1]]),
                     sub(positions[t[0]], positions[t[2]])};  // e[i]: corner i -> corner i+1
    const double len[3] = {norm3(e[0]), norm3(e[1]), norm3(e[2])};
    const double area2 = cross_norm(e[0], e[2]);  // twice the area
    if (!(area2 > 0) || !std::isfinite(area2) || !(len[0] > 0) || !(len[1] > 0) || !(len[2] > 0)) continue;
    for (int i = 0; i < 3; ++i) {
      // Corner i: between -e[i-1] (towards corner i-1) and e[i] (towards corner i+1).
      const V3 prev{-e[(i + 2) % 3].x, -e[(i + 2) % 3].y, -e[(i + 2) % 3].z};
      const double c = dot3(prev, e[i]);  // |.||.| cos(angle_i)
      if (kind == WeightKind::Cotan) {
        // cot(angle_i) = cos / sin = c / area2 weighs the opposite edge (corner i+1 -> i+2).
        const int h = static_cast<int>(3 * f) + (i + 1) % 3;
        w[edge_of[h]] += c / area2;
        got[edge_of[h]] = 1;
      } else {
        // tan(angle_i / 2) = sin / (1 + cos) = area2 / (|a||b| + c), on both edges at corner i.
        const double denom = len[i] * len[(i + 2) % 3] + c;
        const double th = denom > 0 ? area2 / denom : HUGE_VAL;
        const int out = static_cast<int>(3 * f) + i, in = static_cast<int>(3 * f) + (i + 2) % 3;
        w[edge_of[out]] += th / len[i];
        w[edge_of[in]] += th / len[(i + 2) % 3];
        got[edge_of[out]] = got[edge_of[in]] = 1;
      }
    }
  }
  std::vector<double> positive;
  for (int e = 0; e < ne; ++e)
    if (got[e] && std::isfinite(w[e]) && w[e] > 0) positive.push_back(w[e]);
  double m = 1;
  if (!positive.empty()) {
    std::nth_element(positive.begin(), positive.begin() + positive.size() / 2, positive.end());
    m = positive[positive.size() / 2];
  }
  const double lo = std::ldexp(m, -8), hi = std::ldexp(m, 8);
  std::vector<int> weight(ne);
  for (int e = 0; e < ne; ++e) {
    double x = w[e];
    if (!got[e] || std::isnan(x)) x = lo;
    x = std::min(hi, std::max(lo, x));
    weight[e] = static_cast<int>(std::min(65536.0, std::max(1.0, std::nearbyint(x / lo))));
  }
  std::vector<int> out(nh);
  for (std::size_t h = 0; h < nh; ++h) out[h] = weight[edge_of[h]];
  return out;
}

}  // namespace igm
