#include "igm/quality/quality.h"

#include "../core/parallel.h"

#include <algorithm>
#include <map>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numeric>
#include <utility>

#include "igm/core/error.h"
#include "igm/quality/surface_distance.h"
#include "vec3.h"

namespace igm {

using namespace quality_internal;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

// The power of two 2^-e with max_abs = m 2^e, 0.5 <= m < 1 (1 for max_abs = 0): multiplying by it
// is exact (but for results below 2^-1022) and brings every coordinate below 1 in magnitude, so
// that differences, cross products and squares stay finite.
double unit_scale(double max_abs) {
  if (!(max_abs > 0)) return 1.0;
  int e = 0;
  std::frexp(max_abs, &e);
  return std::ldexp(1.0, -e);
}

double max_abs(const std::vector<Vec3d>& points) {
  double m = 0;
  for (const Vec3d& p : points) m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  return m;
}

std::vector<Vec3d> scaled(const std::vector<Vec3d>& points, double s) {
  std::vector<Vec3d> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = mul(points[i], s);
  return out;
}

void require_finite(const std::vector<Vec3d>& points, const char* what) {
  for (std::size_t v = 0; v < points.size(); ++v)
    if (!finite(points[v]))
      throw Error(
          ErrorKind::NonFinite,
          std::string(what) + ": vertex " + std::to_string(v) + " has a non-finite coordinate",
          {static_cast<std::int64_t>(v)});
}

template <std::size_t N>
void require_ids(const std::vector<std::array<int, N>>& faces, std::size_t num_vertices,
                 const char* what) {
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int v : faces[f])
      if (v < 0 || static_cast<std::size_t>(v) >= num_vertices)
        throw Error(ErrorKind::IndexOutOfRange,
                    std::string(what) + " " + std::to_string(f) + " uses vertex " +
                        std::to_string(v) + " of " + std::to_string(num_vertices),
                    {static_cast<std::int64_t>(f)});
}

// Exactly: the 3D triangle has zero area iff its projections onto the three coordinate planes
// all do (their orientations are the components of the cross product).
bool zero_area_3d(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  using P = Vec2d;
  return orient2d(P{a.x, a.y}, P{b.x, b.y}, P{c.x, c.y}) == Sign::Zero &&
         orient2d(P{a.y, a.z}, P{b.y, b.z}, P{c.y, c.z}) == Sign::Zero &&
         orient2d(P{a.z, a.x}, P{b.z, b.x}, P{c.z, c.x}) == Sign::Zero;
}

double triangle_area(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return 0.5 * norm(cross(sub(b, a), sub(c, a)));
}

Quantiles weighted_summary(const std::vector<double>& values, const std::vector<double>& weights) {
  const std::vector<double> q = weighted_quantiles(values, weights, {0.5, 0.9, 0.99});
  Quantiles r;
  r.median = q[0];
  r.p90 = q[1];
  r.p99 = q[2];
  r.max = values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
  return r;
}

// Per-triangle quantities of the map 3D -> UV (docs/quality.md, "IGM").
struct TriangleMap {
  double area3 = 0, area_uv = 0;  // of the scaled coordinates
  double frobenius2 = 0;          // |J|_F^2 = s1^2 + s2^2
  double det = 0;                 // det J = s1 s2 = area_uv / area3
  double conformal = 0;           // s1 / s2
};

// False if a quantity is not finite or not positive in double.
bool map_triangle(const std::array<Vec3d, 3>& p, const std::array<Vec2d, 3>& u, TriangleMap& m) {
  // Isometric plane coordinates: p0 -> (0, 0), p1 -> (l1, 0), p2 -> (x2, y2) with y2 > 0.
  const Vec3d e1 = sub(p[1], p[0]), e2 = sub(p[2], p[0]);
  const double l1 = norm(e1);
  const double n = norm(cross(e1, e2));
  const double x2 = dot(e1, e2) / l1, y2 = n / l1;
  const double du1x = u[1].x - u[0].x, du1y = u[1].y - u[0].y;
  const double du2x = u[2].x - u[0].x, du2y = u[2].y - u[0].y;
  // J [l1 x2; 0 y2] = [du1 du2]: J's first column is du1 / l1, its second (du2 - x2 J e_x) / y2.
  const double a = du1x / l1, c = du1y / l1;
  const double b = (du2x - x2 * a) / y2, d = (du2y - x2 * c) / y2;
  m.area3 = 0.5 * n;
  m.area_uv = 0.5 * (du1x * du2y - du1y * du2x);
  m.frobenius2 = a * a + b * b + c * c + d * d;
  m.det = m.area_uv / m.area3;
  // Singular values of [a b; c d]: s1 = hypot(E, H) + hypot(F, G), s2 = det / s1.
  const double s1 =
      std::hypot(0.5 * (a + d), 0.5 * (c - b)) + std::hypot(0.5 * (a - d), 0.5 * (c + b));
  m.conformal = std::max(1.0, s1 * s1 / m.det);  // s1 / s2 >= 1; the clamp only absorbs rounding
  for (double x : {m.area3, m.area_uv, m.frobenius2, m.det, m.conformal})
    if (!(x > 0) || !std::isfinite(x)) return false;
  return true;
}

