#include "field_internal.h"

#include <algorithm>

#include "igm/core/error.h"
#include "igm/core/det_math.h"
#include "../quality/vec3.h"

namespace igm::field_internal {

using quality_internal::norm;
using quality_internal::sub;

double mean_edge_length(const TriMesh& mesh, const std::vector<Vec3d>& p) {
  double total = 0;
  long long edges = 0;
  for (int h = 0; h < mesh.num_halfedges(); ++h)
    if (mesh.twin(h) < h) {  // each edge once (a boundary half-edge has twin -1 < h)
      total += norm(sub(p[mesh.target(h)], p[mesh.origin(h)]));
      ++edges;
    }
  return edges > 0 ? total / static_cast<double>(edges) : 0.0;
}

System build_system(const TriMesh& mesh, const std::vector<Vec3d>& p, const FaceFrames& fr) {
  const int nf = mesh.num_faces(), nh = mesh.num_halfedges();
  System s;
  s.mean_edge = mean_edge_length(mesh, p);
  for (int f = 0; f < nf; ++f) s.total_area += fr.area[f];
  const double mean_area = s.total_area / nf;
  const double min_area = mean_area > 0 ? 1e-6 * mean_area : 1.0;
  const double min_dist = s.mean_edge > 0 ? 1e-3 * s.mean_edge : 1.0;
  s.mass.resize(nf);
  for (int f = 0; f < nf; ++f) s.mass[f] = std::max(fr.area[f], min_area);
  std::vector<Vec3d> centroid(nf);
  for (int f = 0; f < nf; ++f) {
    const auto v = mesh.face_vertices(f);
    centroid[f] = {(p[v[0]].x + p[v[1]].x + p[v[2]].x) / 3, (p[v[0]].y + p[v[1]].y + p[v[2]].y) / 3,
                   (p[v[0]].z + p[v[1]].z + p[v[2]].z) / 3};
  }
  s.weight.assign(nh, 0.0);
  std::vector<Eigen::Triplet<Complex>> trip;
  trip.reserve(static_cast<std::size_t>(nh) + nf);
  std::vector<double> diag(nf, 0.0);
  for (int h = 0; h < nh; ++h) {
    const int t = mesh.twin(h);
    if (t < h) continue;  // boundary, or the edge was done from its twin
    const int f = TriMesh::face(h), g = TriMesh::face(t);
    const double len = norm(sub(p[mesh.target(h)], p[mesh.origin(h)]));
    const double w = std::max(len, min_dist) / std::max(norm(sub(centroid[f], centroid[g])), min_dist);
    s.weight[h] = s.weight[t] = w;
    const SinCos sc = det_sincos(4 * fr.transport[h]);
    const Complex r(sc.cos, sc.sin);
    diag[f] += w;
    diag[g] += w;
    trip.emplace_back(g, f, -w * r);
    trip.emplace_back(f, g, -w * std::conj(r));
  }
  for (int f = 0; f < nf; ++f) trip.emplace_back(f, f, Complex(diag[f], 0));
  s.A.resize(nf, nf);
  s.A.setFromTriplets(trip.begin(), trip.end());
  return s;
}

SpMat restricted(const System& s, const std::vector<int>& free_faces, const std::vector<int>& slot, double shift) {
  std::vector<Eigen::Triplet<Complex>> trip;
  const int n = static_cast<int>(free_faces.size());
  for (int i = 0; i < n; ++i) {
    const int f = free_faces[i];
    for (SpMat::InnerIterator it(s.A, f); it; ++it) {
      const int j = slot[it.row()];
      if (j < 0) continue;
      Complex v = it.value();
      if (j == i) {
        const double d = v.real() * (1 + kRegularization) + shift * s.mass[f];
        v = d > 0 ? d : s.mass[f];
      }
      trip.emplace_back(j, i, v);
    }
  }
  SpMat r(n, n);
  r.setFromTriplets(trip.begin(), trip.end());
  return r;
}

template <class Scalar>
void Factor<Scalar>::fail() {
  throw Error(ErrorKind::Internal, "cross field: the sparse factorization failed (matrix not positive definite)");
}

template class Factor<double>;
template class Factor<Complex>;

}  // namespace igm::field_internal
