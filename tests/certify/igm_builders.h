#pragma once
// Synthetic IGMs for the certifier tests, built here (the certifier tests link only igm::certify).
#include <array>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "certify/certify.h"

namespace certify_test {

using igm::certify::IgmInput;
using Uv = std::array<mpq_class, 2>;

inline void add_tri(IgmInput& in, int a, int b, int c, const Uv& ua, const Uv& ub, const Uv& uc) {
  in.faces.push_back({a, b, c});
  in.corner_uv.push_back(ua);
  in.corner_uv.push_back(ub);
  in.corner_uv.push_back(uc);
}

inline Uv uv(const mpq_class& x, const mpq_class& y) { return {x, y}; }

/// n x n torus: vertex (i, j) has id i + n j; the chart is [0, n]^2 unwrapped, so the corners at
/// the wrap carry coordinate n and the seams are translations by n. 2 n^2 triangles, all k = 4.
/// Face of cell (i, j): 2 (i + n j) (lower) and 2 (i + n j) + 1 (upper).
inline IgmInput torus(int n) {
  IgmInput in;
  in.num_vertices = n * n;
  auto id = [n](int i, int j) { return (i % n) + n * (j % n); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      add_tri(in, id(i, j), id(i + 1, j), id(i + 1, j + 1), uv(i, j), uv(i + 1, j), uv(i + 1, j + 1));
      add_tri(in, id(i, j), id(i + 1, j + 1), id(i, j + 1), uv(i, j), uv(i + 1, j + 1), uv(i, j + 1));
    }
  return in;
}

/// Faces of the cells [i0, i1) x [j0, j1) of torus(n).
inline std::vector<int> block_faces(int n, int i0, int i1, int j0, int j1) {
  std::vector<int> f;
  for (int j = j0; j < j1; ++j)
    for (int i = i0; i < i1; ++i) {
      f.push_back(2 * (i + n * j));
      f.push_back(2 * (i + n * j) + 1);
    }
  return f;
}

/// Applies the map uv -> (a x + b y + tx, c x + d y + ty) to the corners of the given faces.
inline void map_faces(IgmInput& in, const std::vector<int>& faces, int a, int b, int c, int d,
                      const mpq_class& tx, const mpq_class& ty) {
  for (int f : faces)
    for (int k = 0; k < 3; ++k) {
      Uv& p = in.corner_uv[3 * f + k];
      Uv q{a * p[0] + b * p[1] + tx, c * p[0] + d * p[1] + ty};
      p = q;
    }
}

/// Torus with two re-parametrised 2x2 blocks: one chart rotated by +90 degrees, one by -90
/// degrees (plus integer shifts): seams with k = 1 and k = 3, still a valid IGM. Needs n >= 7.
inline IgmInput rotated_chart_torus(int n) {
  IgmInput in = torus(n);
  map_faces(in, block_faces(n, 1, 3, 1, 3), 0, -1, 1, 0, 5, -2);   // R
  map_faces(in, block_faces(n, 4, 6, 4, 6), 0, 1, -1, 0, -3, 7);   // R^3
  return in;
}

/// Surface of the cube [0, m]^3 as m x m quads per side, every quad its own unit-square chart,
/// each quad split into two triangles: 8 cones of index 3 at the corners. `sides` keeps some of
/// the six sides only (bit 2a + (s == m) for the side x_a = s): an open surface.
inline IgmInput cube(int m, int sides = 63) {
  IgmInput in;
  std::map<std::array<int, 3>, int> ids;
  auto id = [&](std::array<int, 3> p) {
    auto it = ids.find(p);
    if (it != ids.end()) return it->second;
    int v = static_cast<int>(ids.size());
    ids.emplace(p, v);
    return v;
  };
  const Uv s00 = uv(0, 0), s10 = uv(1, 0), s11 = uv(1, 1), s01 = uv(0, 1);
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (int side : {0, m}) {
      if (((sides >> (2 * a + (side == m))) & 1) == 0) continue;
      for (int u = 0; u < m; ++u)
        for (int w = 0; w < m; ++w) {
          std::array<std::array<int, 3>, 4> q;
          const int du[4] = {0, 1, 1, 0}, dw[4] = {0, 0, 1, 1};
          for (int k = 0; k < 4; ++k) {
            q[k][a] = side;
            q[k][b] = u + du[k];
            q[k][c] = w + dw[k];
          }
          if (side == 0) std::swap(q[1], q[3]);  // outward orientation
          int v0 = id(q[0]), v1 = id(q[1]), v2 = id(q[2]), v3 = id(q[3]);
          add_tri(in, v0, v1, v2, s00, s10, s11);
          add_tri(in, v0, v2, v3, s00, s11, s01);
        }
    }
  }
  in.num_vertices = static_cast<std::int64_t>(ids.size());
  return in;
}