// Scaled Jacobian, four corner-angle deviations (degrees) and area of one quad
// (docs/quality.md, "Quad mesh").
struct QuadShape {
  double sj = 0;
  bool degenerate = false;
  std::array<double, 4> angle_deviation{};
  double area = 0;
};

QuadShape quad_shape(const std::array<Vec3d, 4>& p) {
  QuadShape r;
  const Vec3d d = cross(sub(p[2], p[0]), sub(p[3], p[1]));
  const double dn = norm(d);
  r.degenerate = !(dn > 0) || !std::isfinite(dn);
  const Vec3d n = r.degenerate ? Vec3d{} : mul(d, 1.0 / dn);
  double sj = kInf;
  for (int i = 0; i < 4; ++i) {
    const Vec3d e1 = sub(p[(i + 1) % 4], p[i]), e2 = sub(p[(i + 3) % 4], p[i]);
    const double l1 = norm(e1), l2 = norm(e2);
    const Vec3d c = cross(e1, e2);
    if (!(l1 > 0 && l2 > 0)) {
      r.degenerate = true;
      r.angle_deviation[i] = 90.0;  // a corner with a zero edge: angle 0 by convention
      continue;
    }
    // angle = atan2(|c|, e1.e2), so angle - 90 deg = -atan2(e1.e2, |c|) (exactly 0 when e1.e2 = 0).
    r.angle_deviation[i] = std::fabs(std::atan2(dot(e1, e2), norm(c))) * kDegreesPerRadian;
    sj = std::min(sj, dot(c, n) / (l1 * l2));
  }
  r.sj = r.degenerate || !std::isfinite(sj) ? 0.0 : sj;
  r.degenerate = r.degenerate || !std::isfinite(sj);
  r.area = 0.5 * (triangle_area(p[0], p[1], p[2]) + triangle_area(p[0], p[2], p[3]) +
                  triangle_area(p[0], p[1], p[3]) + triangle_area(p[1], p[2], p[3]));
  return r;
}

// Every `stride`-th sample (fixed stride n / m, as integers): indices floor(i n / m), i < m.
std::vector<Vec3d> subsample(std::vector<Vec3d> samples, std::size_t m) {
  const std::size_t n = samples.size();
  if (n <= m) return samples;
  std::vector<Vec3d> out(m);
  for (std::size_t i = 0; i < m; ++i)
    out[i] = samples[static_cast<std::size_t>((static_cast<unsigned __int128>(i) * n) / m)];
  return out;
}

// The positions of the vertices that some face uses, in increasing id.
std::vector<Vec3d> used_positions(const std::vector<Vec3d>& p, const auto& faces) {
  std::vector<char> used(p.size(), 0);
  for (const auto& f : faces)
    for (int v : f) used[v] = 1;
  std::vector<Vec3d> out;
  for (std::size_t v = 0; v < p.size(); ++v)
    if (used[v]) out.push_back(p[v]);
  return out;
}

