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
      if (j == i) v = regularized_diagonal(s, f, v.real(), shift);
      trip.emplace_back(j, i, v);
    }
  }
  SpMat r(n, n);
  r.setFromTriplets(trip.begin(), trip.end());
  return r;
}

void LargeFactor::factorize(const System& sys, const std::vector<int>& slot, double shift, double& seconds) {
  const auto t0 = Clock::now();
  const SpMat& a = sys.A;
  const int n = static_cast<int>(a.rows());
  // The pattern: row 2f (real part of face f) and 2f + 1 (imaginary part) hold both parts of every
  // neighbour g of f in A (g != f; rows of a column are sorted). A(f, g) = conj(A(g, f)) is read
  // down column f.
  std::vector<int> xadj(2 * static_cast<std::size_t>(n) + 1, 0), adj;
  adj.reserve(4 * static_cast<std::size_t>(a.nonZeros()));
  for (int f = 0; f < n; ++f)
    for (int part = 0; part < 2; ++part) {
      for (SpMat::InnerIterator it(a, f); it; ++it) {
        const int g = static_cast<int>(it.row());
        if (g == f) continue;
        adj.push_back(2 * g);
        adj.push_back(2 * g + 1);
      }
      xadj[2 * f + part + 1] = static_cast<int>(adj.size());
    }
  if (!analyzed_ || xadj != xadj_ || adj != adj_) {
    xadj_.swap(xadj);
    adj_.swap(adj);
    group_.resize(2 * static_cast<std::size_t>(n));
    for (int f = 0; f < n; ++f) group_[2 * f] = group_[2 * f + 1] = f;
    chol_.analyze(xadj_, adj_, group_, SparseCholesky::Ordering::Metis);
    analyzed_ = true;
    ++analyses_;
  }
  // The values, aligned with adj_: for h = A(f, g) = a + ib, row 2f gets (a, -b), row 2f + 1 gets
  // (b, a); 0 where f or g is not free. The diagonal: regularized_diagonal; 1 if not free.
  std::vector<double> val(adj_.size()), diag(2 * static_cast<std::size_t>(n));
  std::size_t k = 0;
  for (int f = 0; f < n; ++f) {
    const double d = slot[f] >= 0 ? regularized_diagonal(sys, f, a.coeff(f, f).real(), shift) : 1.0;
    diag[2 * f] = diag[2 * f + 1] = d;
    for (int part = 0; part < 2; ++part)
      for (SpMat::InnerIterator it(a, f); it; ++it) {
        const int g = static_cast<int>(it.row());
        if (g == f) continue;
        const bool both = slot[f] >= 0 && slot[g] >= 0;
        const Complex h = both ? std::conj(it.value()) : Complex(0, 0);
        val[k++] = part == 0 ? h.real() : h.imag();
        val[k++] = part == 0 ? -h.imag() : h.real();
      }
  }
  const bool ok = chol_.factorize_numeric(val, diag);
  seconds += since(t0);
  if (!ok) throw Error(ErrorKind::Internal, "cross field: the sparse factorization failed (matrix not positive definite)");
}

Vec LargeFactor::solve(const Vec& b) const {
  const Eigen::Index n = b.size();
  Eigen::MatrixXd x(2 * n, 1);
  for (Eigen::Index i = 0; i < n; ++i) {
    x(2 * i, 0) = b[i].real();
    x(2 * i + 1, 0) = b[i].imag();
  }
  chol_.solve(x);
  Vec r(n);
  for (Eigen::Index i = 0; i < n; ++i) r[i] = Complex(x(2 * i, 0), x(2 * i + 1, 0));
  return r;
}

template <class Scalar>
void Factor<Scalar>::fail() {
  throw Error(ErrorKind::Internal, "cross field: the sparse factorization failed (matrix not positive definite)");
}

template class Factor<double>;
template class Factor<Complex>;

}  // namespace igm::field_internal
