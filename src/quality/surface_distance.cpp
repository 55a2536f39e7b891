#include "igm/quality/surface_distance.h"

#include "../core/parallel.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>

#include "igm/core/error.h"
#include "vec3.h"

namespace igm {

using namespace quality_internal;

namespace {

constexpr int kLeafSize = 4;
// Depth <= 63 + ceil(log2(F)) <= 94 for F < 2^31; the traversal holds at most depth + 1 nodes.
constexpr int kStackSize = 96;
constexpr double kInf = std::numeric_limits<double>::infinity();

Vec3d closest_on_segment(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = sub(b, a);
  const double l2 = dot(ab, ab);
  if (!(l2 > 0)) return a;
  const double t = std::clamp(dot(sub(p, a), ab) / l2, 0.0, 1.0);
  return add(a, mul(ab, t));
}

// Squared distance from p to box [lo, hi].
inline double box_distance2(const double* lo, const double* hi, const Vec3d& p) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double c = coordinate(p, k);
    const double d = std::max(0.0, std::max(lo[k] - c, c - hi[k]));
    d2 += d * d;
  }
  return d2;
}

// Spreads the low 21 bits of v to every third bit.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

// The order of the points along a Morton (Z-order) curve of their bounding box, 21 bits an axis;
// ties by index, so deterministic. `sorted_codes`, if given, receives the codes in that order.
std::vector<int> morton_order(const std::vector<Vec3d>& points,
                              std::vector<std::uint64_t>* sorted_codes = nullptr) {
  double lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
  for (const Vec3d& p : points)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], coordinate(p, k));
      hi[k] = std::max(hi[k], coordinate(p, k));
    }
  std::vector<std::pair<std::uint64_t, int>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const double extent = hi[k] - lo[k];
      const double u = extent > 0 ? (coordinate(points[i], k) - lo[k]) / extent : 0.0;
      const double t = u >= 0 ? std::min(u, 1.0) : 0.0;  // nan (inf / inf) -> 0: a valid cast
      const auto cell = static_cast<std::uint64_t>(t * 2097151.0);
      code |= spread_bits(cell) << k;
    }
    keyed[i] = {code, static_cast<int>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<int> order(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) order[i] = keyed[i].second;
  if (sorted_codes) {
    sorted_codes->resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) (*sorted_codes)[i] = keyed[i].first;
  }
  return order;
}

inline Vec3d closest_point(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  // Barycentric coordinates (u, v, w) of the projection of p onto the plane, from the normal
  // equations of p - a ~ v ab + w ac; denominator |ab x ac|^2 (Lagrange's identity).
  const Vec3d ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d00 = dot(ab, ab), d01 = dot(ab, ac), d11 = dot(ac, ac);
  const double d20 = dot(ap, ab), d21 = dot(ap, ac);
  const double denom = d00 * d11 - d01 * d01;
  // p's projection beyond the edge opposite a, b, c; all three for a triangle whose Gram
  // determinant is not positive in double (degenerate, or a sliver within rounding of it).
  std::array<bool, 3> outside = {true, true, true};
  if (denom > 0) {
    const double v = (d11 * d20 - d01 * d21) / denom, w = (d00 * d21 - d01 * d20) / denom;
    const double u = 1.0 - v - w;
    if (u >= 0 && v >= 0 && w >= 0) return add(a, add(mul(ab, v), mul(ac, w)));
    if (u < 0 || v < 0 || w < 0) outside = {u < 0, v < 0, w < 0};  // else nan: all three
  }
  // Else the nearest point lies on an edge whose line has the projection on its outer side (the
  // nearest point x of a convex polygon to a point q of its plane outside it: q - x is normal to
  // the boundary at x, so q is beyond an edge through x).
  const std::array<std::pair<const Vec3d*, const Vec3d*>, 3> edges = {
      {{&b, &c}, {&c, &a}, {&a, &b}}};
  Vec3d best;
  double best2 = kInf;
  for (int i = 0; i < 3; ++i) {
    if (!outside[i]) continue;
    const Vec3d q = closest_on_segment(p, *edges[i].first, *edges[i].second);
    const double d2 = dot(sub(p, q), sub(p, q));
    if (d2 < best2 || best2 == kInf) best2 = d2, best = q;
  }
  return best;
}

}  // namespace

Vec3d closest_point_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return closest_point(p, a, b, c);
}