// Samples on the quad mesh: its vertices, edge midpoints and quad centres (docs/quality.md).
std::vector<Vec3d> quad_samples(const std::vector<Vec3d>& p,
                                const std::vector<std::array<int, 4>>& quads) {
  std::vector<Vec3d> out = used_positions(p, quads);
  std::vector<std::pair<int, int>> edges;
  edges.reserve(4 * quads.size());
  for (const auto& q : quads)
    for (int i = 0; i < 4; ++i) edges.push_back(std::minmax(q[i], q[(i + 1) % 4]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& [a, b] : edges) out.push_back(mul(add(p[a], p[b]), 0.5));
  for (const auto& q : quads)
    out.push_back(mul(add(add(p[q[0]], p[q[1]]), add(p[q[2]], p[q[3]])), 0.25));
  return out;
}

// Samples on the input: its vertices and triangle centroids.
std::vector<Vec3d> input_samples(const std::vector<Vec3d>& p,
                                 const std::vector<std::array<int, 3>>& tris) {
  std::vector<Vec3d> out = used_positions(p, tris);
  for (const auto& t : tris) out.push_back(mul(add(add(p[t[0]], p[t[1]]), p[t[2]]), 1.0 / 3.0));
  return out;
}

// The diagonal of the bounding box of the vertices used by the triangles (0 if none).
double used_diagonal(const std::vector<Vec3d>& p, const std::vector<std::array<int, 3>>& tris) {
  const std::vector<Vec3d> used = used_positions(p, tris);
  if (used.empty()) return 0.0;
  Vec3d lo = used[0], hi = used[0];
  for (const Vec3d& q : used) {
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
  }
  return norm(sub(hi, lo));
}

void measure_distance(const std::vector<Vec3d>& qp, const std::vector<std::array<int, 4>>& quads,
                      const std::vector<Vec3d>& ip, const std::vector<std::array<int, 3>>& tris,
                      std::size_t max_samples, QuadQuality& r) {
  r.distance_measured = true;
  const std::vector<Vec3d> on_quads = subsample(quad_samples(qp, quads), max_samples);
  const std::vector<Vec3d> on_input = subsample(input_samples(ip, tris), max_samples);
  r.distance_samples_quads = on_quads.size();
  r.distance_samples_input = on_input.size();
  if (quads.empty() || tris.empty()) {
    r.distance_max = r.distance_p99 = kInf;
    return;
  }
  std::vector<std::array<int, 3>> quad_triangles;
  quad_triangles.reserve(2 * quads.size());
  for (const auto& q : quads) {
    quad_triangles.push_back({q[0], q[1], q[2]});
    quad_triangles.push_back({q[0], q[2], q[3]});
  }
  std::vector<double> d = TriangleBvh(ip, tris).distances(on_quads);
  const std::vector<double> d_input = TriangleBvh(qp, quad_triangles).distances(on_input);
  d.insert(d.end(), d_input.begin(), d_input.end());
  const double diagonal = used_diagonal(ip, tris);
  r.distance_max = *std::max_element(d.begin(), d.end()) / diagonal;
  r.distance_p99 = quantiles(d, {0.99})[0] / diagonal;
}

// JSON writing: keys in the caller's order, numbers in the shortest round-trip form.
void put_number(std::string& o, double x) {
  if (!std::isfinite(x)) {
    o += "null";
    return;
  }
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  o.append(buf, res.ptr);
}

void put_key(std::string& o, const char* key) {
  if (o.size() > 1) o += ", ";
  o += '"';
  o += key;
  o += "\": ";
}

void put_field(std::string& o, const char* key, double x) {
  put_key(o, key);
  put_number(o, x);
}

void put_count(std::string& o, const char* key, long long n) {
  put_key(o, key);
  o += std::to_string(n);
}

void put_quantiles(std::string& o, const char* key, const Quantiles& q) {
  put_key(o, key);
  std::string inner = "{";
  put_field(inner, "median", q.median);
  put_field(inner, "p90", q.p90);
  put_field(inner, "p99", q.p99);
  put_field(inner, "max", q.max);
  o += inner + "}";
}

}  // namespace

std::vector<double> weighted_quantiles(const std::vector<double>& values,
                                       const std::vector<double>& weights,
                                       const std::vector<double>& qs) {
  if (values.size() != weights.size())
    throw Error(ErrorKind::InvalidArgument, "weighted_quantiles: " + std::to_string(values.size()) +
                                                " values but " + std::to_string(weights.size()) +
                                                " weights");
  for (std::size_t i = 0; i < values.size(); ++i)
    if (std::isnan(values[i]) || !std::isfinite(weights[i]) || !(weights[i] >= 0))
      throw Error(ErrorKind::InvalidArgument,
                  "weighted_quantiles: value " + std::to_string(i) +
                      " is nan, or its weight is not finite or negative",
                  {static_cast<std::int64_t>(i)});
  std::vector<double> out(qs.size(), 0.0);
  if (values.empty()) return out;
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return values[a] < values[b] || (values[a] == values[b] && a < b);
  });
  std::vector<double> cumulative(order.size());
  double sum = 0;
  for (std::size_t i = 0; i < order.size(); ++i) cumulative[i] = sum += weights[order[i]];
  for (std::size_t k = 0; k < qs.size(); ++k) {
    // The first position whose cumulative weight reaches q * total; the last reaches the total.
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), qs[k] * sum);
    const std::size_t i = it == cumulative.end() ? order.size() - 1 : it - cumulative.begin();
    out[k] = values[order[i]];
  }
  return out;
}

