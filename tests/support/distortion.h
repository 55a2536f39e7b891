#pragma once
// Distortion of an IGM's map against its 3D triangles, for the smoothing tests and benchmark (a
// small local measure; doubles only, nothing is decided from it but a test's expectation).
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "igm/output/igm_mesh.h"

namespace igm_test {

struct Distortion {
  double p99_conformal = 0;  // area-weighted 99th percentile of s1/s2
  double sd_energy = 0;      // area-weighted mean of s1^2 + s2^2 + s1^-2 + s2^-2 (4 at best)
  int measured = 0;          // triangles of positive 3D and UV area (the others are left out)
};

/// s1 >= s2 are the singular values of the map from each 3D triangle, scaled by sqrt(total UV
/// area / total 3D area) of the measured triangles, to its UV triangle (coordinates rounded to
/// doubles).
inline Distortion measure_distortion(const igm::IgmMesh& m,
                                     const std::vector<std::array<igm::Point2q, 3>>& uv) {
  struct Tri {
    double n2, det, area;  // |F|^2 and det F before scaling, 3D area
  };
  std::vector<Tri> tris;
  double area3 = 0, area_uv = 0;
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const auto& t = m.triangles[f];
    const igm::Vec3d &p0 = m.positions[t[0]], &p1 = m.positions[t[1]], &p2 = m.positions[t[2]];
    const double a[3] = {p1.x - p0.x, p1.y - p0.y, p1.z - p0.z},
                 b[3] = {p2.x - p0.x, p2.y - p0.y, p2.z - p0.z};
    const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]};
    const double cross = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    double u[3][2];
    for (int i = 0; i < 3; ++i)
      u[i][0] = igm::approximate(uv[f][i].x), u[i][1] = igm::approximate(uv[f][i].y);
    const double j00 = u[1][0] - u[0][0], j01 = u[2][0] - u[0][0], j10 = u[1][1] - u[0][1],
                 j11 = u[2][1] - u[0][1];
    const double det_j = j00 * j11 - j01 * j10;
    if (!(cross > 0) || !(la > 0) || !(det_j > 0)) continue;
    // the 3D triangle laid as [[la, dot/la], [0, cross/la]]; F = J M^-1
    const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const double m00 = 1 / la, m01 = -dot / (la * cross), m11 = la / cross;
    const double f00 = j00 * m00, f01 = j00 * m01 + j01 * m11, f10 = j10 * m00,
                 f11 = j10 * m01 + j11 * m11;
    tris.push_back(
        {f00 * f00 + f01 * f01 + f10 * f10 + f11 * f11, f00 * f11 - f01 * f10, cross / 2});
    area3 += cross / 2;
    area_uv += det_j / 2;
  }
  Distortion d;
  d.measured = static_cast<int>(tris.size());
  if (tris.empty()) return d;
  const double k2 = area3 / area_uv;  // F scaled by 1/s: |F|^2 and det F times 1/s^2
  std::vector<std::pair<double, double>> conformal;
  for (const Tri& t : tris) {
    const double n2 = t.n2 * k2, det = t.det * k2;
    d.sd_energy += t.area * n2 * (1 + 1 / (det * det)) / area3;
    const double s1sq = (n2 + std::sqrt(std::max(0.0, n2 * n2 - 4 * det * det))) / 2;
    conformal.push_back({s1sq / det, t.area});
  }
  std::sort(conformal.begin(), conformal.end());
  double acc = 0;
  d.p99_conformal = conformal.back().first;
  for (const auto& [value, area] : conformal)
    if ((acc += area) >= 0.99 * area3) {
      d.p99_conformal = value;
      break;
    }
  return d;
}

}  // namespace igm_test
