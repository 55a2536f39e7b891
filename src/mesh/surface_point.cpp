#include "igm/mesh/surface_point.h"

#include <algorithm>
#include <string>

#include "igm/core/error.h"

namespace igm {

SurfacePoint SurfacePoint::vertex(int id) {
  SurfacePoint p;
  p.v[0] = id;
  p.w[0] = 1;
  return p;
}

int SurfacePoint::size() const { return v[2] >= 0 ? 3 : (v[1] >= 0 ? 2 : (v[0] >= 0 ? 1 : 0)); }

namespace {
// Adds weight*p into the accumulator (ids kept sorted ascending in the used prefix).
void accumulate(SurfacePoint& acc, const SurfacePoint& p, const Rational& weight) {
  for (int i = 0; i < 3 && p.v[i] >= 0; ++i) {
    if (sgn(p.w[i]) == 0) continue;
    Rational add = p.w[i] * weight;
    int slot = -1;
    for (int j = 0; j < 3; ++j)
      if (acc.v[j] == p.v[i]) slot = j;
    if (slot < 0) {
      int n = acc.size();
      if (n == 3)
        throw Error(ErrorKind::Internal, "surface point combination spans more than three input vertices",
                    {p.v[i]});
      acc.v[n] = p.v[i];
      acc.w[n] = add;
      for (int j = n; j > 0 && acc.v[j] < acc.v[j - 1]; --j) {
        std::swap(acc.v[j], acc.v[j - 1]);
        std::swap(acc.w[j], acc.w[j - 1]);
      }
    } else {
      acc.w[slot] += add;
    }
  }
}
}  // namespace

SurfacePoint combine(const SurfacePoint& a, const Rational& ta, const SurfacePoint& b, const Rational& tb) {
  SurfacePoint r;
  accumulate(r, a, ta);
  accumulate(r, b, tb);
  return r;
}

SurfacePoint lerp(const SurfacePoint& a, const SurfacePoint& b, const Rational& t) {
  Rational s = 1 - t;
  return combine(a, s, b, t);
}

SurfacePoint average(const std::vector<SurfacePoint>& points) {
  if (points.empty()) throw Error(ErrorKind::Internal, "average of no surface points");
  SurfacePoint r;
  Rational w = make_rational(1, static_cast<long>(points.size()));
  for (const auto& p : points) accumulate(r, p, w);
  return r;
}

SurfacePoint barycentric_point(const SurfacePoint& a, const SurfacePoint& b, const SurfacePoint& c,
                               const std::array<Rational, 3>& w) {
  const Rational wab = w[0] + w[1];
  if (sgn(wab) == 0) return c;
  const SurfacePoint ab = combine(a, Rational(w[0] / wab), b, Rational(w[1] / wab));
  return combine(ab, wab, c, w[2]);
}

Vec3d evaluate(const SurfacePoint& p, const std::vector<Vec3d>& pos) {
  Vec3d r;
  for (int i = 0; i < 3 && p.v[i] >= 0; ++i) {
    double t = to_double(p.w[i]);
    r.x += t * pos[p.v[i]].x;
    r.y += t * pos[p.v[i]].y;
    r.z += t * pos[p.v[i]].z;
  }
  return r;
}

int RefinedSurface::split_edge(int h, const Rational& t) {
  SurfacePoint p = lerp(point(mesh.origin(h)), point(mesh.target(h)), t);
  int v = mesh.split_edge(h);
  if (v != num_input_vertices + static_cast<int>(constructed.size()))
    throw Error(ErrorKind::Internal, "refined surface out of step with its mesh", {v});
  constructed.push_back(std::move(p));
  return v;
}

int RefinedSurface::split_face(int f) {
  auto c = mesh.face_vertices(f);
  SurfacePoint p = average({point(c[0]), point(c[1]), point(c[2])});
  int v = mesh.split_face(f);
  if (v != num_input_vertices + static_cast<int>(constructed.size()))
    throw Error(ErrorKind::Internal, "refined surface out of step with its mesh", {v});
  constructed.push_back(std::move(p));
  return v;
}

}  // namespace igm
