#include "igm/igm/quad_charts.h"

#include <algorithm>
#include <string>
#include <unordered_set>

#include "igm/core/error.h"

namespace igm {

namespace {

// uv = U0 + A (x - k0): the affine map of a template region.
struct Affine {
  Point2q k0, u0;
  Rational ax, bx, ay, by;
  Point2q operator()(const Point2q& x) const {
    const Rational dx = x.x - k0.x, dy = x.y - k0.y;
    Point2q r{Rational(u0.x + ax * dx), Rational(u0.y + ay * dx)};
    r.x += bx * dy;
    r.y += by * dy;
    return r;
  }
};

Affine region_map(const QuadTemplate& t, const TemplateRegion& r) {
  const Point2q &k0 = t.points[r.corners[0]], &k1 = t.points[r.corners[1]], &k2 = t.points[r.corners[2]];
  const Rational area = cross(k0, k1, k2);
  const Rational a1 = (k2.y - k0.y) / area, b1 = -(k2.x - k0.x) / area;  // lambda1 = a1 dx + b1 dy
  const Rational a2 = -(k1.y - k0.y) / area, b2 = (k1.x - k0.x) / area;  // lambda2 = a2 dx + b2 dy
  const Rational e1x = r.uv[1].x - r.uv[0].x, e1y = r.uv[1].y - r.uv[0].y;
  const Rational e2x = r.uv[2].x - r.uv[0].x, e2y = r.uv[2].y - r.uv[0].y;
  Affine m;
  m.k0 = k0;
  m.u0 = r.uv[0];
  m.ax = a1 * e1x + a2 * e2x;
  m.bx = b1 * e1x + b2 * e2x;
  m.ay = a1 * e1y + a2 * e2y;
  m.by = b1 * e1y + b2 * e2y;
  return m;
}

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

}  // namespace

QuadCharts compute_quad_charts(const QuadTemplate& t, const OverlayResult& ov, const QuadChartsOptions& options) {
  const auto regions = template_regions(t);
  const auto segs = template_segments(t);
  const auto& P = ov.mesh.positions;
  const auto& F = ov.mesh.triangles;
  const int nf = static_cast<int>(F.size());
  if (ov.chains.size() != segs.size())
    throw Error(ErrorKind::InvalidArgument, "quad charts: the overlay was not made with this template's segments");
  for (std::size_t s = 0; s < segs.size(); ++s) {
    const auto& c = ov.chains[s];
    if (c.size() < 2 || !same_point(P[c.front()], t.points[segs[s].a]) || !same_point(P[c.back()], t.points[segs[s].b]))
      throw Error(ErrorKind::InvalidArgument, "quad charts: chain " + std::to_string(s) + " does not match template segment",
                  {static_cast<std::int64_t>(s)});
  }
  const PlanarAdjacency adj = PlanarAdjacency::build(static_cast<int>(P.size()), F);
  auto directed = [&](int a, int b) {  // triangle with directed edge a->b, or -1; O(deg a)
    for (int k = adj.star_begin[a]; k < adj.star_begin[a + 1]; ++k) {
      const auto& T = F[adj.star[k]];
      for (int i = 0; i < 3; ++i)
        if (T[i] == a && T[(i + 1) % 3] == b) return adj.star[k];
    }
    return -1;
  };
  QuadCharts ch;
  ch.region.assign(nf, -1);
  std::unordered_set<std::uint64_t> barrier;
  std::vector<int> queue;
  auto seed = [&](int tri, int region, int s) {
    if (tri < 0) {
      if (region >= 0) throw Error(ErrorKind::Internal, "quad charts: a chain edge has no triangle on an inner side", {s});
      return;
    }
    if (region < 0) throw Error(ErrorKind::Internal, "quad charts: a triangle lies outside the polygon", {tri});
    if (ch.region[tri] >= 0 && ch.region[tri] != region)
      throw Error(ErrorKind::Internal, "quad charts: triangle " + std::to_string(tri) + " touches two template regions", {tri});
    if (ch.region[tri] < 0) queue.push_back(tri);
    ch.region[tri] = region;
  };
  for (std::size_t s = 0; s < segs.size(); ++s) {
    const auto& c = ov.chains[s];
    for (std::size_t k = 0; k + 1 < c.size(); ++k) {
      barrier.insert(edge_key(c[k], c[k + 1]));
      seed(directed(c[k], c[k + 1]), segs[s].left, static_cast<int>(s));
      seed(directed(c[k + 1], c[k]), segs[s].right, static_cast<int>(s));
    }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {  // each triangle enters once: bounded by F
    const int tri = queue[head];
    for (int i = 0; i < 3; ++i) {
      const int n = adj.neighbor[tri][i];
      if (n < 0 || barrier.count(edge_key(F[tri][i], F[tri][(i + 1) % 3]))) continue;
      if (ch.region[n] < 0) {
        ch.region[n] = ch.region[tri];
        queue.push_back(n);
      } else if (ch.region[n] != ch.region[tri]) {
        throw Error(ErrorKind::Internal, "quad charts: template regions leak into each other at triangle " + std::to_string(n),
                    {n});
      }
    }
  }
  std::vector<Affine> maps;
  maps.reserve(regions.size());
  for (const auto& r : regions) maps.push_back(region_map(t, r));
  ch.quad.resize(nf);
  ch.uv.resize(nf);
  // Each vertex is mapped once per region around it (a vertex has ~6 corners, seams 2-3 regions).
  std::vector<std::vector<std::pair<int, int>>> done(P.size());  // vertex -> (region, triangle*3+corner)
  for (int tri = 0; tri < nf; ++tri) {
    const int r = ch.region[tri];
    if (r < 0) throw Error(ErrorKind::Internal, "quad charts: triangle " + std::to_string(tri) + " got no region", {tri});
    ch.quad[tri] = regions[r].quad;
    for (int i = 0; i < 3; ++i) {
      auto& d = done[F[tri][i]];
      auto it = std::find_if(d.begin(), d.end(), [&](const auto& x) { return x.first == r; });
      if (it != d.end()) {
        ch.uv[tri][i] = ch.uv[it->second / 3][it->second % 3];
        continue;
      }
      ch.uv[tri][i] = maps[r](P[F[tri][i]]);
      d.emplace_back(r, 3 * tri + i);
      ch.max_uv_bits = std::max({ch.max_uv_bits, bit_size(ch.uv[tri][i].x), bit_size(ch.uv[tri][i].y)});
    }
    if (options.check) {
      if (orient2d(ch.uv[tri][0], ch.uv[tri][1], ch.uv[tri][2]) != Sign::Positive)
        throw Error(ErrorKind::Internal, "quad charts: UV triangle " + std::to_string(tri) + " is not positive", {tri});
      for (const auto& u : ch.uv[tri])
        if (sign(u.x) == Sign::Negative || u.x > 1 || sign(u.y) == Sign::Negative || u.y > 1)
          throw Error(ErrorKind::Internal, "quad charts: UV of triangle " + std::to_string(tri) + " leaves the unit square",
                      {tri});
    }
  }
  return ch;
}

}  // namespace igm
