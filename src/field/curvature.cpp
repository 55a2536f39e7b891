#include "igm/field/curvature.h"

#include <cmath>

#include "../quality/vec3.h"

namespace igm {

using quality_internal::cross;
using quality_internal::dot;
using quality_internal::norm;
using quality_internal::sub;

std::vector<std::complex<double>> curvature_cross_guide(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                                        const FaceFrames& frames) {
  const int nf = mesh.num_faces(), nh = mesh.num_halfedges();
  // Per half-edge h (the edge counted once, from its half-edge h < twin or its boundary
  // half-edge): the dihedral angle beta and the edge vector; beta > 0 where the surface is convex.
  std::vector<double> beta(nh, 0.0);
  for (int h = 0; h < nh; ++h) {
    const int t = mesh.twin(h);
    if (t < 0 || t < h) continue;
    const Vec3d& n1 = frames.normal[TriMesh::face(h)];
    const Vec3d& n2 = frames.normal[TriMesh::face(t)];
    const Vec3d e = sub(positions[mesh.target(h)], positions[mesh.origin(h)]);
    const double len = norm(e);
    if (!(len > 0)) continue;
    beta[h] = std::atan2(dot(cross(n1, n2), e) / len, dot(n1, n2));
  }
  // A face sums the edges and faces around its three corners, each once (stamps).
  std::vector<std::complex<double>> guide(nf);
  std::vector<int> edge_seen(nh, -1), face_seen(nf, -1);
  for (int f = 0; f < nf; ++f) {
    std::complex<double> t = 0;
    double area = 0;
    const Vec3d& x = frames.axis_x[f];
    const Vec3d& y = frames.axis_y[f];
    for (int v : mesh.face_vertices(f)) {
      // The fan of v from its first corner (the boundary one on an open fan): at most nh steps.
      const int first = mesh.vertex_halfedge(v);
      int h = first;
      for (int step = 0; step < nh && h >= 0; ++step) {
        const int g = TriMesh::face(h);
        if (face_seen[g] != f) {
          face_seen[g] = f;
          area += frames.area[g];
        }
        for (int e : {h, TriMesh::prev(h)}) {  // the two edges of g at v
          const int te = mesh.twin(e);
          const int key = te >= 0 && te < e ? te : e;
          if (edge_seen[key] == f) continue;
          edge_seen[key] = f;
          if (beta[key] == 0) continue;  // boundary, flat or zero-length edge
          const Vec3d d = sub(positions[mesh.target(key)], positions[mesh.origin(key)]);
          const double px = dot(d, x), py = dot(d, y);
          const double l2 = px * px + py * py;
          if (!(l2 > 0)) continue;
          // beta |e| exp(2 i phi), exp(2 i phi) = (px + i py)^2 / (px^2 + py^2).
          const double s = beta[key] * norm(d) / l2;
          t += std::complex<double>(s * (px * px - py * py), s * 2 * px * py);
        }
        h = mesh.next_around_origin(h);
        if (h == first) break;
      }
    }
    t /= 2 * (area > 0 ? area : 1.0);
    const double m = std::abs(t);
    guide[f] = m > 0 ? t * t / m : std::complex<double>(0, 0);
  }
  return guide;
}

}  // namespace igm