std::vector<double> quantiles(const std::vector<double>& values, const std::vector<double>& qs) {
  return weighted_quantiles(values, std::vector<double>(values.size(), 1.0), qs);
}

IgmQuality measure_igm(const std::vector<Vec3d>& positions,
                       const std::vector<std::array<int, 3>>& triangles,
                       const std::vector<std::array<Vec2d, 3>>& corner_uv) {
  if (corner_uv.size() != triangles.size())
    throw Error(ErrorKind::InvalidArgument, "measure_igm: " + std::to_string(triangles.size()) +
                                                " triangles but UVs for " +
                                                std::to_string(corner_uv.size()));
  require_ids(triangles, positions.size(), "measure_igm: triangle");
  double max3 = 0, max_uv = 0;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const Vec3d& p = positions[triangles[t][i]];
      const Vec2d& u = corner_uv[t][i];
      if (!finite(p))
        throw Error(ErrorKind::NonFinite,
                    "measure_igm: vertex " + std::to_string(triangles[t][i]) +
                        " has a non-finite coordinate",
                    {triangles[t][i]});
      if (!finite(u))
        throw Error(ErrorKind::NonFinite,
                    "measure_igm: triangle " + std::to_string(t) + " has a non-finite UV",
                    {static_cast<std::int64_t>(t)});
      max3 = std::max({max3, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
      max_uv = std::max({max_uv, std::fabs(u.x), std::fabs(u.y)});
    }
  const double s3 = unit_scale(max3), s_uv = unit_scale(max_uv);
  IgmQuality r;
  r.triangles = static_cast<int>(triangles.size());
  // Each triangle's map in parallel (core/parallel.h), then the valid ones in triangle order.
  std::vector<TriangleMap> all(triangles.size());
  std::vector<char> valid(triangles.size(), 0);
  parallel::for_each_index(static_cast<std::int64_t>(triangles.size()), 4096, [&](std::int64_t t) {
    const std::array<Vec3d, 3> p = {positions[triangles[t][0]], positions[triangles[t][1]],
                                    positions[triangles[t][2]]};
    const std::array<Vec2d, 3>& u = corner_uv[t];
    valid[t] = !zero_area_3d(p[0], p[1], p[2]) && orient2d(u[0], u[1], u[2]) == Sign::Positive &&
               map_triangle({mul(p[0], s3), mul(p[1], s3), mul(p[2], s3)},
                            {{{u[0].x * s_uv, u[0].y * s_uv},
                              {u[1].x * s_uv, u[1].y * s_uv},
                              {u[2].x * s_uv, u[2].y * s_uv}}},
                            all[t]);
  });
  std::vector<TriangleMap> maps;
  maps.reserve(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (valid[t])
      maps.push_back(all[t]);
    else
      ++r.degenerate;
  }
  std::vector<TriangleMap>().swap(all);
  if (maps.empty()) return r;
  double sum3 = 0, sum_uv = 0;
  for (const TriangleMap& m : maps) sum3 += m.area3, sum_uv += m.area_uv;
  // c2: the square of the UV scaling that makes the total UV area the total 3D area.
  const double c2 = sum3 / sum_uv;
  std::vector<double> weight(maps.size()), conformal(maps.size()), area(maps.size());
  double dirichlet = 0;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const TriangleMap& m = maps[i];
    weight[i] = m.area3;
    conformal[i] = m.conformal;
    // (A_uv / sum A_uv) / (A_3d / sum A_3d); finite and positive but for triangles whose
    // distortion leaves the double range (then the value is +inf, the sum below inf or nan).
    const double ratio = c2 * m.det;
    area[i] = std::max(ratio, 1.0 / ratio);
    // s1^2 + s2^2 + s1^-2 + s2^-2 = |J|^2 (1 + 1 / det^2), with J scaled by sqrt(c2).
    dirichlet += m.area3 * (c2 * m.frobenius2) * (1.0 + 1.0 / (ratio * ratio));
  }
  r.conformal = weighted_summary(conformal, weight);
  r.area = weighted_summary(area, weight);
  r.symmetric_dirichlet = dirichlet / sum3;
  return r;
}

