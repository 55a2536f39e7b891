#pragma once
// Internal to smooth.cpp: the symmetric Dirichlet energy of one triangle of a map from a
// reference triangle (the 3D triangle, regularized and scaled) to its UV triangle, with the
// gradient and the Hessian projected to positive semi-definite by the energy's analytic
// eigensystem, and the first step at which a moving UV triangle degenerates.
//
// For the map's Jacobian F (2x2) with singular values s1 >= s2 > 0:
//   psi(F) = s1^2 + s2^2 + s1^-2 + s2^-2 = |F|^2 (1 + det(F)^-2)        (minimum 4, at rotations)
// Eigensystem of d2 psi / dF2 (Smith, de Goes, Kim, "Analytic eigensystems for isotropic
// distortion energies", 2019; F = U diag(s1, s2) V^T):
//   scaling  u1 v1^T, u2 v2^T:           2 + 6 s_i^-4                       (always > 0)
//   flip     (u1 v2^T + u2 v1^T)/sqrt 2:  2 + 2 (s1^2 + s1 s2 + s2^2)/(s1 s2)^3  (always > 0)
//   twist    (u1 v2^T - u2 v1^T)/sqrt 2:  2 - 2 (s1^2 - s1 s2 + s2^2)/(s1 s2)^3  (negative where
//            the triangle is compressed: replaced by its absolute value)
// the last two are (psi_1 -+ psi_2)/(s1 -+ s2) written without the cancelling difference. The
// absolute value rather than 0 for the negative eigenvalue (the "absolute value" filter; Chen et
// al., "Trust-region eigenvalue filtering for projected Newton", 2024, use it far from the
// minimum): with 0 the Hessian is nearly singular along the twists of compressed triangles, the
// Newton steps there are huge and the first degeneracy cuts every step short (measured: half the
// energy decrease per iteration on the pipeline's maps).
// Doubles only: nothing here decides validity (smooth.cpp checks every accepted iterate exactly).
#include <array>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm::smooth_detail {

/// One triangle's reference: the inverse of the 2x2 matrix M whose columns are the reference
/// images of p1 - p0 and p2 - p0, det(M^-1), and the weight (reference area / total reference
/// area: the energies are area-weighted means, 4 at best).
struct SdReference {
  double minv[2][2] = {{1, 0}, {0, 1}};
  double det_minv = 1;
  double weight = 0;
};

struct SdReferenceStats {
  int enlarged = 0;  // references below the size floor (coincident points included), enlarged
  int fattened = 0;  // references thinner than the aspect floor (collinear points included)
};

/// The references of all triangles. The positions are first scaled by a power of two so that the
/// largest |coordinate| is below 1 (exact; no overflow in the differences). Each triangle is laid
/// in its plane isometrically (its longer side from corner 0 along the x-axis) as M; then, with
/// l = sqrt(mean 3D area) (1 if that is 0) and M's singular values s1 >= s2:
///  - size floor: if s1 < min_size l, M is scaled up to s1 = min_size l (an equilateral triangle
///    of side min_size l when all three points coincide);
///  - aspect floor: if s2 < min_aspect s1, s2 becomes min_aspect s1 (M = U diag(s1, s2) V^T).
/// Finally every M is scaled by s = sqrt(uv_area / total reference area), so that the references
/// have the map's total UV area. Degenerate 3D triangles thus keep a finite energy and take part
/// in the line search and the exact checks like every other triangle.
/// Pre: positions finite, uv_area > 0. Cost O(F).
std::vector<SdReference> sd_references(const std::vector<Vec3d>& positions,
                                       const std::vector<std::array<int, 3>>& triangles,
                                       double uv_area, double min_size, double min_aspect,
                                       SdReferenceStats& stats);

/// weight * psi of the map from the reference to the UV triangle (a, b, c); +inf when the UV
/// triangle's determinant computed in doubles is not positive. Cost O(1).
double sd_energy(const SdReference& r, const Vec2d& a, const Vec2d& b, const Vec2d& c);

/// The same energy with its gradient (grad[2i + j]: d/d coordinate j of corner i) and its Hessian
/// projected to positive semi-definite (hess[6 * row + col], symmetric). Pre: the determinant is
/// positive (sd_energy finite). Cost O(1).
double sd_derivatives(const SdReference& r, const std::array<Vec2d, 3>& uv, double grad[6],
                      double hess[36]);

/// The smallest t > 0 at which the triangle uv + t duv has determinant 0 (computed in doubles:
/// the smallest positive root of a quadratic in t), +inf if none. Smith and Schaefer, "Bijective
/// parameterization with free boundaries", 2015.
double first_degeneracy(const std::array<Vec2d, 3>& uv, const std::array<Vec2d, 3>& duv);

}  // namespace igm::smooth_detail
