#include "symmetric_dirichlet.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace igm::smooth_detail {

namespace {

// A = Rot(phi) diag(s1, s2) Rot(theta) for A = [[a, b], [c, d]], Rot(t) = [[cos t, -sin t],
// [sin t, cos t]]: s1 >= |s2|, s2 of the sign of det A. Closed form (the sums and differences of
// the entries, Blinn 1996): with e = (a+d)/2, f = (a-d)/2, g = (c+b)/2, h = (c-b)/2, a1 the angle
// of (f, g) and a2 that of (e, h): s1 = |(e, h)| + |(f, g)|, phi = (a2 + a1) / 2, theta = (a2 -
// a1) / 2; s2 = det / s1 avoids the cancellation in |(e, h)| - |(f, g)| for thin A.
// Computed without a trigonometric function, by +, -, *, / and sqrt alone (IEEE, correctly
// rounded): libm's atan2, sin and cos are picked at run time by the CPU's features (FMA or not) and
// their last bits differ between those versions, which changed the smoothed maps from machine to
// machine. The rotations are unit vectors: (cos a1, sin a1) = (f, g) / |(f, g)|, Rot(a1 + a2) their
// product, Rot(phi) the half turn of that (bisector formula), Rot(theta) = Rot(a2) Rot(-phi) (so
// that phi + theta = a2 and phi - theta = a1 up to whole turns, which leaves the product as it is).
struct Svd2 {
  double s1 = 0, s2 = 0;
  double cp = 1, sp = 0, ct = 1, st = 0;  // cos and sin of phi and theta
};

// |(x, y)| without overflow or underflow in the squares.
double norm2(double x, double y) {
  const double m = std::max(std::abs(x), std::abs(y));
  if (m == 0 || !std::isfinite(m)) return m;
  const double a = x / m, b = y / m;
  return m * std::sqrt(a * a + b * b);
}

// The unit vector of (x, y); (1, 0) for the zero vector (atan2(0, 0) = 0).
void unit(double x, double y, double& c, double& s) {
  const double n = norm2(x, y);
  if (n > 0) {
    c = x / n;
    s = y / n;
  } else {
    c = 1;
    s = 0;
  }
}

// (cos x/2, sin x/2) with cos x/2 >= 0 from (cos x, sin x): proportional to (1 + cos x, sin x), or
// to (sin x, 1 - cos x) turned to cos x/2 >= 0 where cos x < 0 (no cancellation either way).
void half_turn(double c, double s, double& ch, double& sh) {
  if (c >= 0) {
    unit(1 + c, s, ch, sh);
  } else if (s != 0) {
    unit(s, 1 - c, ch, sh);
    if (ch < 0) ch = -ch, sh = -sh;
  } else {
    ch = 0;
    sh = 1;
  }
}

Svd2 svd2(double a, double b, double c, double d, double det) {
  const double e = (a + d) / 2, f = (a - d) / 2, g = (c + b) / 2, h = (c - b) / 2;
  Svd2 r;
  r.s1 = norm2(e, h) + norm2(f, g);
  r.s2 = r.s1 > 0 ? det / r.s1 : 0;
  double c1, s1, c2, s2;
  unit(f, g, c1, s1);  // a1
  unit(e, h, c2, s2);  // a2
  half_turn(c1 * c2 - s1 * s2, s1 * c2 + c1 * s2, r.cp, r.sp);  // phi = (a1 + a2) / 2
  r.ct = c2 * r.cp + s2 * r.sp;                                 // theta = a2 - phi
  r.st = s2 * r.cp - c2 * r.sp;
  return r;
}

// inv = Rot(-theta) diag(1/s1, 1/s2) Rot(-phi): the inverse of Rot(phi) diag(s1, s2) Rot(theta).
void svd_inverse(const Svd2& s, double inv[2][2]) {
  const double ct = s.ct, st = s.st, cp = s.cp, sp = s.sp;
  // Rot(-theta) = [[ct, st], [-st, ct]]; Rot(-phi) = [[cp, sp], [-sp, cp]]
  const double r00 = ct / s.s1, r01 = st / s.s2, r10 = -st / s.s1, r11 = ct / s.s2;
  inv[0][0] = r00 * cp - r01 * sp;
  inv[0][1] = r00 * sp + r01 * cp;
  inv[1][0] = r10 * cp - r11 * sp;
  inv[1][1] = r10 * sp + r11 * cp;
}

struct Jacobian {
  double f[2][2];
  double det;  // det F
};

// F = J M^-1 with J = [uv1 - uv0, uv2 - uv0]; det <= 0 (or NaN) when J's computed determinant is.
Jacobian jacobian(const SdReference& r, const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  const double j00 = b.x - a.x, j01 = c.x - a.x, j10 = b.y - a.y, j11 = c.y - a.y;
  Jacobian J;
  J.det = (j00 * j11 - j01 * j10) * r.det_minv;
  J.f[0][0] = j00 * r.minv[0][0] + j01 * r.minv[1][0];
  J.f[0][1] = j00 * r.minv[0][1] + j01 * r.minv[1][1];
  J.f[1][0] = j10 * r.minv[0][0] + j11 * r.minv[1][0];
  J.f[1][1] = j10 * r.minv[0][1] + j11 * r.minv[1][1];
  return J;
}

}  // namespace