QuadQuality measure_quads(const std::vector<Vec3d>& quad_positions,
                          const std::vector<std::array<int, 4>>& quads,
                          const std::vector<Vec3d>& input_positions,
                          const std::vector<std::array<int, 3>>& input_triangles,
                          const QuadQualityOptions& options) {
  require_ids(quads, quad_positions.size(), "measure_quads: quad");
  require_ids(input_triangles, input_positions.size(), "measure_quads: input triangle");
  require_finite(quad_positions, "measure_quads: quad mesh");
  require_finite(input_positions, "measure_quads: input");
  if (options.max_samples < 1)
    throw Error(ErrorKind::InvalidArgument, "measure_quads: max_samples must be >= 1");
  const double s = unit_scale(std::max(max_abs(quad_positions), max_abs(input_positions)));
  const std::vector<Vec3d> qp = scaled(quad_positions, s), ip = scaled(input_positions, s);

  QuadQuality r;
  r.quads = static_cast<int>(quads.size());
  r.vertices = static_cast<int>(quad_positions.size());
  std::vector<int> around(qp.size(), 0);
  for (const auto& q : quads)
    for (int v : q) ++around[v];
  for (int k : around) ++r.valence[k];
  {
    // Boundary vertices: on an edge that one quad has (an edge counted once over all quads).
    std::map<std::pair<int, int>, int> edges;
    for (const auto& q : quads)
      for (int i = 0; i < 4; ++i) ++edges[{std::min(q[i], q[(i + 1) % 4]), std::max(q[i], q[(i + 1) % 4])}];
    std::vector<char> boundary(qp.size(), 0);
    for (const auto& [e, n] : edges)
      if (n == 1) boundary[e.first] = boundary[e.second] = 1;
    for (std::size_t v = 0; v < around.size(); ++v) {
      if (boundary[v] || around[v] == 0) continue;
      if (around[v] != 4) ++r.irregular_vertices;
      r.max_valence = std::max(r.max_valence, around[v]);
    }
  }

  std::vector<double> sj(quads.size()), area(quads.size()), deviation;
  deviation.reserve(4 * quads.size());
  int below_half = 0, nonpositive = 0;
  for (std::size_t f = 0; f < quads.size(); ++f) {
    const auto& q = quads[f];
    const QuadShape shape = quad_shape({qp[q[0]], qp[q[1]], qp[q[2]], qp[q[3]]});
    sj[f] = shape.sj;
    area[f] = shape.area;
    r.degenerate += shape.degenerate;
    below_half += shape.sj < 0.5;
    nonpositive += shape.sj <= 0;
    deviation.insert(deviation.end(), shape.angle_deviation.begin(), shape.angle_deviation.end());
  }
  double input_area = 0;
  for (const auto& t : input_triangles) input_area += triangle_area(ip[t[0]], ip[t[1]], ip[t[2]]);
  if (!quads.empty()) {
    const std::vector<double> sq = quantiles(sj, {0.05, 0.5});
    r.sj_min = *std::min_element(sj.begin(), sj.end());
    r.sj_p5 = sq[0];
    r.sj_median = sq[1];
    r.sj_below_half = static_cast<double>(below_half) / static_cast<double>(quads.size());
    r.sj_nonpositive = static_cast<double>(nonpositive) / static_cast<double>(quads.size());
    const std::vector<double> dq = quantiles(deviation, {0.5, 0.95});
    r.angle_deviation_median = dq[0];
    r.angle_deviation_p95 = dq[1];
    const std::vector<double> aq = quantiles(area, {0.05, 0.95});
    r.area_p95_over_p5 = aq[0] > 0 ? aq[1] / aq[0] : kInf;
    std::sort(area.begin(), area.end());
    const double total = std::accumulate(area.begin(), area.end(), 0.0);
    const double half = std::accumulate(
        area.begin(), area.begin() + static_cast<std::ptrdiff_t>(area.size() / 2), 0.0);
    r.area_ratio = total / input_area;
    r.smallest_half_area = half / total;
  }
  if (options.distance) measure_distance(qp, quads, ip, input_triangles, options.max_samples, r);
  return r;
}

