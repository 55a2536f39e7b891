#pragma once
// Small closed surfaces with known cross fields, shared by the field tests: a subdivided cube
// (8 valence-3 cones at its corners) and a torus of revolution (no cone).
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "igm/core/error.h"
#include "igm/exact/predicates.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/trimesh.h"
#include "igm/mesh/validate_surfaces.h"

namespace igm_test {

struct Surface {
  igm::TriMesh mesh;
  std::vector<igm::Vec3d> positions;
};

inline Surface from(const std::vector<igm::Vec3d>& positions, const std::vector<std::array<int, 3>>& tris, bool open = false) {
  return {igm::TriMesh::from_triangles(static_cast<int>(positions.size()), tris, open), positions};
}

// A surface component (mesh/validate_surfaces.h) as a Surface: its mesh open where it has loops.
inline Surface surface_of(const igm::SurfaceComponent& c) {
  return {igm::TriMesh::from_triangles(static_cast<int>(c.positions.size()), c.triangles, !c.boundary_loops.empty()),
          c.positions};
}

// A generated surface (mesh/generate.h) of one component: genus, about `faces` faces, boundary
// loops, seed. Throws if the generator gave several components (it never does).
inline Surface generated(int genus, std::int64_t faces, int boundaries, std::uint64_t seed) {
  igm::GenerateOptions o;
  o.genus = genus;
  o.faces = faces;
  o.boundaries = boundaries;
  o.seed = seed;
  const igm::SurfaceSet set = igm::validate_surfaces(igm::generate_mesh(o));
  if (set.components.size() != 1) throw igm::Error(igm::ErrorKind::Internal, "generated: not one component");
  return surface_of(set.components[0]);
}

// A cube [-1, 1]^3 with every face cut into n x n squares, each split along a diagonal whose
// direction alternates (no symmetry of the triangulation helps); shared vertices.
inline Surface subdivided_cube(int n) {
  std::vector<igm::Vec3d> pos;
  std::vector<std::array<int, 3>> tris;
  std::map<std::array<long, 3>, int> id;
  auto vertex = [&](const igm::Vec3d& p) {
    const std::array<long, 3> key{std::lround(p.x * n * 2), std::lround(p.y * n * 2), std::lround(p.z * n * 2)};
    auto it = id.find(key);
    if (it != id.end()) return it->second;
    id[key] = static_cast<int>(pos.size());
    pos.push_back(p);
    return static_cast<int>(pos.size()) - 1;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1}) {
      // (u, v, normal) with u x v = normal (outward).
      auto point = [&](double a, double b) {
        igm::Vec3d p;
        double c[3];
        c[axis] = side;
        c[(axis + 1) % 3] = side > 0 ? a : b;
        c[(axis + 2) % 3] = side > 0 ? b : a;
        p = {c[0], c[1], c[2]};
        return p;
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const double a0 = -1 + 2.0 * i / n, a1 = -1 + 2.0 * (i + 1) / n;
          const double b0 = -1 + 2.0 * j / n, b1 = -1 + 2.0 * (j + 1) / n;
          const int v00 = vertex(point(a0, b0)), v10 = vertex(point(a1, b0)), v11 = vertex(point(a1, b1)),
                    v01 = vertex(point(a0, b1));
          if ((i + j) % 2 == 0) {
            tris.push_back({v00, v10, v11});
            tris.push_back({v00, v11, v01});
          } else {
            tris.push_back({v00, v10, v01});
            tris.push_back({v10, v11, v01});
          }
        }
    }
  return from(pos, tris);
}

// A torus of revolution (radii R > r) on an nu x nv grid, diagonals alternating.
inline Surface torus(double R, double r, int nu, int nv) {
  std::vector<igm::Vec3d> pos;
  std::vector<std::array<int, 3>> tris;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      pos.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      if ((i + j) % 2 == 0) {
        tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        tris.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        tris.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return from(pos, tris);
}

// A pencil: a cylinder of radius 1 and height 4 closed by a flat disk below and a cone of height
// `tip` above; n vertices per ring, m rings on each of the three parts. With tip = 3.5 the apex
// angles sum to about 98 degrees: the field turns three quarters around it (a cone of valence 1
// before the cleanup splits it).
inline Surface pencil(int n, int m, double tip) {
  std::vector<std::vector<igm::Vec3d>> rings{{{0, 0, 4 + tip}}};
  auto ring = [&](double r, double z) {
    std::vector<igm::Vec3d> ps;
    for (int u = 0; u < n; ++u)
      ps.push_back({r * std::cos(2 * std::numbers::pi * u / n), r * std::sin(2 * std::numbers::pi * u / n), z});
    rings.push_back(ps);
  };
  for (int k = 1; k <= m; ++k) ring(double(k) / m, 4 + tip * (1 - double(k) / m));
  for (int k = 1; k <= m; ++k) ring(1, 4 - 4.0 * k / m);
  for (int k = m - 1; k >= 1; --k) ring(double(k) / m, 0);
  rings.push_back({{0, 0, 0}});
  std::vector<igm::Vec3d> pos;
  std::vector<std::vector<int>> ids;
  for (const auto& r : rings) {
    ids.emplace_back();
    for (const auto& q : r) {
      ids.back().push_back(static_cast<int>(pos.size()));
      pos.push_back(q);
    }
  }
  std::vector<std::array<int, 3>> tris;
  for (std::size_t k = 0; k + 1 < ids.size(); ++k) {
    const auto &a = ids[k], &b = ids[k + 1];
    for (int u = 0; u < n; ++u) {
      const int w = (u + 1) % n;
      if (a.size() == 1) {
        tris.push_back({a[0], b[u], b[w]});
      } else if (b.size() == 1) {
        tris.push_back({a[u], b[0], a[w]});
      } else {
        tris.push_back({a[u], b[u], b[w]});
        tris.push_back({a[u], b[w], a[w]});
      }
    }
  }
  return from(pos, tris);
}

}  // namespace igm_test
