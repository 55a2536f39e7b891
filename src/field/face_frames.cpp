#include "igm/field/face_frames.h"

#include <cmath>
#include <numbers>

#include "igm/core/det_math.h"
#include "../quality/vec3.h"

namespace igm {

namespace {

using quality_internal::add;
using quality_internal::cross;
using quality_internal::dot;
using quality_internal::mul;
using quality_internal::norm;
using quality_internal::sub;

constexpr double kPi = std::numbers::pi;

// The angle between two vectors in [0, pi]; 0 if either is zero.
double angle_between(const Vec3d& a, const Vec3d& b) { return det_atan2(norm(cross(a, b)), dot(a, b)); }

// A fixed unit vector orthogonal to the unit vector x: x crossed with the axis of its smallest
// component.
Vec3d orthogonal_to(const Vec3d& x) {
  const double ax = std::fabs(x.x), ay = std::fabs(x.y), az = std::fabs(x.z);
  const Vec3d e = ax <= ay && ax <= az ? Vec3d{1, 0, 0} : ay <= az ? Vec3d{0, 1, 0} : Vec3d{0, 0, 1};
  const Vec3d c = cross(x, e);
  return mul(c, 1.0 / norm(c));
}

// v / |v| when that is a finite non-zero vector (scaled first, so that neither tiny nor huge
// coordinates underflow or overflow); false otherwise.
bool normalize(Vec3d& v) {
  const double s = std::fmax(std::fabs(v.x), std::fmax(std::fabs(v.y), std::fabs(v.z)));
  if (!(s > 0) || !std::isfinite(s)) return false;
  const Vec3d u{v.x / s, v.y / s, v.z / s};
  v = mul(u, 1.0 / norm(u));
  return true;
}

}  // namespace

FaceFrames face_frames(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                       const std::vector<char>& constrained) {
  const int nf = mesh.num_faces(), nh = mesh.num_halfedges();
  FaceFrames fr;
  fr.reference.resize(nf);
  fr.edge_angle.assign(nh, 0.0);
  fr.transport.assign(nh, 0.0);
  fr.transport_turns.assign(nh, 0);
  fr.area.resize(nf);
  fr.axis_x.resize(nf);
  fr.axis_y.resize(nf);
  fr.normal.resize(nf);
  auto vec = [&](int h) { return sub(positions[mesh.target(h)], positions[mesh.origin(h)]); };
  std::vector<Vec3d> area_vector(nf);
  for (int f = 0; f < nf; ++f) {
    const int h0 = 3 * f;
    area_vector[f] = mul(cross(vec(h0), vec(h0 + 1)), 0.5);
    fr.area[f] = norm(area_vector[f]);
    double len[3];
    for (int i = 0; i < 3; ++i) len[i] = norm(vec(h0 + i));
    int r = -1;
    auto is_constrained = [&](int h) {
      return mesh.twin(h) < 0 || (!constrained.empty() && constrained[h]);
    };
    for (int i = 0; i < 3; ++i)  // longest constrained half-edge of non-zero length
      if (is_constrained(h0 + i) && len[i] > 0 && (r < 0 || len[i] > len[r - h0])) r = h0 + i;
    if (r < 0 && len[0] > 0) r = h0;
    if (r < 0) {
      r = h0;
      for (int i = 1; i < 3; ++i)
        if (len[i] > len[r - h0]) r = h0 + i;
    }
    fr.reference[f] = r;
    const Vec3d er = vec(r), en = vec(TriMesh::next(r)), ep = vec(TriMesh::prev(r));
    const double a = angle_between(er, mul(ep, -1.0));  // corner at origin(r)
    const double b = angle_between(mul(er, -1.0), en);  // corner at target(r)
    fr.edge_angle[r] = 0.0;
    fr.edge_angle[TriMesh::next(r)] = kPi - b;
    fr.edge_angle[TriMesh::prev(r)] = kPi + a;
  }
  for (int f = 0; f < nf; ++f) {
    const int r = fr.reference[f];
    Vec3d x = vec(r);
    bool degenerate = false;
    if (!normalize(x)) {
      degenerate = true;
      x = {1, 0, 0};
    }
    Vec3d n = area_vector[f];
    if (!(fr.area[f] > 0)) {  // fallback: the neighbours' area vectors
      degenerate = true;
      n = {0, 0, 0};
      for (int i = 0; i < 3; ++i) {
        const int t = mesh.twin(3 * f + i);
        if (t >= 0) n = add(n, area_vector[TriMesh::face(t)]);
      }
    }
    if (normalize(n)) n = sub(n, mul(x, dot(n, x)));
    if (!normalize(n)) {
      degenerate = true;
      n = orthogonal_to(x);
    }
    fr.axis_x[f] = x;
    fr.normal[f] = n;
    fr.axis_y[f] = cross(n, x);
    if (degenerate) ++fr.degenerate_faces;
  }
  for (int h = 0; h < nh; ++h) {
    const int t = mesh.twin(h);
    if (t < 0 || t < h) continue;
    double rho = fr.edge_angle[t] + kPi - fr.edge_angle[h];  // in [-pi, 4 pi]: at most 3 turns
    int w = 0;
    while (rho > kPi) rho -= 2 * kPi, --w;
    while (rho <= -kPi) rho += 2 * kPi, ++w;
    fr.transport[h] = rho;
    fr.transport_turns[h] = w;
    fr.transport[t] = -rho;
    fr.transport_turns[t] = -w - 1;
  }
  return fr;
}

Vec3d frame_direction(const FaceFrames& frames, int f, double phi) {
  const SinCos r = det_sincos(phi);
  return add(mul(frames.axis_x[f], r.cos), mul(frames.axis_y[f], r.sin));
}

}  // namespace igm