FeatureQuality measure_features(const std::vector<Vec3d>& input_positions,
                                const std::vector<std::array<int, 2>>& feature_edges,
                                const std::vector<Vec3d>& quad_positions,
                                const std::vector<std::array<int, 4>>& quads,
                                const FeatureQualityOptions& options) {
  require_ids(feature_edges, input_positions.size(), "measure_features: feature edge");
  require_ids(quads, quad_positions.size(), "measure_features: quad");
  require_finite(input_positions, "measure_features: input");
  require_finite(quad_positions, "measure_features: quad mesh");
  if (!(options.spacing > 0) || !(options.tolerance >= 0) || options.max_samples < 1)
    throw Error(ErrorKind::InvalidArgument,
                "measure_features: need spacing > 0, tolerance >= 0 and max_samples >= 1");
  const double s = unit_scale(std::max(max_abs(quad_positions), max_abs(input_positions)));
  const std::vector<Vec3d> ip = scaled(input_positions, s), qp = scaled(quad_positions, s);
  FeatureQuality r;
  r.edges = static_cast<int>(feature_edges.size());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double total = 0;
  for (const auto& e : feature_edges) total += norm(sub(ip[e[1]], ip[e[0]]));
  r.length = total / s;
  if (!(total > 0)) {
    r.covered_fraction = r.distance_max = r.distance_p99 = nan;
    return r;
  }
  Vec3d lo = ip.empty() ? Vec3d{0, 0, 0} : ip[0], hi = lo;
  for (const Vec3d& p : ip) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double diagonal = norm(sub(hi, lo));
  // The samples: midpoints of equal pieces of each edge, weighted by the piece's length.
  const double step = std::max(options.spacing * diagonal, total / static_cast<double>(options.max_samples));
  std::vector<Vec3d> samples;
  std::vector<double> weight;
  for (const auto& e : feature_edges) {
    const Vec3d a = ip[e[0]], d = sub(ip[e[1]], a);
    const double len = norm(d);
    const auto n = static_cast<std::int64_t>(std::max(1.0, std::ceil(len / step)));
    for (std::int64_t k = 0; k < n; ++k) {
      samples.push_back(add(a, mul(d, (static_cast<double>(k) + 0.5) / static_cast<double>(n))));
      weight.push_back(len / static_cast<double>(n));
    }
  }
  r.samples = samples.size();
  // The quads' edges, once each.
  std::vector<std::array<int, 2>> segments;
  for (const auto& q : quads)
    for (int i = 0; i < 4; ++i) segments.push_back({std::min(q[i], q[(i + 1) % 4]), std::max(q[i], q[(i + 1) % 4])});
  std::sort(segments.begin(), segments.end());
  segments.erase(std::unique(segments.begin(), segments.end()), segments.end());
  if (segments.empty()) {
    r.covered_fraction = 0;
    r.distance_max = r.distance_p99 = kInf;
    return r;
  }
  // A uniform grid over the segments and the samples: cells of about the mean segment length,
  // at most ~4 cells per segment (the cell grows until they fit).
  Vec3d glo = samples[0], ghi = glo;
  double mean = 0;
  auto grow = [&](const Vec3d& p) {
    glo = {std::min(glo.x, p.x), std::min(glo.y, p.y), std::min(glo.z, p.z)};
    ghi = {std::max(ghi.x, p.x), std::max(ghi.y, p.y), std::max(ghi.z, p.z)};
  };
  for (const Vec3d& p : samples) grow(p);
  for (const auto& g : segments) {
    grow(qp[g[0]]);
    grow(qp[g[1]]);
    mean += norm(sub(qp[g[1]], qp[g[0]]));
  }
  mean /= static_cast<double>(segments.size());
  const Vec3d extent = sub(ghi, glo);
  double h = std::max({mean, options.tolerance * diagonal, 1e-300 + 1e-9 * norm(extent)});
  std::array<std::int64_t, 3> dims{};
  const double budget = 4.0 * static_cast<double>(segments.size()) + 64;
  for (int round = 0; round < 200; ++round) {  // bound: h doubles each round
    for (int a = 0; a < 3; ++a) dims[a] = static_cast<std::int64_t>(coordinate(extent, a) / h) + 1;
    if (static_cast<double>(dims[0]) * static_cast<double>(dims[1]) * static_cast<double>(dims[2]) <= budget) break;
    h *= 2;
  }
  auto cell_of = [&](double x, int a) {
    const auto c = static_cast<std::int64_t>((x - coordinate(glo, a)) / h);
    return std::clamp<std::int64_t>(c, 0, dims[a] - 1);
  };
  const std::int64_t cells = dims[0] * dims[1] * dims[2];
  std::vector<std::int64_t> first(static_cast<std::size_t>(cells) + 1, 0);
  std::vector<int> members;
  for (int pass = 0; pass < 2; ++pass) {  // count, then fill (CSR)
    std::vector<std::int64_t> fill(first.begin(), first.end() - 1);
    for (std::size_t g = 0; g < segments.size(); ++g) {
      const Vec3d &a = qp[segments[g][0]], &b = qp[segments[g][1]];
      std::array<std::int64_t, 3> c0{}, c1{};
      for (int k = 0; k < 3; ++k) {
        c0[k] = cell_of(std::min(coordinate(a, k), coordinate(b, k)), k);
        c1[k] = cell_of(std::max(coordinate(a, k), coordinate(b, k)), k);
      }
      for (std::int64_t i = c0[0]; i <= c1[0]; ++i)
        for (std::int64_t j = c0[1]; j <= c1[1]; ++j)
          for (std::int64_t k = c0[2]; k <= c1[2]; ++k) {
            const std::int64_t c = (i * dims[1] + j) * dims[2] + k;
            if (pass == 0) ++first[static_cast<std::size_t>(c) + 1];
            else members[static_cast<std::size_t>(fill[static_cast<std::size_t>(c)]++)] = static_cast<int>(g);
          }
    }
    if (pass == 0) {
      for (std::int64_t c = 0; c < cells; ++c) first[c + 1] += first[c];
      members.assign(static_cast<std::size_t>(first[cells]), 0);
    }
  }
  auto segment_distance2 = [&](const Vec3d& p, int g) {
    const Vec3d &a = qp[segments[g][0]], d = sub(qp[segments[g][1]], a), pa = sub(p, a);
    const double dd = dot(d, d);
    const double t = dd > 0 ? std::clamp(dot(pa, d) / dd, 0.0, 1.0) : 0.0;
    const Vec3d e = sub(pa, mul(d, t));
    return dot(e, e);
  };
  // Nearest segment: shells of cells at Chebyshev index distance r = 0, 1, ... around the sample's
  // cell; after shell r every unseen segment is at least r h away. Bound: r <= max(dims).
  std::vector<double> dist(samples.size());
  const std::int64_t max_r = std::max({dims[0], dims[1], dims[2]});
  parallel::for_each_index(static_cast<std::int64_t>(samples.size()), 256, [&](std::int64_t i) {
    const Vec3d& p = samples[i];
    const std::array<std::int64_t, 3> c{cell_of(p.x, 0), cell_of(p.y, 1), cell_of(p.z, 2)};
    double best = kInf;
    // The shell's cells inside the grid only: over all shells, each cell of the grid once.
    auto lo_of = [&](std::int64_t rr, int a) { return std::max(-rr, -c[a]); };
    auto hi_of = [&](std::int64_t rr, int a) { return std::min(rr, dims[a] - 1 - c[a]); };
    for (std::int64_t rr = 0; rr <= max_r; ++rr) {
      for (std::int64_t di = lo_of(rr, 0); di <= hi_of(rr, 0); ++di)
        for (std::int64_t dj = lo_of(rr, 1); dj <= hi_of(rr, 1); ++dj) {
          const bool side = di == -rr || di == rr || dj == -rr || dj == rr;
          for (std::int64_t dk = lo_of(rr, 2); dk <= hi_of(rr, 2); ++dk) {
            if (!side && dk != -rr && dk != rr) {
              if (dk < rr) dk = rr - 1;  // jump to the far face (the loop's ++ lands on rr)
              continue;
            }
            const std::int64_t x = c[0] + di, y = c[1] + dj, z = c[2] + dk;
            const std::int64_t cell = (x * dims[1] + y) * dims[2] + z;
            for (std::int64_t m = first[cell]; m < first[cell + 1]; ++m)
              best = std::min(best, segment_distance2(p, members[static_cast<std::size_t>(m)]));
          }
        }
      const double reach = static_cast<double>(rr) * h;
      if (best <= reach * reach) break;
    }
    dist[i] = std::sqrt(best) / diagonal;
  });
  double covered = 0, sum = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    sum += weight[i];
    if (dist[i] <= options.tolerance) covered += weight[i];
  }
  r.covered_fraction = covered / sum;
  r.distance_max = *std::max_element(dist.begin(), dist.end());
  r.distance_p99 = weighted_quantiles(dist, weight, {0.99})[0];
  return r;
}

