#include "igm/field/curvature.h"

#include <array>
#include <cmath>

#include "igm/core/det_math.h"
#include "../quality/vec3.h"

namespace igm {

using quality_internal::cross;
using quality_internal::dot;
using quality_internal::norm;
using quality_internal::sub;

namespace {

// A symmetric 3 x 3 tensor: xx, yy, zz, xy, xz, yz.
using Tensor = std::array<double, 6>;

void add_edge(Tensor& t, const Vec3d& e, double s) {  // t += s e e^T
  t[0] += s * e.x * e.x;
  t[1] += s * e.y * e.y;
  t[2] += s * e.z * e.z;
  t[3] += s * e.x * e.y;
  t[4] += s * e.x * e.z;
  t[5] += s * e.y * e.z;
}

double form(const Tensor& t, const Vec3d& a, const Vec3d& b) {  // a^T t b
  return a.x * (t[0] * b.x + t[3] * b.y + t[4] * b.z) + a.y * (t[3] * b.x + t[1] * b.y + t[5] * b.z) +
         a.z * (t[4] * b.x + t[5] * b.y + t[2] * b.z);
}

}  // namespace

std::vector<std::complex<double>> curvature_cross_guide(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                                        const FaceFrames& frames) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces(), nh = mesh.num_halfedges();
  // Per edge (once, from its half-edge h < twin) its tensor beta |e| e_hat e_hat^T = beta / |e| e e^T,
  // beta the signed dihedral angle (> 0 where the surface is convex), added to both ends; per
  // vertex the area of its faces.
  std::vector<Tensor> vertex_tensor(nv, Tensor{});
  std::vector<double> vertex_area(nv, 0.0), beta_over_len(nh, 0.0);
  for (int h = 0; h < nh; ++h) {
    const int t = mesh.twin(h);
    if (t < 0 || t < h) continue;
    const Vec3d e = sub(positions[mesh.target(h)], positions[mesh.origin(h)]);
    const double len = norm(e);
    if (!(len > 0)) continue;
    const Vec3d& n1 = frames.normal[TriMesh::face(h)];
    const Vec3d& n2 = frames.normal[TriMesh::face(t)];
    const double beta = det_atan2(dot(cross(n1, n2), e) / len, dot(n1, n2));
    beta_over_len[h] = beta / len;
    add_edge(vertex_tensor[mesh.origin(h)], e, beta_over_len[h]);
    add_edge(vertex_tensor[mesh.target(h)], e, beta_over_len[h]);
  }
  for (int f = 0; f < nf; ++f)
    for (int v : mesh.face_vertices(f)) vertex_area[v] += frames.area[f];
  std::vector<std::complex<double>> guide(nf);
  for (int f = 0; f < nf; ++f) {
    // The edges at f's corners: the three vertex sums count f's own edges twice; once removed.
    Tensor t{};
    double area = 0;
    for (int v : mesh.face_vertices(f)) {
      for (int k = 0; k < 6; ++k) t[k] += vertex_tensor[v][k];
      area += vertex_area[v];
    }
    for (int i = 0; i < 3; ++i) {
      const int h = 3 * f + i, tw = mesh.twin(h);
      if (tw < 0) continue;
      const int key = tw < h ? tw : h;
      const Vec3d e = sub(positions[mesh.target(key)], positions[mesh.origin(key)]);
      add_edge(t, e, -beta_over_len[key]);
    }
    // The tensor restricted to f's plane, its traceless part as a complex number:
    // ((t_xx - t_yy) + 2 i t_xy) / 2 = |t| exp(2 i phi).
    const Vec3d& x = frames.axis_x[f];
    const Vec3d& y = frames.axis_y[f];
    const double a = area > 0 ? 0.5 / area : 0.0;
    const std::complex<double> z(a * (form(t, x, x) - form(t, y, y)), a * 2 * form(t, x, y));
    const double m = det_hypot(z.real(), z.imag());
    guide[f] = m > 0 && std::isfinite(m) ? z * z / m : std::complex<double>(0, 0);
  }
  return guide;
}

}  // namespace igm
