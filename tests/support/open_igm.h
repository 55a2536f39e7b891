#pragma once
// IGMs of surfaces with boundary and of several components for the igm-side tests (smoothing,
// extraction): the certifier tests' exact builders (tests/certify/boundary_builders.h: grid disks,
// cylinders, L-shapes, slit squares, a pillow with a hole, disjoint unions) given 3D positions,
// and valid perturbations of their UVs (every free vertex moved, every straight boundary vertex
// slid along its isoline) so that a smoother starts from a distorted map.
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "../certify/boundary_builders.h"
#include "igm/output/igm_mesh.h"
#include "igm/smooth/seamless.h"

namespace igm_test {

/// The certifier's options for an IGM with boundary and several components.
inline igm::certify::Options open_options() {
  igm::certify::Options o;
  o.allow_boundary = true;
  o.allow_components = true;
  return o;
}

/// The exact UVs of a builder's IGM, three per face.
inline std::vector<std::array<igm::Point2q, 3>> exact_uv(const igm::certify::IgmInput& in) {
  std::vector<std::array<igm::Point2q, 3>> uv(in.faces.size());
  for (std::size_t f = 0; f < in.faces.size(); ++f)
    for (int i = 0; i < 3; ++i) uv[f][i] = {in.corner_uv[3 * f + i][0], in.corner_uv[3 * f + i][1]};
  return uv;
}

/// A builder's IGM as an IgmMesh; vertex v sits at lift(v, the UV of v's first corner in face
/// order). Lift: (int, const igm::Point2q&) -> igm::Vec3d.
template <class Lift>
igm::IgmMesh lifted(const igm::certify::IgmInput& in, Lift lift) {
  igm::IgmMesh m;
  m.triangles = in.faces;
  m.corner_uv = exact_uv(in);
  const int nv = static_cast<int>(in.num_vertices);
  std::vector<int> first(nv, -1);
  for (std::size_t c = 0; c < 3 * in.faces.size(); ++c)
    if (first[in.faces[c / 3][c % 3]] < 0) first[in.faces[c / 3][c % 3]] = static_cast<int>(c);
  for (int v = 0; v < nv; ++v)
    m.positions.push_back(lift(v, m.corner_uv[first[v] / 3][first[v] % 3]));
  return m;
}

/// A bumped height field over the UV plane: (u, v, 0.7 sin(u) cos(0.8 v)).
inline igm::Vec3d bumped(int, const igm::Point2q& uv) {
  const double u = igm::to_double(uv.x), v = igm::to_double(uv.y);
  return {u, v, 0.7 * std::sin(u) * std::cos(0.8 * v)};
}

/// certify_test::cylinder(n, m) on a bulging tube: u once around (period n), v along the axis.
inline igm::IgmMesh tube(int n, int m) {
  return lifted(certify_test::cylinder(n, m).igm, [n](int, const igm::Point2q& uv) {
    const double a = 2 * std::numbers::pi * igm::to_double(uv.x) / n;
    const double h = igm::to_double(uv.y);
    const double r = 0.8 * n / (2 * std::numbers::pi) * (1 + 0.3 * std::sin(1.7 * h));
    return igm::Vec3d{r * std::cos(a), r * std::sin(a), 1.2 * h};
  });
}

/// certify_test::pillow_with_hole(m, ci, cj) inflated: the front sheet (UV (i, j)) at height
/// +b, the back one (UV (-i, j)) at -b, b = m/3 sin(pi |u| / m) sin(pi v / m), 0 on the seam.
inline igm::IgmMesh inflated_pillow_with_hole(int m, int ci, int cj) {
  return lifted(certify_test::pillow_with_hole(m, ci, cj), [m](int, const igm::Point2q& uv) {
    const double u = igm::to_double(uv.x), v = igm::to_double(uv.y);
    const double pi = std::numbers::pi;
    const double b = m / 3.0 * std::sin(pi * std::abs(u) / m) * std::sin(pi * v / m);
    return igm::Vec3d{std::abs(u), v, u >= 0 ? b : -b};
  });
}

/// certify_test::torus(n) on a ring torus, translated by `dx` along x.
inline igm::Vec3d ring(int n, double dx, const igm::Point2q& uv) {
  const double turn = 2 * std::numbers::pi / n;
  const double a = turn * igm::to_double(uv.x), b = turn * igm::to_double(uv.y);
  const double R = n / 2.0, r = n / 5.0;
  return {dx + (R + r * std::cos(b)) * std::cos(a), (R + r * std::cos(b)) * std::sin(a),
          r * std::sin(b)};
}

/// Two components: the bumped square disk [0, n]^2 and the ring torus(t) (vertex ids after the
/// disk's), ten units apart.
inline igm::IgmMesh disk_and_torus(int n, int t) {
  const igm::certify::IgmInput disk = certify_test::square_disk(n).igm;
  const int first_torus = static_cast<int>(disk.num_vertices);
  return lifted(certify_test::disjoint_union(disk, certify_test::torus(t)),
                [=](int v, const igm::Point2q& uv) {
                  return v < first_torus ? bumped(v, uv) : ring(t, 10.0 + n, uv);
                });
}

/// `igm` with every free vertex (seamless.h) moved by up to amount/64 in both coordinates and
/// every sliding one along its isoline, pseudo-randomly (seed), exactly, through the seamless
/// structure (every corner follows its vertex). A move that would make a triangle of the vertex
/// non-positive (exact orient2d) is halved, at most 6 times, then skipped. Cones and boundary
/// corners stay. The result has the input's structure (tests certify it).
inline igm::IgmMesh perturbed(const igm::IgmMesh& igm, int amount, std::uint32_t seed) {
  using igm::Point2q;
  using igm::Rational;
  const igm::SeamlessStructure s = igm::seamless_structure(igm);
  const igm::TriMesh& mesh = s.mesh;
  const int nv = s.num_vertices(), nh = mesh.num_halfedges();
  std::vector<std::vector<int>> corners(nv);
  for (int c = 0; c < nh; ++c) corners[mesh.origin(c)].push_back(c);
  std::vector<Point2q> x = s.vertex_uv;
  auto corner = [&](int c) { return igm::apply(s.corner_motion[c], x[mesh.origin(c)]); };
  auto star_positive = [&](int v) {
    for (int c : corners[v]) {
      const int f = c / 3;
      if (igm::orient2d(corner(3 * f), corner(3 * f + 1), corner(3 * f + 2)) !=
          igm::Sign::Positive)
        return false;
    }
    return true;
  };
  std::uint32_t state = seed;
  auto next = [&state, amount] {  // in -amount .. amount
    state = state * 1664525u + 1013904223u;
    return static_cast<int>((state >> 8) % static_cast<std::uint32_t>(2 * amount + 1)) - amount;
  };
  for (int v = 0; v < nv; ++v) {
    if (s.is_cone(v)) continue;
    Rational dx(next(), 64), dy(next(), 64);
    if (s.isoline_axis[v] == 0) dx = 0;
    if (s.isoline_axis[v] == 1) dy = 0;
    const Point2q old = x[v];
    for (int halvings = 0; halvings <= 6; ++halvings, dx /= 2, dy /= 2) {
      x[v] = {old.x + dx, old.y + dy};
      if (star_positive(v)) break;
      x[v] = old;
    }
  }
  igm::IgmMesh out = igm;
  for (int c = 0; c < nh; ++c) out.corner_uv[c / 3][c % 3] = corner(c);
  return out;
}

}  // namespace igm_test