std::string to_json(const FeatureQuality& q) {
  std::string o = "{";
  put_count(o, "edges", q.edges);
  put_count(o, "curves", q.curves);
  put_count(o, "corners", q.corners);
  put_count(o, "short_edges", q.short_edges);
  put_field(o, "length", q.length);
  put_field(o, "covered_fraction", q.covered_fraction);
  put_field(o, "distance_max", q.distance_max);
  put_field(o, "distance_p99", q.distance_p99);
  put_count(o, "samples", static_cast<long long>(q.samples));
  return o + "}";
}

std::string summary_line(const FeatureQuality& q) {
  if (q.edges == 0) return "no features";
  char line[256];
  std::snprintf(line, sizeof line, "features %d curves, %d edges: %.1f %% covered, distance max %.3g %% p99 %.3g %%",
                q.curves, q.edges, 100 * q.covered_fraction, 100 * q.distance_max, 100 * q.distance_p99);
  std::string out = line;
  if (q.short_edges > 0) out += " (" + std::to_string(q.short_edges) + " edges in chains too short to follow)";
  return out;
}

std::string to_json(const IgmQuality& q) {
  std::string o = "{";
  put_count(o, "triangles", q.triangles);
  put_count(o, "degenerate", q.degenerate);
  put_quantiles(o, "conformal", q.conformal);
  put_quantiles(o, "area", q.area);
  put_field(o, "symmetric_dirichlet", q.symmetric_dirichlet);
  return o + "}";
}