TriangleBvh::TriangleBvh(const std::vector<Vec3d>& positions,
                         const std::vector<std::array<int, 3>>& triangles) {
  const std::size_t n = triangles.size();
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max() / 2))
    throw Error(ErrorKind::TooLarge, "TriangleBvh: more than 2^30 triangles");
  for (std::size_t t = 0; t < n; ++t)
    for (int v : triangles[t])
      if (v < 0 || static_cast<std::size_t>(v) >= positions.size())
        throw Error(
            ErrorKind::IndexOutOfRange,
            "TriangleBvh: triangle " + std::to_string(t) + " uses vertex " + std::to_string(v),
            {static_cast<std::int64_t>(t)});
  if (n == 0) return;
  std::vector<Vec3d> centroid(n);
  for (std::size_t t = 0; t < n; ++t) {
    const auto& tri = triangles[t];
    for (int v : tri)
      if (!finite(positions[v]))
        throw Error(ErrorKind::NonFinite, "TriangleBvh: vertex " + std::to_string(v), {v});
    centroid[t] = mul(add(add(positions[tri[0]], positions[tri[1]]), positions[tri[2]]), 1.0 / 3.0);
  }
  std::vector<std::uint64_t> code;
  ids_ = morton_order(centroid, &code);
  corners_.resize(n);
  slot_of_.resize(n);
  for (std::size_t s = 0; s < n; ++s) {
    const auto& tri = triangles[ids_[s]];
    corners_[s] = {positions[tri[0]], positions[tri[1]], positions[tri[2]]};
    slot_of_[ids_[s]] = static_cast<int>(s);
  }
  // Each task makes one node from a non-empty range of slots; a range of more than kLeafSize
  // triangles is split into two non-empty parts, so at most 2n - 1 nodes (and tasks) in all.
  // The split: where the highest bit in which the range's first and last codes differ turns to 1
  // (the range's cell halved), or the middle if all codes are equal. Depth <= 63 + ceil(log2 n).
  struct Task {
    int node, begin, end;
  };
  std::vector<Task> tasks = {{0, 0, static_cast<int>(n)}};
  nodes_.push_back({});
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    Node& node = nodes_[task.node];
    if (task.end - task.begin <= kLeafSize) {
      node.first = task.begin;
      node.count = task.end - task.begin;
      continue;
    }
    int mid = task.begin + (task.end - task.begin) / 2;
    const std::uint64_t differ = code[task.begin] ^ code[task.end - 1];
    if (differ != 0) {
      const int bit = 63 - std::countl_zero(differ);
      mid = static_cast<int>(
          std::partition_point(code.begin() + task.begin, code.begin() + task.end,
                               [&](std::uint64_t c) { return !((c >> bit) & 1); }) -
          code.begin());
    }
    node.first = static_cast<int>(nodes_.size());
    node.second = node.first + 1;
    node.count = 0;
    tasks.push_back({node.second, mid, task.end});
    tasks.push_back({node.first, task.begin, mid});
    nodes_.push_back({});  // invalidates `node`
    nodes_.push_back({});
  }
  // Boxes bottom-up: children have larger indices than their parent.
  for (std::size_t i = nodes_.size(); i-- > 0;) {
    Node& node = nodes_[i];
    std::fill(node.lo, node.lo + 3, kInf);
    std::fill(node.hi, node.hi + 3, -kInf);
    auto grow = [&](const double* lo, const double* hi) {
      for (int k = 0; k < 3; ++k)
        node.lo[k] = std::min(node.lo[k], lo[k]), node.hi[k] = std::max(node.hi[k], hi[k]);
    };
    if (node.count > 0) {
      for (int s = node.first; s < node.first + node.count; ++s)
        for (const Vec3d& p : corners_[s]) {
          const double c[3] = {p.x, p.y, p.z};
          grow(c, c);
        }
    } else {
      grow(nodes_[node.first].lo, nodes_[node.first].hi);
      grow(nodes_[node.second].lo, nodes_[node.second].hi);
    }
  }
}

double TriangleBvh::query(const Vec3d& p, int& slot, Vec3d& point) const {
  double best2 = kInf;
  auto test = [&](int s) {
    const auto& c = corners_[s];
    const Vec3d q = closest_point(p, c[0], c[1], c[2]);
    const double d2 = dot(sub(p, q), sub(p, q));
    if (d2 < best2 || slot < 0) best2 = d2, slot = s, point = q;
  };
  if (slot >= 0) test(slot);
  if (nodes_.empty()) return best2;
  int stack[kStackSize];
  double stack_d2[kStackSize];
  int top = 0;
  stack[top] = 0;
  stack_d2[top++] = box_distance2(nodes_[0].lo, nodes_[0].hi, p);
  while (top > 0) {  // bound: every node is pushed at most once
    --top;
    if (stack_d2[top] > best2) continue;
    const Node& node = nodes_[stack[top]];
    if (node.count > 0) {
      for (int s = node.first; s < node.first + node.count; ++s) test(s);
      continue;
    }
    int near = node.first, far = node.second;
    double near_d2 = box_distance2(nodes_[near].lo, nodes_[near].hi, p);
    double far_d2 = box_distance2(nodes_[far].lo, nodes_[far].hi, p);
    if (far_d2 < near_d2) std::swap(near, far), std::swap(near_d2, far_d2);
    if (top + 2 > kStackSize) throw Error(ErrorKind::Internal, "TriangleBvh: stack overflow");
    if (far_d2 <= best2) stack[top] = far, stack_d2[top++] = far_d2;
    if (near_d2 <= best2) stack[top] = near, stack_d2[top++] = near_d2;
  }
  return best2;
}

SurfaceNearest TriangleBvh::nearest(const Vec3d& p, int hint) const {
  if (hint < -1 || hint >= static_cast<int>(ids_.size()))
    throw Error(ErrorKind::InvalidArgument,
                "TriangleBvh: hint " + std::to_string(hint) + " is not a triangle id");
  SurfaceNearest r;
  int slot = hint < 0 ? -1 : slot_of_[hint];
  r.distance = std::sqrt(query(p, slot, r.point));
  r.triangle = slot < 0 ? -1 : ids_[slot];
  return r;
}

std::vector<double> TriangleBvh::distances(const std::vector<Vec3d>& points) const {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i]))
      throw Error(ErrorKind::NonFinite, "TriangleBvh: query point " + std::to_string(i),
                  {static_cast<std::int64_t>(i)});
  }
  std::vector<double> out(points.size(), kInf);
  if (ids_.empty()) return out;
  // In parallel over chunks of the Morton order, each starting its own hint: the nearest distance
  // does not depend on the hint (nor on the threads).
  const std::vector<int> order = morton_order(points);
  parallel::for_chunks(static_cast<std::int64_t>(order.size()), 1024, [&](std::int64_t b, std::int64_t e) {
    int slot = -1;
    Vec3d point;
    for (std::int64_t k = b; k < e; ++k) out[order[k]] = std::sqrt(query(points[order[k]], slot, point));
  });
  return out;
}

}  // namespace igm
