#pragma once
// The independent exact check that an output mesh is a refinement of its input (issue 6), shared
// by the pipeline tests (on the IGM) and the topology tests (on the refined surface).
#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "igm/mesh/validate.h"
#include "igm/output/igm_mesh.h"

namespace igm_test {

using namespace igm;

// Independent check (issue 6) that `igm` is an exact refinement of `input`, from the raw input
// triangles only (not the producer's adjacency). Returns "" or the first violation found:
//  - every location is a canonical convex combination: used slots first, ids ascending and in
//    range, weights > 0 summing exactly to 1;
//  - vertex v < n (n input vertices) is the weight-1 point of v at the input position;
//  - every other vertex has a support of 2 vertices forming an input edge or 3 forming an input
//    face (a support of 1 would be a duplicate of an input vertex);
//  - every position is evaluate() of its location (bitwise);
//  - the three corners of every triangle have a joint support of exactly the corners of one input
//    face f, and the triangle is positively oriented in f: the determinant of the corners'
//    barycentric coordinates w.r.t. f's corners (in f's order), i.e. area(triangle) / area(f),
//    is > 0. Two input faces on the same three vertices (a 3-vertex sphere) have opposite
//    orientations, so at most one of them gives a positive determinant;
//  - with check_areas, these exact area fractions sum to exactly 1 in every input face (the
//    triangles tile each face: no face missed, none covered twice).
// The input as its triangles and positions (an open surface's too: nothing here needs it closed).
inline std::string refinement_violation(const std::vector<std::array<int, 3>>& in_tris,
                                        const std::vector<Vec3d>& in_positions, const IgmMesh& igm,
                                        bool check_areas) {
  const int n = static_cast<int>(in_positions.size()), F = static_cast<int>(in_tris.size());
  struct {
    const std::vector<Vec3d>& positions;
  } input{in_positions};
  std::vector<std::pair<int, int>> in_edges;  // sorted (a < b)
  std::vector<std::pair<std::array<int, 3>, int>> faces_of(F);  // (sorted corners, input face), sorted
  for (int f = 0; f < F; ++f) {
    std::array<int, 3> c = in_tris[f];
    for (int i = 0; i < 3; ++i) in_edges.push_back(std::minmax(c[i], c[(i + 1) % 3]));
    std::sort(c.begin(), c.end());
    faces_of[f] = {c, f};
  }
  std::sort(in_edges.begin(), in_edges.end());
  std::sort(faces_of.begin(), faces_of.end());
  auto faces_on = [&](const std::array<int, 3>& c) {  // the input faces with corners c (sorted)
    return std::equal_range(faces_of.begin(), faces_of.end(), std::pair<std::array<int, 3>, int>{c, -1},
                            [](const auto& x, const auto& y) { return x.first < y.first; });
  };
  const std::size_t nv = igm.positions.size();
  if (igm.locations.size() != nv)
    return "locations: " + std::to_string(igm.locations.size()) + " for " + std::to_string(nv) + " vertices";
  if (nv < static_cast<std::size_t>(n)) return "fewer output vertices than input vertices";
  auto same = [](const Vec3d& a, const Vec3d& b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
  Rational sum;
  for (std::size_t v = 0; v < nv; ++v) {
    const SurfacePoint& p = igm.locations[v];
    auto at = [v] { return "vertex " + std::to_string(v) + ": "; };
    int k = 0;
    while (k < 3 && p.v[k] >= 0) ++k;
    sum = 0;
    for (int i = 0; i < 3; ++i) {
      if (i < k && (p.v[i] >= n || sgn(p.w[i]) <= 0 || (i > 0 && p.v[i] <= p.v[i - 1])))
        return at() + "support not ascending in-range ids with weights > 0";
      if (i >= k && (p.v[i] != -1 || sgn(p.w[i]) != 0)) return at() + "used slot after an unused one";
      sum += p.w[i];
    }
    if (sum != 1) return at() + "weights sum to " + to_string(sum);
    if (v < static_cast<std::size_t>(n)) {
      if (k != 1 || p.v[0] != static_cast<int>(v)) return at() + "input vertex is not the weight-1 point of itself";
      if (!same(igm.positions[v], input.positions[v])) return at() + "input vertex moved";
    } else if (k == 1) {
      return at() + "new vertex on input vertex " + std::to_string(p.v[0]);
    } else if (k == 2 && !std::binary_search(in_edges.begin(), in_edges.end(), std::pair{p.v[0], p.v[1]})) {
      return at() + "support " + std::to_string(p.v[0]) + " " + std::to_string(p.v[1]) + " is not an input edge";
    } else if (k == 3) {
      const auto range = faces_on({p.v[0], p.v[1], p.v[2]});
      if (range.first == range.second) return at() + "support is not an input face";
    }
    if (!same(igm.positions[v], evaluate(p, input.positions))) return at() + "position is not evaluate(location)";
  }
  std::vector<Rational> area(check_areas ? F : 0);
  const Rational zero = 0;
  Rational det, minor, product;  // (in-place GMP operations below: no allocation per triangle)
  for (std::size_t t = 0; t < igm.triangles.size(); ++t) {
    const std::array<int, 3>& tri = igm.triangles[t];
    auto at = [t] { return "triangle " + std::to_string(t) + ": "; };
    std::array<int, 9> ids;  // the corners' supports, then sorted and made unique
    int m = 0;
    for (int c : tri) {
      if (c < 0 || static_cast<std::size_t>(c) >= nv) return at() + "corner out of range";
      for (int i = 0; i < 3 && igm.locations[c].v[i] >= 0; ++i) ids[m++] = igm.locations[c].v[i];
    }
    std::sort(ids.begin(), ids.begin() + m);
    m = static_cast<int>(std::unique(ids.begin(), ids.begin() + m) - ids.begin());
    if (m != 3) return at() + "joint support of " + std::to_string(m) + " input vertices, not one face";
    const auto [first, last] = faces_on({ids[0], ids[1], ids[2]});
    if (first == last) return at() + "joint support is not an input face";
    int inside = -1;
    for (auto it = first; it != last; ++it) {
      const int f = it->second;
      const Rational* w[3][3];  // w[i][j]: weight of input corner j of f in the location of corner i
      for (int i = 0; i < 3; ++i) {
        const SurfacePoint& p = igm.locations[tri[i]];
        for (int j = 0; j < 3; ++j) {
          w[i][j] = &zero;
          for (int s = 0; s < 3; ++s)
            if (p.v[s] == in_tris[f][j]) w[i][j] = &p.w[s];
        }
      }
      det = 0;  // area(triangle) / area(f): the determinant of w, by the first row
      for (int j = 0; j < 3; ++j) {
        if (sgn(*w[0][j]) == 0) continue;
        const int a = (j + 1) % 3, b = (j + 2) % 3;
        mpq_mul(minor.get_mpq_t(), w[1][a]->get_mpq_t(), w[2][b]->get_mpq_t());
        mpq_mul(product.get_mpq_t(), w[1][b]->get_mpq_t(), w[2][a]->get_mpq_t());
        mpq_sub(minor.get_mpq_t(), minor.get_mpq_t(), product.get_mpq_t());
        mpq_mul(product.get_mpq_t(), w[0][j]->get_mpq_t(), minor.get_mpq_t());
        mpq_add(det.get_mpq_t(), det.get_mpq_t(), product.get_mpq_t());
      }
      if (sgn(det) > 0) {
        if (inside >= 0) return at() + "positively inside two input faces";
        inside = f;
        if (check_areas) area[f] += det;
      }
    }
    if (inside < 0) return at() + "not positively oriented inside its input face";
  }
  for (std::size_t f = 0; f < area.size(); ++f)
    if (area[f] != 1)
      return "input face " + std::to_string(f) + ": output triangles cover a fraction " + to_string(area[f]) + " of it";
  return {};
}

inline std::string refinement_violation(const ValidMesh& input, const IgmMesh& igm, bool check_areas) {
  std::vector<std::array<int, 3>> tris(input.mesh.num_faces());
  for (int f = 0; f < input.mesh.num_faces(); ++f) tris[f] = input.mesh.face_vertices(f);
  return refinement_violation(tris, input.positions, igm, check_areas);
}

/// The same check on a refined surface (its vertices' exact points, positions and faces).
inline std::string refinement_violation(const ValidMesh& input, const RefinedSurface& rs, bool check_areas) {
  IgmMesh m;
  for (int v = 0; v < rs.mesh.num_vertices(); ++v) {
    m.locations.push_back(rs.point(v));
    m.positions.push_back(v < rs.num_input_vertices ? input.positions[v] : evaluate(rs.point(v), input.positions));
  }
  for (int f = 0; f < rs.mesh.num_faces(); ++f) m.triangles.push_back(rs.mesh.face_vertices(f));
  return refinement_violation(input, m, check_areas);
}

}  // namespace igm_test