std::string to_json(const QuadQuality& q) {
  std::string o = "{";
  put_count(o, "quads", q.quads);
  put_count(o, "vertices", q.vertices);
  put_count(o, "degenerate", q.degenerate);
  put_key(o, "valence");
  std::string valence = "{";
  for (const auto& [k, n] : q.valence) put_count(valence, std::to_string(k).c_str(), n);
  o += valence + "}";
  put_count(o, "irregular_vertices", q.irregular_vertices);
  put_count(o, "max_valence", q.max_valence);
  put_field(o, "sj_min", q.sj_min);
  put_field(o, "sj_p5", q.sj_p5);
  put_field(o, "sj_median", q.sj_median);
  put_field(o, "sj_below_half", q.sj_below_half);
  put_field(o, "sj_nonpositive", q.sj_nonpositive);
  put_field(o, "angle_deviation_median", q.angle_deviation_median);
  put_field(o, "angle_deviation_p95", q.angle_deviation_p95);
  put_field(o, "area_p95_over_p5", q.area_p95_over_p5);
  put_field(o, "area_ratio", q.area_ratio);
  put_field(o, "smallest_half_area", q.smallest_half_area);
  put_key(o, "distance_measured");
  o += q.distance_measured ? "true" : "false";
  const double unmeasured = std::numeric_limits<double>::quiet_NaN();
  put_field(o, "distance_max", q.distance_measured ? q.distance_max : unmeasured);
  put_field(o, "distance_p99", q.distance_measured ? q.distance_p99 : unmeasured);
  put_count(o, "distance_samples_quads", static_cast<long long>(q.distance_samples_quads));
  put_count(o, "distance_samples_input", static_cast<long long>(q.distance_samples_input));
  return o + "}";
}

std::string summary_line(const IgmQuality& igm, const QuadQuality& quads) {
  char distance[64] = "distance not measured";
  if (quads.distance_measured)
    std::snprintf(distance, sizeof distance, "distance max %.3g %%", 100 * quads.distance_max);
  char line[512];
  std::snprintf(line, sizeof line,
                "quads %d (%d irregular vertices, valence <= %d): SJ median %.2f p5 %.2f min %.2f, <0.5 %.1f %%, "
                "<=0 %.1f %%, angle dev median %.1f deg, area/input %.3f, smallest half %.0f %%, %s; IGM "
                "conformal p99 %.3g, area p99 %.3g",
                quads.quads, quads.irregular_vertices, quads.max_valence, quads.sj_median, quads.sj_p5, quads.sj_min, 100 * quads.sj_below_half,
                100 * quads.sj_nonpositive, quads.angle_deviation_median, quads.area_ratio,
                100 * quads.smallest_half_area, distance, igm.conformal.p99, igm.area.p99);
  return line;
}

}  // namespace igm
