// Tests of the per-triangle symmetric Dirichlet energy of the smoother (src/smooth/
// symmetric_dirichlet.h, internal): values by hand, derivatives against finite differences, the
// projected Hessian's eigenvalues, the first degeneracy, the regularized references.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "../../src/smooth/symmetric_dirichlet.h"

using namespace igm;
using namespace igm::smooth_detail;

namespace {

// The reference of the 3D triangle (0,0,0), (2,0,0), (0.5,1.5,0) scaled to UV area `uv_area`.
SdReference reference(double uv_area) {
  SdReferenceStats stats;
  const auto refs =
      sd_references({{0, 0, 0}, {2, 0, 0}, {0.5, 1.5, 0}}, {{0, 1, 2}}, uv_area, 1e-6, 1e-3, stats);
  CHECK(stats.enlarged == 0);
  CHECK(stats.fattened == 0);
  return refs[0];
}

// The UV triangle F applied to the reference triangle laid in the plane (M = minv^-1).
std::array<Vec2d, 3> mapped(const SdReference& r, const double F[2][2]) {
  const double det = r.minv[0][0] * r.minv[1][1] - r.minv[0][1] * r.minv[1][0];
  const double M[2][2] = {{r.minv[1][1] / det, -r.minv[0][1] / det},
                          {-r.minv[1][0] / det, r.minv[0][0] / det}};
  std::array<Vec2d, 3> uv{};
  for (int j = 0; j < 2; ++j) {
    const double x = M[0][j], y = M[1][j];  // column j of M: the reference's edge j
    uv[j + 1] = {F[0][0] * x + F[0][1] * y + 0.25, F[1][0] * x + F[1][1] * y - 0.5};
  }
  uv[0] = {0.25, -0.5};
  return uv;
}

double coordinate(std::array<Vec2d, 3>& uv, int k, double delta) {
  double& x = k % 2 == 0 ? uv[k / 2].x : uv[k / 2].y;
  x += delta;
  return x;
}

}  // namespace

TEST_CASE("energy by hand: a rotation scores 4, a scaling s scores 2 (s^2 + s^-2)") {
  const SdReference r = reference(1.5);  // the 3D area: the scale is 1
  CHECK(r.weight == 1.0);
  const double c = std::cos(0.7), s = std::sin(0.7);
  const double rot[2][2] = {{c, -s}, {s, c}};
  const auto uv = mapped(r, rot);
  CHECK(sd_energy(r, uv[0], uv[1], uv[2]) == doctest::Approx(4).epsilon(1e-12));
  const double scale[2][2] = {{2, 0}, {0, 2}};
  const auto big = mapped(r, scale);
  CHECK(sd_energy(r, big[0], big[1], big[2]) == doctest::Approx(2 * (4 + 0.25)).epsilon(1e-12));
  // With the references scaled to UV area 6 (4 times the 3D area), the scaling by 2 is optimal.
  const SdReference r4 = reference(6);
  const auto big4 = mapped(r4, rot);
  CHECK(sd_energy(r4, big4[0], big4[1], big4[2]) == doctest::Approx(4).epsilon(1e-12));
  // A flipped UV triangle: infinite.
  CHECK(sd_energy(r, uv[0], uv[2], uv[1]) == std::numeric_limits<double>::infinity());
}

TEST_CASE("gradient and Hessian against central differences where no eigenvalue is filtered") {
  const SdReference r = reference(1.5);
  // s = (1.5, 1.5) rotated and (2, 1.3) sheared: the twist eigenvalue 2 - 2 (s1^2 - s1 s2 +
  // s2^2) / (s1 s2)^3 is positive in both, so the projected Hessian is the Hessian.
  const double Fs[2][2][2] = {{{1.5 * 0.6, -1.5 * 0.8}, {1.5 * 0.8, 1.5 * 0.6}},
                              {{2.0, 0.4}, {0.3, 1.3}}};
  for (const auto& F : Fs) {
    std::array<Vec2d, 3> uv = mapped(r, F);
    double g[6], H[36];
    const double e = sd_derivatives(r, uv, g, H);
    CHECK(e == doctest::Approx(sd_energy(r, uv[0], uv[1], uv[2])).epsilon(1e-12));
    const double d = 1e-5;
    for (int k = 0; k < 6; ++k) {
      std::array<Vec2d, 3> p = uv, m = uv;
      coordinate(p, k, d);
      coordinate(m, k, -d);
      const double fd = (sd_energy(r, p[0], p[1], p[2]) - sd_energy(r, m[0], m[1], m[2])) / (2 * d);
      CHECK(g[k] == doctest::Approx(fd).epsilon(1e-6));
      double gp[6], gm[6], Hs[36];
      sd_derivatives(r, p, gp, Hs);
      sd_derivatives(r, m, gm, Hs);
      for (int l = 0; l < 6; ++l)
        CHECK(H[6 * l + k] == doctest::Approx((gp[l] - gm[l]) / (2 * d)).epsilon(1e-5).scale(1));
    }
  }
}