std::vector<SdReference> sd_references(const std::vector<Vec3d>& positions,
                                       const std::vector<std::array<int, 3>>& triangles,
                                       double uv_area, double min_size, double min_aspect,
                                       SdReferenceStats& stats) {
  stats = {};
  double maxabs = 0;
  for (const Vec3d& p : positions)
    maxabs = std::max({maxabs, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  const double scale = maxabs > 0 ? std::ldexp(1.0, -(std::ilogb(maxabs) + 1)) : 1.0;  // exact
  const std::size_t nf = triangles.size();
  struct Laid {
    double m[2][2];
    double area;
  };
  std::vector<Laid> laid(nf);
  double area_sum = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const Vec3d& p0 = positions[triangles[f][0]];
    const Vec3d& p1 = positions[triangles[f][1]];
    const Vec3d& p2 = positions[triangles[f][2]];
    const double e1[3] = {(p1.x - p0.x) * scale, (p1.y - p0.y) * scale, (p1.z - p0.z) * scale};
    const double e2[3] = {(p2.x - p0.x) * scale, (p2.y - p0.y) * scale, (p2.z - p0.z) * scale};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    const double cross = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double dot = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
    const double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    const double l2 = std::sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    Laid& L = laid[f];
    if (l1 >= l2 && l1 > 0) {  // e1 -> (l1, 0), e2 -> (dot / l1, cross / l1)
      L.m[0][0] = l1, L.m[0][1] = dot / l1, L.m[1][0] = 0, L.m[1][1] = cross / l1;
    } else if (l2 > 0) {  // e2 -> (l2, 0), e1 -> (dot / l2, -cross / l2)
      L.m[0][0] = dot / l2, L.m[0][1] = l2, L.m[1][0] = -cross / l2, L.m[1][1] = 0;
    } else {
      L.m[0][0] = L.m[0][1] = L.m[1][0] = L.m[1][1] = 0;
    }
    L.area = cross / 2;
    area_sum += L.area;
  }
  double l = std::sqrt(area_sum / static_cast<double>(nf));
  if (!(l > 0) || !std::isfinite(l)) l = 1;
  const double floor_size = min_size * l;
  std::vector<SdReference> refs(nf);
  std::vector<Svd2> svds(nf);
  double total = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    Laid& L = laid[f];
    Svd2 s = svd2(L.m[0][0], L.m[0][1], L.m[1][0], L.m[1][1], 2 * L.area);
    if (!(s.s1 >= floor_size)) {
      ++stats.enlarged;
      if (s.s1 > 0) {
        const double k = floor_size / s.s1;
        s.s1 *= k;
        s.s2 *= k;
      } else {  // all three points coincide: an equilateral triangle of side floor_size
        const double h = floor_size * std::sqrt(3.0) / 2;
        s = svd2(floor_size, floor_size / 2, 0, h, floor_size * h);
      }
    }
    if (!(s.s2 >= min_aspect * s.s1)) {
      ++stats.fattened;
      s.s2 = min_aspect * s.s1;
    }
    svds[f] = s;
    total += s.s1 * s.s2 / 2;
  }
  // Scale every reference by sqrt(uv_area / total): M -> k M, M^-1 -> M^-1 / k.
  const double k = std::sqrt(uv_area / total);
  for (std::size_t f = 0; f < nf; ++f) {
    Svd2 s = svds[f];
    s.s1 *= k;
    s.s2 *= k;
    svd_inverse(s, refs[f].minv);
    refs[f].det_minv = 1 / (s.s1 * s.s2);
    refs[f].weight = svds[f].s1 * svds[f].s2 / 2 / total;
  }
  return refs;
}

