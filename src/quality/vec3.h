#pragma once
// Internal to the quality metrics (quality.cpp, surface_distance.cpp): double vector arithmetic on
// igm::Vec3d. Not installed, not part of the API.
#include <cmath>

#include "igm/exact/predicates.h"

namespace igm::quality_internal {

inline Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3d add(const Vec3d& a, const Vec3d& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3d mul(const Vec3d& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3d& a) { return std::sqrt(dot(a, a)); }
inline bool finite(const Vec3d& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
inline bool finite(const Vec2d& a) { return std::isfinite(a.x) && std::isfinite(a.y); }
inline double coordinate(const Vec3d& a, int axis) {
  return axis == 0 ? a.x : axis == 1 ? a.y : a.z;
}

}  // namespace igm::quality_internal