TEST_CASE("the projected Hessian of a compressed triangle is positive semi-definite") {
  const SdReference r = reference(1.5);
  const double F[2][2] = {{0.5, 0.1}, {-0.05, 0.35}};  // s1, s2 < 1: the twist eigenvalue < 0
  const auto uv = mapped(r, F);
  double g[6], H[36];
  sd_derivatives(r, uv, g, H);
  Eigen::Matrix<double, 6, 6> A;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) A(i, j) = H[6 * i + j];
  CHECK((A - A.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * A.cwiseAbs().maxCoeff());
  const Eigen::VectorXd ev =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(A).eigenvalues();
  CHECK(ev.minCoeff() >= -1e-9 * ev.maxCoeff());
  // Translations of the triangle are its null space: 2 zero eigenvalues, 4 positive ones.
  int positive = 0;
  for (int i = 0; i < 6; ++i) positive += ev[i] > 1e-9 * ev.maxCoeff();
  CHECK(positive == 4);
}

TEST_CASE("first degeneracy: the smallest positive root of the determinant") {
  const std::array<Vec2d, 3> uv{Vec2d{0, 0}, Vec2d{1, 0}, Vec2d{0, 1}};
  // corner 2 moves down at speed 2: det = 1 - 2t
  CHECK(first_degeneracy(uv, {Vec2d{0, 0}, Vec2d{0, 0}, Vec2d{0, -2}}) == 0.5);
  // corners 1 and 2 move towards corner 0: det = (1 - t)^2, a double root at 1
  CHECK(first_degeneracy(uv, {Vec2d{0, 0}, Vec2d{-1, 0}, Vec2d{0, -1}}) == doctest::Approx(1));
  // a translation never degenerates; moving away only grows the triangle
  CHECK(first_degeneracy(uv, {Vec2d{3, 1}, Vec2d{3, 1}, Vec2d{3, 1}}) ==
        std::numeric_limits<double>::infinity());
  CHECK(first_degeneracy(uv, {Vec2d{0, 0}, Vec2d{1, 0}, Vec2d{0, 1}}) ==
        std::numeric_limits<double>::infinity());
  // det = 1 + t - 6 t^2 (corner 1 to (1 + t, 2t), corner 2 to (3t, 1)): roots 1/2 and -1/3
  CHECK(first_degeneracy(uv, {Vec2d{0, 0}, Vec2d{1, 2}, Vec2d{3, 0}}) == doctest::Approx(0.5));
}

TEST_CASE("degenerate 3D triangles get finite regularized references") {
  SdReferenceStats stats;
  // coincident points, a collinear triple, a tiny but well-shaped one, and a normal one
  const std::vector<Vec3d> p{{0, 0, 0},    {0, 0, 0}, {0, 0, 0}, {1, 0, 0},
                             {2, 0, 0},    {3, 0, 0}, {0, 0, 5}, {1e-9, 0, 5},
                             {0, 1e-9, 5}, {0, 1, 1}, {1, 1, 1}, {0, 2, 1}};
  const auto refs =
      sd_references(p, {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}}, 4.0, 1e-6, 1e-3, stats);
  CHECK(stats.enlarged == 2);  // the coincident one and the tiny one
  CHECK(stats.fattened == 1);  // the collinear one
  double total = 0;
  const std::array<Vec2d, 3> uv{Vec2d{0, 0}, Vec2d{1, 0}, Vec2d{0, 1}};
  for (const SdReference& r : refs) {
    CHECK(r.weight > 0);
    CHECK(std::isfinite(r.det_minv));
    CHECK(std::isfinite(sd_energy(r, uv[0], uv[1], uv[2])));
    total += r.weight;
  }
  CHECK(total == doctest::Approx(1));
}
