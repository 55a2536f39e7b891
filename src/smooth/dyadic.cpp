#include "igm/smooth/dyadic.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "../core/parallel.h"

namespace igm {

namespace {

constexpr double kTwo51 = 2251799813685248.0;  // 2^51
constexpr std::int64_t kChunk = 4096;           // faces per parallel chunk (core/parallel.h)

// The integer as a double when |z| < 2^51, else nullopt.
std::optional<double> small_integer(const Integer& z) {
  if (mpz_sizeinbase(z.get_mpz_t(), 2) > 51) return std::nullopt;
  return z.get_d();  // exact
}

// x rounded to the nearest multiple of 2^exponent (halves up), as a double: exact for
// |result| < 2^(exponent + 53).
double round_exact(const Rational& x, int exponent) {
  // floor(x 2^-exponent + 1/2) = floor((2 num 2^-exponent + den) / (2 den))
  Integer n = x.get_num(), d = x.get_den();
  mpz_mul_2exp(n.get_mpz_t(), n.get_mpz_t(), static_cast<mp_bitcnt_t>(1 - exponent));
  n += d;
  d *= 2;
  Integer m;
  mpz_fdiv_q(m.get_mpz_t(), n.get_mpz_t(), d.get_mpz_t());
  return std::ldexp(m.get_d(), exponent);
}

}  // namespace

Vec2d apply(const GridMotionD& m, const Vec2d& p) {
  switch (m.k & 3) {
    case 0:
      return {p.x + m.tx, p.y + m.ty};
    case 1:
      return {-p.y + m.tx, p.x + m.ty};
    case 2:
      return {-p.x + m.tx, -p.y + m.ty};
    default:
      return {p.y + m.tx, -p.x + m.ty};
  }
}

std::optional<GridMap> round_to_grid(const SeamlessStructure& s) {
  GridMap map;
  const int nh = s.mesh.num_halfedges(), nv = s.num_vertices();
  map.corner_motion.resize(nh);
  double tmax = 0;
  for (int c = 0; c < nh; ++c) {
    const GridMotion& m = s.corner_motion[c];
    const auto tx = small_integer(m.tx), ty = small_integer(m.ty);
    if (!tx || !ty) return std::nullopt;
    map.corner_motion[c] = {m.k, *tx, *ty};
    tmax = std::max({tmax, std::abs(*tx), std::abs(*ty)});
  }
  double xmax = 1;
  for (const Point2q& p : s.vertex_uv)
    xmax = std::max({xmax, std::abs(approximate(p.x)), std::abs(approximate(p.y))});
  if (xmax >= kTwo51 / 8) return std::nullopt;
  double bound = 8;
  while (bound < 8 * xmax) bound *= 2;  // at most 48 doublings
  // bound <= 2^51 and tmax < 2^51: the sum is exact; 2^e > bound + tmax with e = ilogb + 1.
  const int e = std::ilogb(bound + tmax) + 1;
  if (e > 53) return std::nullopt;
  map.grid = {e - 53, bound};
  map.vertex_uv.resize(nv);
  for (int v = 0; v < nv; ++v)
    map.vertex_uv[v] = {round_exact(s.vertex_uv[v].x, map.grid.exponent),
                        round_exact(s.vertex_uv[v].y, map.grid.exponent)};
  return map;
}

std::optional<double> round_to_grid(double x, const DyadicGrid& grid) {
  const double r = std::ldexp(std::nearbyint(std::ldexp(x, -grid.exponent)), grid.exponent);
  if (!(std::abs(r) <= grid.bound)) return std::nullopt;  // also NaN and inf
  return r;
}

void grid_corners(const SeamlessStructure& s, const GridMap& map,
                  std::vector<std::array<Vec2d, 3>>& corners) {
  grid_corners(s, map, map.vertex_uv, corners);
}

void grid_corners(const SeamlessStructure& s, const GridMap& map, const std::vector<Vec2d>& vertex_uv,
                  std::vector<std::array<Vec2d, 3>>& corners) {
  const int nf = s.mesh.num_faces();
  corners.resize(nf);
  parallel::for_each_index(nf, kChunk, [&](std::int64_t f) {
    for (int i = 0; i < 3; ++i) {
      const int c = static_cast<int>(3 * f + i);
      corners[f][i] = apply(map.corner_motion[c], vertex_uv[s.mesh.origin(c)]);
    }
  });
}

MapCheck check_map(const SeamlessStructure& s, const std::vector<std::array<Vec2d, 3>>& corners) {
  MapCheck r;
  // (count, first) per chunk, combined in order: the first is the least face id
  const auto bad = parallel::reduce_chunks<std::pair<int, int>>(
      static_cast<std::int64_t>(corners.size()), kChunk, {0, -1},
      [&](std::int64_t b, std::int64_t e) {
        std::pair<int, int> c{0, -1};
        for (std::int64_t f = b; f < e; ++f)
          if (orient2d(corners[f][0], corners[f][1], corners[f][2]) != Sign::Positive && c.first++ == 0)
            c.second = static_cast<int>(f);
        return c;
      },
      [](std::pair<int, int> a, std::pair<int, int> b) {
        return std::pair<int, int>{a.first + b.first, a.second >= 0 ? a.second : b.second};
      });
  r.nonpositive = bad.first;
  r.first_nonpositive = bad.second;
  if (r.nonpositive > 0) return r;
  // Boundary edges, then held interior edges, on their isolines: exact comparisons of doubles.
  for (const std::vector<BoundaryIsoline>* edges : {&s.boundary_edges, &s.isoline_edges})
    for (const BoundaryIsoline& e : *edges) {
      const int f = e.halfedge / 3;
      const std::optional<double> value = small_integer(e.value);  // no grid holds a larger one
      const Vec2d &a = corners[f][e.halfedge % 3], &b = corners[f][TriMesh::next(e.halfedge) % 3];
      if (!value || (e.axis == 0 ? a.x : a.y) != *value || (e.axis == 0 ? b.x : b.y) != *value) {
        if (r.off_isoline++ == 0) r.first_off_isoline = e.halfedge;
      }
    }
  if (r.off_isoline > 0) return r;
  const std::vector<int> angles = angle_indices(s.mesh, corners);
  for (std::size_t v = 0; v < angles.size(); ++v)
    if (angles[v] != s.angle_index[v]) {
      if (r.angles_changed++ == 0) r.first_angle_changed = static_cast<int>(v);
    }
  return r;
}

std::vector<std::array<Point2q, 3>> to_exact(const std::vector<std::array<Vec2d, 3>>& corners) {
  std::vector<std::array<Point2q, 3>> out(corners.size());
  parallel::for_each_index(static_cast<std::int64_t>(corners.size()), kChunk, [&](std::int64_t f) {
    for (int i = 0; i < 3; ++i) out[f][i] = to_point2q(corners[f][i]);
  });
  return out;
}

std::size_t max_uv_bits(const std::vector<std::array<Point2q, 3>>& corner_uv) {
  return parallel::reduce_chunks<std::size_t>(
      static_cast<std::int64_t>(corner_uv.size()), kChunk, 0,
      [&](std::int64_t b, std::int64_t e) {
        std::size_t bits = 0;
        for (std::int64_t f = b; f < e; ++f)
          for (const Point2q& p : corner_uv[f]) bits = std::max({bits, bit_size(p.x), bit_size(p.y)});
        return bits;
      },
      [](std::size_t a, std::size_t b) { return std::max(a, b); });
}

DyadicResult round_to_dyadic(const IgmMesh& igm) {
  return round_to_dyadic(igm, seamless_structure(igm));
}

DyadicStats place_on_grid(const SeamlessStructure& s, std::optional<GridMap>& map,
                          std::vector<std::array<Vec2d, 3>>& corners) {
  DyadicStats st;
  map = round_to_grid(s);
  if (!map) {
    st.reason = "no double grid holds the map: a translation of 2^51 or a vertex UV of 2^48 or more";
    return st;
  }
  st.grid_exponent = map->grid.exponent;
  grid_corners(s, *map, corners);
  const MapCheck check = check_map(s, corners);
  st.nonpositive = check.nonpositive;
  st.first_nonpositive = check.first_nonpositive;
  st.off_isoline = check.off_isoline;
  st.angles_changed = check.angles_changed;
  const std::string grid = "rounding to the grid of spacing 2^" + std::to_string(map->grid.exponent);
  if (check.valid()) {
    st.on_grid = true;
  } else if (check.nonpositive > 0) {
    st.reason = grid + " makes " + std::to_string(check.nonpositive) +
                " triangles non-positive (the first: face " + std::to_string(check.first_nonpositive) + ")";
  } else if (check.off_isoline > 0) {
    st.reason = grid + " moves " + std::to_string(check.off_isoline) +
                " boundary edges off their isolines (the first: half-edge " +
                std::to_string(check.first_off_isoline) + ")";
  } else {
    st.reason = grid + " changes the angle of " + std::to_string(check.angles_changed) +
                " vertices (the first: vertex " + std::to_string(check.first_angle_changed) + ")";
  }
  return st;
}

DyadicResult round_to_dyadic(const IgmMesh& igm, const SeamlessStructure& s) {
  DyadicResult r;
  std::optional<GridMap> map;
  std::vector<std::array<Vec2d, 3>> corners;
  r.stats = place_on_grid(s, map, corners);
  r.corner_uv = r.stats.on_grid ? to_exact(corners) : igm.corner_uv;
  r.stats.max_uv_bits = max_uv_bits(r.corner_uv);
  return r;
}

}  // namespace igm