double sd_energy(const SdReference& r, const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  const Jacobian J = jacobian(r, a, b, c);
  if (!(J.det > 0)) return std::numeric_limits<double>::infinity();
  const double n2 =
      J.f[0][0] * J.f[0][0] + J.f[0][1] * J.f[0][1] + J.f[1][0] * J.f[1][0] + J.f[1][1] * J.f[1][1];
  return r.weight * n2 * (1 + 1 / (J.det * J.det));
}

double sd_derivatives(const SdReference& r, const std::array<Vec2d, 3>& uv, double grad[6],
                      double hess[36]) {
  const Jacobian J = jacobian(r, uv[0], uv[1], uv[2]);
  const Svd2 s = svd2(J.f[0][0], J.f[0][1], J.f[1][0], J.f[1][1], J.det);
  const double s1 = s.s1, s2 = s.s2;
  const double cp = s.cp, sp = s.sp, ct = s.ct, st = s.st;
  const double u1[2] = {cp, sp}, u2[2] = {-sp, cp}, v1[2] = {ct, -st}, v2[2] = {st, ct};
  const double w = r.weight;
  const double energy = w * (s1 * s1 + s2 * s2 + 1 / (s1 * s1) + 1 / (s2 * s2));
  // dF / d(corner i, coordinate j) = e_j B_i^T with B_0 = -(row 0 + row 1 of M^-1), B_i = row i-1.
  const double B[3][2] = {{-(r.minv[0][0] + r.minv[1][0]), -(r.minv[0][1] + r.minv[1][1])},
                          {r.minv[0][0], r.minv[0][1]},
                          {r.minv[1][0], r.minv[1][1]}};
  // A matrix D in F-space as a vector over the six corner coordinates: (D B_i^T)_j.
  auto pull = [&](const double D[2][2], double out[6]) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 2; ++j) out[2 * i + j] = D[j][0] * B[i][0] + D[j][1] * B[i][1];
  };
  const double p1 = 2 * s1 - 2 / (s1 * s1 * s1), p2 = 2 * s2 - 2 / (s2 * s2 * s2);
  double P[2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) P[a][b] = p1 * u1[a] * v1[b] + p2 * u2[a] * v2[b];
  pull(P, grad);
  for (int i = 0; i < 6; ++i) grad[i] *= w;
  const double c3 = 1 / (s1 * s1 * s1 * s2 * s2 * s2);
  const double lambda[4] = {2 + 6 / (s1 * s1 * s1 * s1), 2 + 6 / (s2 * s2 * s2 * s2),
                            2 + 2 * (s1 * s1 + s1 * s2 + s2 * s2) * c3,
                            std::abs(2 - 2 * (s1 * s1 - s1 * s2 + s2 * s2) * c3)};
  const double h = 1 / std::sqrt(2.0);
  double D[4][2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      D[0][a][b] = u1[a] * v1[b];
      D[1][a][b] = u2[a] * v2[b];
      D[2][a][b] = h * (u1[a] * v2[b] + u2[a] * v1[b]);
      D[3][a][b] = h * (u1[a] * v2[b] - u2[a] * v1[b]);
    }
  for (int i = 0; i < 36; ++i) hess[i] = 0;
  for (int m = 0; m < 4; ++m) {
    if (lambda[m] == 0) continue;
    double q[6];
    pull(D[m], q);
    const double lw = lambda[m] * w;
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) hess[6 * a + b] += lw * q[a] * q[b];
  }
  return energy;
}

double first_degeneracy(const std::array<Vec2d, 3>& uv, const std::array<Vec2d, 3>& duv) {
  const double e1x = uv[1].x - uv[0].x, e1y = uv[1].y - uv[0].y, e2x = uv[2].x - uv[0].x,
               e2y = uv[2].y - uv[0].y;
  const double f1x = duv[1].x - duv[0].x, f1y = duv[1].y - duv[0].y, f2x = duv[2].x - duv[0].x,
               f2y = duv[2].y - duv[0].y;
  // det(t) = a t^2 + b t + c
  const double a = f1x * f2y - f1y * f2x;
  const double b = e1x * f2y - e1y * f2x + f1x * e2y - f1y * e2x;
  const double c = e1x * e2y - e1y * e2x;
  const double inf = std::numeric_limits<double>::infinity();
  if (a == 0) return b < 0 ? -c / b : inf;
  const double disc = b * b - 4 * a * c;
  if (disc < 0) return inf;
  const double q = -(b + std::copysign(std::sqrt(disc), b)) / 2;
  double t = inf;
  for (const double root : {q / a, q != 0 ? c / q : inf})
    if (root > 0 && root < t) t = root;
  return t;
}

}  // namespace igm::smooth_detail
