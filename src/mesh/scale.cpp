#include "igm/mesh/scale.h"

#include <algorithm>
#include <cmath>

namespace igm {

double unit_scale(const std::vector<Vec3d>& positions) {
  double m = 0;
  for (const Vec3d& p : positions)
    for (double c : {p.x, p.y, p.z})
      if (std::isfinite(c)) m = std::max(m, std::fabs(c));
  if (m == 0) return 1;
  int k = 0;
  std::frexp(m, &k);  // m < 2^k
  return std::ldexp(1.0, -k);
}

double scaled_distance(const Vec3d& p, const Vec3d& q, double s) {
  const double dx = s * p.x - s * q.x, dy = s * p.y - s * q.y, dz = s * p.z - s * q.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

std::vector<Vec3d> scaled_positions(const std::vector<Vec3d>& positions, double s) {
  std::vector<Vec3d> out(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) out[i] = {s * positions[i].x, s * positions[i].y, s * positions[i].z};
  return out;
}

}  // namespace igm