/// Pillow: two m x m grids glued along their boundary. Front vertex (i, j) has uv (i + sx, j + sy),
/// back (-i + sx, j + sy). Cones of index 2 at the four corners (on integer points iff 2 sx, 2 sy
/// ... are integers and sx, sy themselves are). Corner vertex ids: 0, m, m(m+1), m(m+1)+m.
inline IgmInput pillow(int m, const mpq_class& sx = 0, const mpq_class& sy = 0) {
  IgmInput in;
  auto front = [m](int i, int j) { return i + (m + 1) * j; };
  const int base = (m + 1) * (m + 1);
  auto back = [&](int i, int j) {
    if (i == 0 || j == 0 || i == m || j == m) return front(i, j);
    return base + (i - 1) + (m - 1) * (j - 1);
  };
  auto fu = [&](int i, int j) { return uv(i + sx, j + sy); };
  auto bu = [&](int i, int j) { return uv(-i + sx, j + sy); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      // front split along the anti-diagonal, back along the main diagonal: no edge twice
      add_tri(in, front(i, j), front(i + 1, j), front(i, j + 1), fu(i, j), fu(i + 1, j), fu(i, j + 1));
      add_tri(in, front(i + 1, j), front(i + 1, j + 1), front(i, j + 1), fu(i + 1, j), fu(i + 1, j + 1), fu(i, j + 1));
      add_tri(in, back(i, j), back(i + 1, j + 1), back(i + 1, j), bu(i, j), bu(i + 1, j + 1), bu(i + 1, j));
      add_tri(in, back(i, j), back(i, j + 1), back(i + 1, j + 1), bu(i, j), bu(i, j + 1), bu(i + 1, j + 1));
    }
  in.num_vertices = base + (m - 1) * (m - 1);
  return in;
}

/// OBJ text of an in-memory IGM: one vt per corner, written as exact p/q (or decimals when
/// `decimal` and every value has a finite decimal expansion with <= 12 digits after the point).
inline std::string to_obj(const IgmInput& in, bool decimal = false) {
  std::ostringstream o;
  o << "# test IGM\n";
  for (std::int64_t v = 0; v < in.num_vertices; ++v) o << "v " << v << " 0 0\n";
  auto num = [&](const mpq_class& q) {
    if (!decimal) return q.get_str();
    // q * 10^12 must be an integer
    mpz_class scale = 1000000000000;
    mpq_class s = q * scale;
    s.canonicalize();
    mpz_class n = s.get_num();
    std::string sign = n < 0 ? "-" : "";
    n = abs(n);
    mpz_class ip = n / scale, fp = n % scale;
    std::string f = fp.get_str();
    f = std::string(12 - f.size(), '0') + f;
    return sign + ip.get_str() + "." + f;
  };
  for (const auto& p : in.corner_uv) o << "vt " << num(p[0]) << " " << num(p[1]) << "\n";
  for (std::size_t f = 0; f < in.faces.size(); ++f)
    o << "f " << in.faces[f][0] + 1 << "/" << 3 * f + 1 << " " << in.faces[f][1] + 1 << "/" << 3 * f + 2 << " "
      << in.faces[f][2] + 1 << "/" << 3 * f + 3 << "\n";
  return o.str();
}

inline bool has_edge_witness(const igm::certify::CheckResult& c, std::int64_t u, std::int64_t v) {
  if (u > v) std::swap(u, v);
  for (const auto& w : c.witnesses)
    if (w.kind == "edge" && w.ids.size() == 2 && w.ids[0] == u && w.ids[1] == v) return true;
  return false;
}

/// The witness of `kind` whose first id is `id`, or nullptr.
inline const igm::certify::Witness* find_witness(const igm::certify::CheckResult& c,
                                                 const std::string& kind, std::int64_t id) {
  for (const auto& w : c.witnesses)
    if (w.kind == kind && !w.ids.empty() && w.ids[0] == id) return &w;
  return nullptr;
}

inline bool has_witness(const igm::certify::CheckResult& c, const std::string& kind, std::int64_t id) {
  return find_witness(c, kind, id) != nullptr;
}

/// The named value of a witness, or "<absent>".
inline std::string value(const igm::certify::Witness& w, const std::string& key) {
  for (const auto& [k, v] : w.values)
    if (k == key) return v;
  return "<absent>";
}

/// The check with this id; the test stops when it is missing.
inline const igm::certify::CheckResult& chk(const igm::certify::Report& r, int id) {
  const igm::certify::CheckResult* c = r.check(id);
  REQUIRE(c != nullptr);
  return *c;
}

}  // namespace certify_test
